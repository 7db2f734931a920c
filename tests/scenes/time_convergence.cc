// The order in k of the time schemes on the manufactured solution
// (prm/manufactured_2d.prm: contact, damping and slip active on part of
// Gamma_3, viscosity on), at ctest scale: Q2 elements, which hold the exact
// displacement, on a mesh fine enough that the spatial error stays below
// the time error, and k halved twice. The observed rate of
// max_n error_theorem6 must be >= 1.9 for the second-order Bathe scheme
// (Time/Scheme = bathe) at the spectral radius at infinity rho_inf = 0
// (default), 0.5 and 1 (doc/theory.md section 2.4) and for the
// two-stage SDIRK scheme (Time/Scheme = sdirk, section 2.6) at rho_inf = 0
// and 0.5, and about 1 for
// backward Euler (so that the check
// can tell a first-order scheme). benchmarks/convergence runs the longer
// study (time-bathe).

#include "test_tools.h"

#include <cmath>

using namespace DynamicContact;

double
max_error(const std::string &scheme,
          const unsigned int steps,
          const double       rho_inf)
{
  const std::string name =
    (scheme == "backward Euler" ? std::string("euler") : scheme) +
    (rho_inf > 0 ? "-" + test_tools::digits(rho_inf, 2) : std::string());
  std::vector<std::string> options = {
    "Output/Directory=output-time-convergence-" + name + "-" +
      std::to_string(steps),
    "Geometry/Global refinements=4",
    "Finite element/Polynomial degree=2",
    "Time/Time step=" + std::to_string(0.8 / steps)};
  for (const std::string &s : test_tools::scheme_settings(scheme, rho_inf))
    options.push_back(s);
  auto simulator =
    test_tools::run<2>(test_tools::scene("manufactured_2d.prm"), options);
  double      error = 0, numerical = 0;
  const auto &rows = simulator->time_series();
  for (unsigned int n = 1; n < rows.size(); ++n)
    {
      error = std::max(error, rows[n].errors.strain + rows[n].errors.velocity);
      numerical =
        std::min(numerical,
                 rows[n].terms.inertia /
                   rows[n].terms.scale(rows[n - 1].terms.energy.total()));
    }
  // The SDIRK scheme's numerical dissipation is a sum of squares: >= 0 at
  // every step whatever the loads (here a body force, tractions and a
  // Gamma_3 source that change by O(1) over the run), where the Bathe
  // scheme's is not (doc/theory.md section 6).
  if (scheme == "sdirk")
    test_tools::check(numerical >= -EnergyBalanceTerms::roundoff,
                      "numerical dissipation >= 0 at every step, " +
                        std::to_string(steps) + " steps");
  return error;
}

void
study(const std::string &scheme,
      const double       low,
      const double       high,
      const double       rho_inf = 0)
{
  test_tools::out() << "--- Time/Scheme = " << scheme
                    << (rho_inf > 0 ? ", Spectral radius at infinity = " +
                                        test_tools::digits(rho_inf, 2) :
                                      std::string())
                    << std::endl;
  const std::vector<unsigned int> steps = {8, 16, 32};
  std::vector<double>             errors;
  for (const unsigned int n : steps)
    errors.push_back(max_error(scheme, n, rho_inf));
  for (unsigned int i = 1; i < steps.size(); ++i)
    {
      const double rate = std::log2(errors[i - 1] / errors[i]);
      test_tools::check(rate >= low && rate <= high,
                        "rate in k from " + std::to_string(steps[i - 1]) +
                          " to " + std::to_string(steps[i]) + " steps in [" +
                          test_tools::digits(low, 2) + ", " +
                          test_tools::digits(high, 2) + "]");
    }
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  study("bathe", 1.9, 2.6);
  study("bathe", 1.9, 2.6, 0.5);
  study("bathe", 1.9, 2.6, 1);
  study("sdirk", 1.9, 2.6);
  study("sdirk", 1.9, 2.6, 0.5);
  study("backward Euler", 0.8, 1.2);
}
