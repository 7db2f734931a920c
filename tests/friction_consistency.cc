// The friction law holds node by node, to solver tolerance (relative to the
// largest contact pressure, the scale the solver's tolerance refers to), in
// the paper's frictional scene, solved by the frozen convexification loop
// and by the coupled linearization (Friction/Linearization)
// (prm/barboteu_danan_2016_small.prm, mu(s) = 0.5 exp(-2000 s) + 0.5), at
// every step, read back from the contact_NNNNN.csv files the run writes:
//   slip nodes:  |tangential_traction| = mu normal_pressure, the traction
//                opposes w_tau, and mu = mu(|w_tau|) to the loop's tolerance;
//   stick nodes: |tangential_traction| <= mu(0) normal_pressure, w_tau = 0
//                (to 1e-10 of the largest slip rate);
//   free nodes:  no traction.

#include <deal.II/base/utilities.h>

#include "test_tools.h"

#include <map>
#include <sstream>

using namespace DynamicContact;

void
check_law(const std::string &linearization)
{
  const std::string directory = "output-friction-" + linearization;
  const std::string prefix    = linearization + ": ";
  test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                     {"Output/Directory=" + directory,
                      "Output/Output every=1",
                      "Friction/Linearization=" + linearization});
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;

  const auto mu = [](const double s) {
    return 0.5 * std::exp(-2000 * s) + 0.5;
  };
  std::map<std::string, unsigned int> count;
  double slip_law = 0, slip_coefficient = 0, stick_excess = 0,
         stick_velocity = 0, free_traction = 0, p_max = 0, slip_max = 0;
  bool   opposes = true, one_time = true, time_increases = true;
  double last_time = 0;
  for (unsigned int step = 1; step <= 128; ++step)
    {
      char name[64];
      std::snprintf(name, sizeof(name), "/contact_%05u.csv", step);
      const auto rows = test_tools::read_csv(directory + name);
      if (rows.empty())
        test_tools::check(false, prefix + "read " + name);
      if (step == 1)
        test_tools::check(rows[0] == test_tools::split("time,x,y,u_nu,w_nu,"
                                                       "normal_pressure,w_tau,"
                                                       "tangential_traction,mu,"
                                                       "u_x,u_y,state",
                                                       ','),
                          prefix + "contact CSV header");
      // The time of the step, in every row.
      const double time = rows.size() > 1 ? std::stod(rows[1][0]) : 0;
      time_increases    = time_increases && time > last_time;
      last_time         = time;
      for (std::size_t r = 1; r < rows.size(); ++r)
        {
          const auto &fields = rows[r];
          one_time           = one_time && std::stod(fields[0]) == time;
          const double p = std::stod(fields[5]), w_tau = std::stod(fields[6]),
                       t = std::stod(fields[7]), m = std::stod(fields[8]);
          const std::string &state = fields[11];
          ++count[state];
          p_max = std::max(p_max, p);
          if (state == "slip")
            {
              slip_law = std::max(slip_law, std::abs(std::abs(t) - m * p));
              slip_coefficient =
                std::max(slip_coefficient, std::abs(m - mu(std::abs(w_tau))));
              opposes  = opposes && (t * w_tau < 0);
              slip_max = std::max(slip_max, std::abs(w_tau));
            }
          else if (state == "stick")
            {
              stick_excess   = std::max(stick_excess, std::abs(t) - mu(0) * p);
              stick_velocity = std::max(stick_velocity, std::abs(w_tau));
            }
          else
            free_traction = std::max(free_traction, std::abs(t));
        }
    }
  test_tools::check(one_time && time_increases,
                    prefix +
                      "the time column: one time per file, increasing with "
                      "the step");
  test_tools::check(count["slip"] > 100 && count["stick"] > 10,
                    prefix + "many slip and stick node-steps");
  test_tools::check(slip_law < 1e-8 * p_max,
                    prefix +
                      "slip: |traction| = mu p to 1e-8 of the largest pressure");
  test_tools::check(opposes,
                    prefix + "slip: the traction opposes the slip velocity");
  test_tools::check(slip_coefficient < 1e-6,
                    prefix + "slip: mu = mu(|w_tau|) to the coefficient "
                             "tolerance 1e-6");
  test_tools::check(stick_excess < 1e-8 * p_max,
                    prefix + "stick: |traction| <= mu(0) p");
  test_tools::check(stick_velocity < 1e-10 * slip_max,
                    prefix +
                      "stick: w_tau = 0 to 1e-10 of the largest slip rate");
  test_tools::check(free_traction == 0, prefix + "free: no traction");
}


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_law("frozen");
  check_law("coupled");
}
