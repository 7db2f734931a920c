#ifndef dynamic_contact_run_totals_h
#define dynamic_contact_run_totals_h

#include <deal.II/base/conditional_ostream.h>

#include <dynamic_contact/checkpoint.h>
#include <dynamic_contact/parameters.h>

#include <string>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The counts of a run's end summary that come from the rows of
   * time_series.csv (those before a resume included): cut-backs,
   * convexification passes, and the largest coefficient residual
   * max_i |mu_i - mu(|w_tau,i|)| of a step.
   */
  struct RunTotals
  {
    unsigned int cutbacks                 = 0;
    unsigned int convexification          = 0;
    double       max_coefficient_residual = 0;

    /** Add the counts of one step. */
    void
    add(const unsigned int cutbacks,
        const unsigned int convexification_iterations,
        const double       coefficient_residual);

    /** Add the steps of a time_series.csv (its text; row 0 left out). */
    void
    add_rows(const std::string &time_series);

    /**
     * Steps of this run (since its start or resume) whose Newton iteration
     * ended at stagnation (residual above Solver/Newton tolerance, below
     * its square root).
     */
    unsigned int stagnated_steps = 0;

    /**
     * The end summary on @p pcout (steps, iterations, the energy balance,
     * cut-backs, unconverged and stagnated steps, the friction law's
     * residual) with the loop @p state; returns the run's honest ending
     * for run_status: "completed", or "completed with warnings: ..." with
     * what did not hold.
     */
    std::string
    print_summary(const ConditionalOStream &pcout,
                  const RunState           &state,
                  const RunParameters      &parameters,
                  const bool                friction) const;
  };
} // namespace DynamicContact

#endif
