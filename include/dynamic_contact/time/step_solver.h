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
#include <dynamic_contact/time/planned_solvers.h>
#include <dynamic_contact/time/solution_uniqueness.h>
#include <dynamic_contact/time/step_statistics.h>

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
   *
   * Its parts: the solver plan and the contact solvers (PlannedSolvers),
   * the uniqueness measures and the solution count (SolutionUniqueness),
   * and what a solve did (StepStatistics).
   */
  template <int dim>
  class StepSolver
  {
  public:
    /** What the solve of a step did and found (step_statistics.h). */
    using Statistics = StepStatistics;

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
      return solvers.plan().contact_solver_name();
    }

    /** How the steps are solved on the current mesh, and why. */
    const SolverPlan &
    solver_plan() const
    {
      return solvers.plan();
    }

    /** What the contact solvers made so far hold on this process. */
    void
    memory_consumption(MemoryItems &items) const
    {
      solvers.memory_consumption(items);
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
    const Parameters::Friction  friction_parameters;
    TimerOutput                &timer;
    const ConditionalOStream   &details;
    const bool                  friction;
    /**
     * The law's one-sided Lipschitz constant max(0, -min mu') on
     * [0, Friction/Maximum slip rate] (0 without a law that depends on s):
     * the L of the uniqueness bound, and how fast mu can change with the
     * slip rate: what a provisional pass of the convexification loop may
     * leave of the slip rate is measured by it.
     */
    const double lipschitz_constant;

    /** The solver plan and the contact solvers, one per theta. */
    PlannedSolvers<dim> solvers;
    /** The uniqueness measures and the solution count of a step. */
    SolutionUniqueness<dim> uniqueness;

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
