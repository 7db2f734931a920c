// The discrete energy balance of doc/theory.md section 6,
//   E_n - E_{n-1} + D_n = W_n,
// holds at every step to solver tolerance, and every dissipation term is
// >= 0, in a scene where every term is at work: viscosity (C != 0),
// inertia, elasticity, normal compliance from an initial gap, the damped
// response, and slip-weakening friction. For both time schemes: with the
// trapezoidal rule (theta = 1/2) the scheme's numerical dissipation
// (inertia, elastic) and the compliance term vanish (the discrete gradient
// makes it zero by construction) and the other terms are at work. With
// the Bathe scheme dissipation_inertia books the scheme's whole numerical
// dissipation, the energy jump of the extrapolation to the second
// sub-step's start included (dissipation_elastic is 0): it must be >= 0
// too, and at work. With Time/Bathe/Spectral radius at infinity = rho_inf > 0
// the second sub-step is a theta-step (1/2 < theta < 1) whose numerical
// dissipation (theta - 1/2)(...) is booked in dissipation_inertia as well,
// and whose compliance force (2 theta - 1) p(u_n) + 2 (1 - theta) DG
// dissipates (2 theta - 1) times backward Euler's compliance term.
// With the SDIRK scheme (Time/Scheme = sdirk) dissipation_inertia books
// (gamma - 1/4)/(2 gamma^2) |(Y1 - y_{n-1}) - (Y2 - y_hat)|_E^2 and the
// other terms are the stages' (doc/theory.md section 6). Its compliance
// term is not a square: the foundation energy is not quadratic where a
// node enters or leaves contact within a step, and there it can be < 0
// (measured, doc/theory.md section 6); for sdirk that term is checked for
// being at work, not for its sign.

#include "test_tools.h"

using namespace DynamicContact;

namespace
{
  const char *terms[] = {"dissipation_inertia",
                         "dissipation_elastic",
                         "dissipation_viscous",
                         "dissipation_compliance",
                         "dissipation_damping",
                         "friction_dissipation"};
  // The same terms, as fields of the step's EnergyBalanceTerms.
  double EnergyBalanceTerms::*const members[] = {
    &EnergyBalanceTerms::inertia,
    &EnergyBalanceTerms::elastic,
    &EnergyBalanceTerms::viscous,
    &EnergyBalanceTerms::compliance,
    &EnergyBalanceTerms::damping,
    &EnergyBalanceTerms::friction};


  /** The balance's defects and the dissipation terms over a run's steps. */
  struct Balance
  {
    double              worst_defect = 0, most_negative = 0, worst_column = 0;
    std::vector<double> largest          = std::vector<double>(6, 0.);
    std::vector<double> largest_relative = std::vector<double>(6, 0.);
  };


  /** @p sdirk: the compliance term is left out of most_negative. */
  Balance
  measure(const std::vector<StepRecord<2>> &rows, const bool sdirk)
  {
    Balance x;
    for (unsigned int n = 1; n < rows.size(); ++n)
      {
        const auto  &row = rows[n];
        const double scale =
          std::max({std::abs(row.terms.energy.total()),
                    std::abs(rows[n - 1].terms.energy.total()),
                    std::abs(row.terms.load_work),
                    std::abs(row.terms.dissipation())});
        const double defect = row.terms.energy.total() -
                              rows[n - 1].terms.energy.total() +
                              row.terms.dissipation() - row.terms.load_work;
        x.worst_column =
          std::max(x.worst_column, std::abs(defect - row.terms.defect) / scale);
        x.worst_defect = std::max(x.worst_defect, std::abs(defect) / scale);
        for (unsigned int t = 0; t < 6; ++t)
          {
            const double term = row.terms.*members[t];
            if (!(sdirk && members[t] == &EnergyBalanceTerms::compliance))
              x.most_negative = std::min(x.most_negative, term / scale);
            x.largest[t] = std::max(x.largest[t], term);
            x.largest_relative[t] =
              std::max(x.largest_relative[t], std::abs(term) / scale);
          }
      }
    return x;
  }


  void
  check_balance(const std::string &scheme, const double rho_inf = 0)
  {
    const std::string rho = test_tools::digits(rho_inf, 2);
    test_tools::out() << "--- Time/Scheme = " << scheme
                      << (rho_inf > 0 ?
                            ", Spectral radius at infinity = " + rho :
                            std::string())
                      << std::endl;
    std::vector<std::string> settings = {
      "Output/Directory=output-energy-" +
        std::string(scheme == "backward Euler" ? "euler" : scheme) +
        (rho_inf > 0 ? "-" + rho : std::string()),
      "Material/Viscosity lambda=1e7",
      "Material/Viscosity mu=5e6",
      "Foundation/Initial gap/Function expression=0.01*x"};
    for (const std::string &s : test_tools::scheme_settings(scheme, rho_inf))
      settings.push_back(s);
    auto simulator =
      test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                         settings);

    // Which terms the scheme has: all for backward Euler; for the
    // trapezoidal rule not the first two nor the compliance term; for the
    // Bathe scheme all but the elastic one (booked with the inertia).
    const bool trapezoidal = (scheme == "trapezoidal");
    const bool sdirk       = (scheme == "sdirk");
    const bool bathe       = (scheme == "bathe" || sdirk);
    const bool present[]   = {
        !trapezoidal, !trapezoidal && !bathe, true, !trapezoidal, true, true};
    const auto   &rows = simulator->time_series();
    const Balance x    = measure(rows, sdirk);
    test_tools::check(rows.size() > 10, "the run has more than 10 steps");
    test_tools::check(x.worst_column < 1e-9,
                      "the defect column is E_n - E_{n-1} + D_n - W_n");
    test_tools::check(x.worst_defect < 1e-8,
                      "energy balance at every step to 1e-8 of the energy");
    test_tools::check(x.most_negative >= -1e-12,
                      std::string(sdirk ? "every dissipation term but the "
                                          "compliance term" :
                                          "every dissipation term") +
                        " >= 0 at every step (to the round-off of its "
                        "evaluation, 1e-12 of the energy)");
    for (unsigned int t = 0; t < 6; ++t)
      if (present[t])
        test_tools::check(x.largest[t] > 0,
                          std::string(terms[t]) +
                            " is at work (> 0 at some step)");
      else
        test_tools::check(x.largest_relative[t] <= 1e-12,
                          std::string(terms[t]) +
                            " vanishes (<= 1e-12 of the energy at every "
                            "step)");
  }


  /** Time/Scheme and the spectral radius at infinity of each run. */
  const std::vector<std::pair<std::string, double>> schemes = {
    {"backward Euler", 0},
    {"trapezoidal", 0},
    {"bathe", 0},
    {"bathe", 0.5},
    {"bathe", 0.9},
    {"sdirk", 0},
    {"sdirk", 0.5}};
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const auto &[scheme, rho_inf] : schemes)
    check_balance(scheme, rho_inf);
}
