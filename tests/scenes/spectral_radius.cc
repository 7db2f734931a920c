// The high-frequency dissipation of Time/Scheme = bathe and sdirk, measured:
// with Time/<Scheme>/Spectral radius at infinity = rho_inf, a mode far beyond
// the resolution (omega k -> infinity) is multiplied by rho_inf in a step
// (doc/theory.md section 2.4), and in the energy norm the amplification
// of every mode has equal singular values, so that the energy of the
// free, undamped body falls by exactly rho_inf^2 a step when every mode has
// omega k >> 1. The scene: the small paper scene's beam (clamped at both
// ends) on a coarse mesh, made free of contact (a gap of 1 m, no normal
// damping, which acts out of contact too), of load and of viscosity, from
// an initial transverse displacement; k = 10 s is about
// 10^4 periods of its slowest mode (omega_1 about 2e3 rad/s), so that
// sqrt(E_n / E_{n-1}) must equal rho_inf to 1e-3 (the theory: to
// 5/(omega_1 k) for rho_inf = 0, far less for the others), the energy
// balance must close at every step, and the booked numerical dissipation
// (dissipation_inertia), which for this free linear body is E_{n-1} - E_n,
// must be >= 0 and 1 - rho_inf^2 of the energy. (That the resolved modes are
// damped little, at O((omega k)^4) a step, is what second order means:
// tests/time_convergence checks the rate for rho_inf = 0, 0.5 and 1.)

#include "test_tools.h"

#include <cmath>

using namespace DynamicContact;

struct Run
{
  std::vector<double> energy;      // E_0, ..., E_4
  std::vector<double> dissipation; // D_num / scale of steps 1 to 4
};

Run
energies(const std::string &scheme,
         const double       rho_inf,
         const double       k,
         const std::string &name)
{
  std::vector<std::string> settings = {
    "Output/Directory=output-spectral-radius-" + name,
    "Output/Output times=",
    "Geometry/Repetitions=8, 2",
    "Boundary conditions/Traction function/Function constants=F=0, psi=50, "
    "c=2",
    "Foundation/Initial gap/Function expression=1",
    "Foundation/Normal damping/Capped ramp/Coefficient=0",
    "Friction/Law=none",
    "Initial conditions/Displacement/Function expression=0; "
    "1e-3*sin(pi*x/2)",
    "Time/Time step=" + std::to_string(k),
    "Time/End time=" + std::to_string(4 * k)};
  const auto scheme_entries = test_tools::scheme_settings(scheme, rho_inf);
  settings.insert(settings.end(), scheme_entries.begin(), scheme_entries.end());
  auto simulator =
    test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                       settings);
  Run    r;
  double worst_defect = 0;
  for (const auto &row : simulator->time_series())
    {
      r.energy.push_back(row.terms.energy.total());
      if (row.step > 0)
        {
          worst_defect = std::max(worst_defect, row.relative_energy_defect());
          r.dissipation.push_back(row.terms.inertia /
                                  row.terms.scale(row.previous_energy));
        }
    }
  test_tools::check(worst_defect < 1e-10,
                    "energy balance at every step to 1e-10 of the energy");
  return r;
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  unsigned int                     index = 0;
  for (const std::string scheme : {"bathe", "sdirk"})
    for (const double rho_inf : {0., 0.3, 0.6, 0.9, 1.})
      {
        const std::string name = std::to_string(index++);
        test_tools::out() << "--- Time/Scheme = " << scheme
                          << ", Spectral radius at infinity = "
                          << test_tools::digits(rho_inf, 2) << std::endl;
        const Run                  run = energies(scheme, rho_inf, 10., name);
        const std::vector<double> &e   = run.energy;
        test_tools::check(e.size() == 5 && e[0] > 0, "four steps from E_0 > 0");
        // Every step (for rho_inf = 0 the first two: the energy is at
        // round-off after that).
        double worst = 0;
        for (unsigned int n = 1; n <= (rho_inf > 0 ? 4u : 2u) && n < e.size();
             ++n)
          worst =
            std::max(worst, std::abs(std::sqrt(e[n] / e[n - 1]) - rho_inf));
        test_tools::check(
          worst <= 1e-3, "sqrt(E_n/E_{n-1}) = rho_inf to 1e-3 at omega k >> 1");
        // The booked numerical dissipation (dissipation_inertia) of a free,
        // undamped, linear body is E_{n-1} - E_n >= 0 (doc/theory.md section
        // 6): 1 - rho_inf^2 of the energy.
        double most_negative = 0, worst_share = 0;
        for (unsigned int n = 1; n <= run.dissipation.size(); ++n)
          {
            most_negative = std::min(most_negative, run.dissipation[n - 1]);
            if (n <= (rho_inf > 0 ? 4u : 2u))
              worst_share = std::max(worst_share,
                                     std::abs(run.dissipation[n - 1] -
                                              (1 - rho_inf * rho_inf)));
          }
        test_tools::check(most_negative >= -EnergyBalanceTerms::roundoff,
                          "the numerical dissipation is >= 0 at every step");
        test_tools::check(worst_share <= 2e-3,
                          "the numerical dissipation is 1 - rho_inf^2 of the "
                          "energy, to 2e-3");
      }
}
