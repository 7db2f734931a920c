// The paper scene without friction (prm/barboteu_danan_2016_small.prm) is close
// to quasi-static (bending periods ~1 ms << k): when the load is mid-span,
// the total normal contact force equals the applied load up to the share
// the clamped ends carry (and a negligible inertia):
//   contact + applied + reaction = inertia,
// the body's force balance, holds to solver tolerance at every step; and
// the ends' share is small when the load is far from them.

#include "test_tools.h"

using namespace DynamicContact;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             simulator =
    test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                       {"Output/Directory=output-quasi-static",
                        "Friction/Law=none"});

  double worst_balance = 0;
  for (const auto &row : simulator->time_series())
    if (row.step > 0)
      {
        const double applied  = row.forces.applied[1];
        const double contact  = row.normal_force;
        const double reaction = row.forces.reaction[1];
        const double inertia  = row.forces.inertia[1];
        worst_balance =
          std::max(worst_balance,
                   std::abs(contact + applied + reaction - inertia) /
                     std::abs(applied));
      }
  test_tools::check(worst_balance < 1e-8,
                    "vertical force balance at every step to 1e-8");

  // Mid-span (t = 0.5 s, the load at x = 1 m).
  const auto &mid = simulator->time_series()[64];
  test_tools::check(std::abs(mid.time - 0.5) < 1e-12, "t = 0.5");
  const double applied  = -mid.forces.applied[1];
  const double contact  = mid.normal_force;
  const double reaction = mid.forces.reaction[1];
  const double inertia  = mid.forces.inertia[1];
  test_tools::check(std::abs(inertia) < 1e-6 * applied,
                    "quasi-static: inertia below 1e-6 of the load");
  test_tools::check(std::abs(contact - applied) <=
                      std::abs(reaction) + std::abs(inertia) + 1e-8 * applied,
                    "|contact - load| is the clamped ends' share");
  test_tools::check(std::abs(reaction) < 0.1 * applied,
                    "the clamped ends carry less than 10 % of a mid-span load");
  test_tools::out() << "contact force / applied load at t = 0.5: "
                    << test_tools::digits(contact / applied, 3) << std::endl;
  test_tools::out() << "clamped ends' share at t = 0.5: "
                    << test_tools::digits(-reaction / applied, 2) << std::endl;
}
