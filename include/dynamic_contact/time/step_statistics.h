#ifndef dynamic_contact_step_statistics_h
#define dynamic_contact_step_statistics_h

#include <dynamic_contact/contact/contact_solver.h>

#include <algorithm>

namespace DynamicContact
{
  /**
   * What the solve of one step did and found (StepSolver::Statistics): the
   * work of its Newton solves and convexification passes, its residuals,
   * the uniqueness measures and solution count of Friction/Uniqueness
   * monitor and Friction/Count solutions, and the nodes in contact, stick
   * and slip at its solution.
   */
  struct StepStatistics
  {
    unsigned int newton_iterations          = 0;
    unsigned int convexification_iterations = 0;
    bool         convexification_converged  = true;
    unsigned int factorizations             = 0;
    unsigned int bulk_solves                = 0;
    unsigned int cycles                     = 0;
    unsigned int line_search_steps          = 0;
    /** Krylov iterations (Solver/Linear solver = iterative). */
    unsigned int linear_iterations = 0;
    double       residual          = 0;
    /** max_i |mu_i - mu(|w_tau,i|)| over nodes in contact. */
    double coefficient_residual = 0;
    /**
     * Coupled passes (Friction/Linearization = coupled) that did not
     * converge, after which the step was solved by the frozen loop.
     */
    unsigned int coupled_fallbacks = 0;
    /**
     * The uniqueness measures of the solution (doc/theory.md section
     * 5.2), -1 where they were not evaluated (Friction/Uniqueness
     * monitor). uniqueness_bound: rho(C Lambda), Lambda_i = theta L N_i
     * + mu_max^2 m_i kappa_i / 4 (the paper's smallness condition with
     * the coupling through the normal forces), as the Lanczos iteration
     * estimates it from below; a sufficient condition: below 1 the step
     * has one solution, at 1 or more nothing is proven.
     * uniqueness_certificate: an upper bound of it, computed where the
     * Lanczos value is below 1 and the solver holds C's entries (the
     * condensed solver), -1 elsewhere: below 1, one solution is proven.
     * contraction_factor: rho(C D) at the solution, a bound of the
     * frozen-coefficient loop's contraction factor there (below 1: the
     * loop is attracted to it; 1 or more: it may be repelled).
     */
    double uniqueness_bound       = -1;
    double uniqueness_certificate = -1;
    double contraction_factor     = -1;
    /**
     * Friction/Count solutions (doc/theory.md section 5.3): the distinct
     * solutions that the step's starts reached (0: not counted), the
     * largest distance between two of them relative to the largest
     * velocity on Gamma_3, and the starts that reached none.
     */
    unsigned int solutions       = 0;
    double       solution_spread = 0;
    unsigned int failed_starts   = 0;
    unsigned int n_contact       = 0;
    unsigned int n_stick         = 0;
    unsigned int n_slip          = 0;

    /** Add the work of a Newton solve; its residual is the last. */
    void
    add_newton(const ContactSolveResult &r)
    {
      newton_iterations += r.iterations;
      factorizations += r.factorizations;
      bulk_solves += r.bulk_solves;
      cycles += r.cycles;
      line_search_steps += r.line_search_steps;
      linear_iterations += r.linear_iterations;
      residual = r.residual;
    }

    /**
     * Add the work of an earlier sub-step of the same step (a composite
     * scheme): the counts add up, the loop converged only if both did,
     * the coefficient residual is the larger; the residual and the node
     * counts stay those of this (the last) solve.
     */
    void
    add_work(const StepStatistics &earlier)
    {
      newton_iterations += earlier.newton_iterations;
      convexification_iterations += earlier.convexification_iterations;
      convexification_converged =
        convexification_converged && earlier.convexification_converged;
      factorizations += earlier.factorizations;
      bulk_solves += earlier.bulk_solves;
      cycles += earlier.cycles;
      line_search_steps += earlier.line_search_steps;
      linear_iterations += earlier.linear_iterations;
      coefficient_residual =
        std::max(coefficient_residual, earlier.coefficient_residual);
      coupled_fallbacks += earlier.coupled_fallbacks;
      uniqueness_bound = std::max(uniqueness_bound, earlier.uniqueness_bound);
      solutions        = std::max(solutions, earlier.solutions);
      solution_spread  = std::max(solution_spread, earlier.solution_spread);
      failed_starts += earlier.failed_starts;
      // Proven only where every sub-step is.
      uniqueness_certificate =
        uniqueness_certificate < 0 || earlier.uniqueness_certificate < 0 ?
          -1. :
          std::max(uniqueness_certificate, earlier.uniqueness_certificate);
      contraction_factor =
        std::max(contraction_factor, earlier.contraction_factor);
    }
  };
} // namespace DynamicContact

#endif
