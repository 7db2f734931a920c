#ifndef dynamic_contact_step_solver_h
#define dynamic_contact_step_solver_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/contact/solver_plan.h>
#include <dynamic_contact/laws/contact_law.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * One time step of the scheme (doc/theory.md sections 2, 4 and 5): given K0
   * for the current k, the right-hand side b = (rho/k) M w_{n-1} - B u_{n-1}
   * + f_n and u_{n-1}, find w_n. With a slip-rate dependent friction law,
   * the convexification loop freezes mu_i = mu(|w_tau,i|) of the previous
   * iterate, solves the frozen problem by semismooth Newton (a
   * ContactSolver), and stops by the rule (85) together with
   * max_i |mu_i - mu(|w_tau,i|)| <= tol. Without friction, or with a
   * constant coefficient, there is one pass and no friction work.
   */
  template <int dim>
  class StepSolver
  {
  public:
    struct Statistics
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
      double       coefficient_residual = 0;
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
      double       uniqueness_bound       = -1;
      double       uniqueness_certificate = -1;
      double       contraction_factor     = -1;
      /**
       * Friction/Count solutions (doc/theory.md section 5.3): the distinct
       * solutions that the step's starts reached (0: not counted), the
       * largest distance between two of them relative to the largest
       * velocity on Gamma_3, and the starts that reached none.
       */
      unsigned int solutions            = 0;
      double       solution_spread      = 0;
      unsigned int failed_starts        = 0;
      unsigned int n_contact            = 0;
      unsigned int n_stick              = 0;
      unsigned int n_slip               = 0;

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
      add_work(const Statistics &earlier)
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

    StepSolver(const Discretization<dim>  &discretization,
               const BulkOperator<dim>    &bulk,
               const ContactBoundary<dim> &contact_boundary,
               ContactState<dim>          &contact_state,
               const Foundation           &foundation,
               const FrictionLaw          *friction_law,
               const Parameters::Solver   &solver_parameters,
               const Parameters::Friction &friction_parameters,
               TimerOutput                &timer,
               const ConditionalOStream   &details);
    ~StepSolver();

    /**
     * After a change of the mesh (or of Gamma_3): size the Gamma_3 solution
     * (ContactState::reinit) and plan the solver (plan_solver) for
     * @p steps_per_matrix steps with one bulk matrix within @p memory
     * (Preconditioner = auto); @p c_t is the complementarity constant of
     * friction.
     */
    void
    reinit(const double        complementarity_constant,
           const unsigned int  steps_per_matrix,
           const MemoryBudget &memory);

    /**
     * Solve one step of @p scheme (k, theta; bulk's K0 must be formed for it:
     * BulkOperator::set_time_step()). @p w holds the initial guess
     * (w_{n-1}) and returns w_n, in master form; the ContactState holds
     * the friction forces of the last step (the warm start) and returns
     * those of w_n, with the frozen coefficients and the node states. Throws
     * StepFailure if Newton does not converge, and if the convexification
     * loop reaches its cap unless @p accept_unconverged_loop (the smallest
     * time step: the step is then kept, with
     * Statistics::convexification_converged = false).
     */
    Statistics
    solve(const TimeScheme &scheme,
          const Vector_t   &rhs,
          const Vector_t   &u_old,
          const Vector_t   &w_old,
          Vector_t         &w,
          const bool        accept_unconverged_loop = false);

    /** The contact solver in use (Solver/Contact solver, auto resolved). */
    std::string
    solver_name() const
    {
      return plan.contact_solver_name();
    }

    /** How the steps are solved on the current mesh, and why. */
    const SolverPlan &
    solver_plan() const
    {
      return plan;
    }

    /** What the contact solvers made so far hold on this process. */
    void
    memory_consumption(MemoryItems &items) const
    {
      for (const auto &[theta, solver] : solvers)
        solver->memory_consumption(items);
    }

    /** True if the scene has friction (a law with a nonzero coefficient). */
    bool
    has_friction() const
    {
      return friction;
    }

    /**
     * Whether the steps of a scene with the friction law @p law (null:
     * none) run the convexification loop: a law that depends on the slip
     * rate. Only then is the norm of V (BulkOperator::strain_product())
     * needed.
     */
    static bool
    runs_convexification_loop(const FrictionLaw *law)
    {
      // A law that is not constant has friction (mu = 0 is constant).
      return law != nullptr && !law->is_constant();
    }

    /**
     * The states mu~_i at the start of the run: mu(s) of the slip rate of
     * the initial velocity @p w0 at each node (steady sliding).
     */
    void
    start_coefficient_states(const Vector_t &w0);

  private:
    const Discretization<dim>  &discretization;
    const BulkOperator<dim>    &bulk;
    const ContactBoundary<dim> &contact_boundary;
    ContactState<dim>          &contact_state;
    const Foundation           &foundation;
    const FrictionLaw          *friction_law;
    const Parameters::Solver    parameters;
    const Parameters::Friction  friction_parameters;
    TimerOutput                &timer;
    const ConditionalOStream   &details;
    const bool                  friction;
    double                      c_t = 0;
    /**
     * The law's one-sided Lipschitz constant max(0, -min mu') on
     * [0, Friction/Maximum slip rate] (0 without a law that depends on s):
     * the L of the uniqueness bound, and how fast mu can change with the
     * slip rate: what a provisional pass of the convexification loop may
     * leave of the slip rate is measured by it.
     */
    const double lipschitz_constant;

    /**
     * One contact solver per theta of the (sub-)steps, made when first
     * needed: K0 = (rho/k) M + theta A + theta^2 k B depends on theta, and a
     * solver keeps its factorization (and the condensed solver's compliance
     * columns) from step to step while K0 does not change. A composite
     * scheme (Time/Scheme = bathe) alternates two thetas (at rho_inf = 1
     * both sub-steps are trapezoidal over k/2: one); the others use one.
     */
    std::map<double, std::unique_ptr<ContactSolver<dim>>> solvers;
    /** The solver for steps of @p scheme's theta. */
    ContactSolver<dim> &
    solver_for(const TimeScheme &scheme);
    /** How the steps are solved (made by reinit()). */
    SolverPlan plan;
    /** The parameters with the plan's choices, which the solvers keep. */
    Parameters::Solver planned_parameters;

    /** The convexification loop of one step (convexification_loop.cc). */
    class ConvexificationLoop;

    /** What a convexification loop is asked to do. */
    struct LoopOptions
    {
      double       coefficient_tolerance;
      unsigned int max_passes;
      bool         coupled;
    };

    /** What every convexification loop of a step shares. */
    struct LoopArguments
    {
      const TimeScheme                  &scheme;
      ContactSolver<dim>                &contact_solver;
      const Vector_t                    &rhs;
      const Vector_t                    &u_old;
      const std::vector<Tensor<1, dim>> &u_old_nodes;
      const std::vector<Tensor<1, dim>> &w_old_nodes;
    };

    /**
     * A convexification loop of the step from the initial guess @p w (its
     * solution on return) with @p options; whether the loop updates the
     * coefficients (ConvexificationLoop::active()).
     */
    bool
    run_loop(const LoopArguments &arguments,
             Vector_t            &w,
             Statistics          &statistics,
             const LoopOptions   &options,
             const bool           accept_unconverged_loop);

    /**
     * Friction/Count solutions (doc/theory.md section 5.3): the step solved
     * again from several starts to a coefficient residual of 1/100 of
     * Friction/Coefficient tolerance, and the
     * distinct solutions counted into @p statistics. @p start_state is the
     * contact state at the step's start; the contact state and @p w of the
     * step's solution are left as they were (collective).
     */
    void
    count_solutions(const LoopArguments     &arguments,
                    const Vector_t          &w_old,
                    const ContactState<dim> &start_state,
                    Statistics              &statistics);

    /**
     * The uniqueness measures of the solved step into @p statistics
     * (Statistics::uniqueness_bound, uniqueness_certificate,
     * contraction_factor; collective).
     */
    void
    measure_uniqueness(const TimeScheme   &scheme,
                       ContactSolver<dim> &solver,
                       Statistics         &statistics);

    /** Evaluate the owned nodes' states at the converged (w, lambda). */
    void
    update_states(const TimeScheme                  &scheme,
                  const std::vector<Tensor<1, dim>> &u_old_nodes,
                  const std::vector<Tensor<1, dim>> &w_old_nodes,
                  const Vector_t                    &w,
                  Statistics                        &statistics);

    /**
     * With a slip length: the states mu~_i at the end of the solved step
     * (SlipLength::end_state() of the slip rates of update_states()), where
     * the next solve starts.
     */
    void
    advance_coefficient_states(const TimeScheme &scheme);
  };
} // namespace DynamicContact

#endif
