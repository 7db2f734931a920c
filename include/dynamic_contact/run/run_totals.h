#ifndef dynamic_contact_run_totals_h
#define dynamic_contact_run_totals_h

#include <deal.II/base/conditional_ostream.h>

#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/parameters/parameters.h>

#include <string>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The counts of a run's end summary that come from the rows of
   * time_series.csv (those before a resume included): cut-backs,
   * convexification passes, the largest coefficient residual
   * max_i |mu_i - mu(|w_tau,i|)| of a step, the fallbacks of the coupled
   * linearization and the steps not known to have one solution.
   */
  struct RunTotals
  {
    unsigned int cutbacks                 = 0;
    unsigned int convexification          = 0;
    double       max_coefficient_residual = 0;
    /** Coupled passes that fell back to the frozen loop. */
    unsigned int coupled_fallbacks = 0;
    /**
     * Steps in which a Newton iteration came back to active sets or an
     * iterate it had seen (a cycle), which its line search then damped.
     */
    unsigned int cycling_steps = 0;
    /**
     * The uniqueness measures (doc/theory.md section 5.2): the steps whose
     * contraction factor was 1 or more (the frozen loop may be repelled
     * from the solution), the steps where the bound was evaluated and
     * those where its certificate (an upper bound) was below 1 (one
     * solution proven), and the largest of each.
     */
    std::vector<unsigned int> repelling_steps;
    unsigned int              bound_steps          = 0;
    unsigned int              proven_steps         = 0;
    double                    max_uniqueness_bound = -1;
    double                    max_contraction      = -1;
    /**
     * Friction/Count solutions (doc/theory.md section 5.3): the steps
     * counted, those where the starts reached two or more solutions, and
     * the starts that reached none.
     */
    unsigned int              counted_steps = 0;
    std::vector<unsigned int> several_solution_steps;
    unsigned int              failed_starts = 0;

    /** What a step adds: a row of time_series.csv, by column. */
    struct Step
    {
      unsigned int step;
      unsigned int cutbacks;
      unsigned int convexification_iterations;
      double       coefficient_residual;
      unsigned int coupled_fallbacks;
      double       uniqueness_bound;       // -1: not evaluated
      double       uniqueness_certificate; // -1: not evaluated
      double       contraction_factor;     // -1: not evaluated
      unsigned int active_set_cycles;  // Newton cycles answered by damping
      unsigned int solutions     = 0;  // Friction/Count solutions; 0: not
      unsigned int failed_starts = 0;
    };

    /** Add the counts of one step. */
    void
    add(const Step &step);

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

  private:
    /** The summary's line on the uniqueness of the steps' solutions. */
    void
    print_uniqueness(const ConditionalOStream &pcout) const;

    /** The summary's line of the solution count. */
    void
    print_solution_count(const ConditionalOStream &pcout) const;
  };
} // namespace DynamicContact

#endif
