#ifndef dynamic_contact_planned_solvers_h
#define dynamic_contact_planned_solvers_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/solver_plan.h>
#include <dynamic_contact/laws/foundation.h>

#include <map>
#include <memory>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * How the steps are solved on the current mesh (the SolverPlan that
   * reinit() makes) and the contact solvers made by it for the StepSolver,
   * one per theta of the (sub-)steps, made when first needed: K0 =
   * (rho/k) M + theta A + theta^2 k B depends on theta, and a solver keeps
   * its factorization (and the condensed solver's compliance columns) from
   * step to step while K0 does not change. A composite scheme (Time/Scheme
   * = bathe) alternates two thetas (at rho_inf = 1 both sub-steps are
   * trapezoidal over k/2: one); the others use one.
   */
  template <int dim>
  class PlannedSolvers
  {
  public:
    /**
     * The solvers' problem (ContactProblem): @p friction, the scene has
     * friction; @p slip_rate_accuracy, how accurately the loop needs the
     * slip rates.
     */
    PlannedSolvers(const Discretization<dim>  &discretization,
                   const BulkOperator<dim>    &bulk,
                   const ContactBoundary<dim> &contact_boundary,
                   const Foundation           &foundation,
                   const Parameters::Solver   &solver_parameters,
                   TimerOutput                &timer,
                   const ConditionalOStream   &details,
                   const bool                  friction,
                   const double                slip_rate_accuracy)
      : parameters(solver_parameters)
      , problem{discretization,
                bulk,
                contact_boundary,
                foundation,
                planned_parameters,
                timer,
                details,
                friction,
                0.,
                slip_rate_accuracy}
    {}

    /**
     * Plan the solver for @p steps_per_matrix steps with one bulk matrix
     * within @p memory and forget the solvers made so far;
     * @p complementarity_constant is c_t of friction.
     */
    void
    reinit(const double        complementarity_constant,
           const unsigned int  steps_per_matrix,
           const MemoryBudget &memory);

    /** The solver for steps of @p scheme's theta. */
    ContactSolver<dim> &
    solver_for(const TimeScheme &scheme);

    /** The complementarity constant c_t of friction (reinit()). */
    double
    complementarity_constant() const
    {
      return problem.c_t;
    }

    /** How the steps are solved (made by reinit()). */
    const SolverPlan &
    plan() const
    {
      return solver_plan;
    }

    /** The planned contact solver solves passes provisionally. */
    bool
    provisional_passes() const
    {
      return parameters.contact_solver_plugin(solver_plan.contact_solver)
        .provisional_passes();
    }

    /** What the contact solvers made so far hold on this process. */
    void
    memory_consumption(MemoryItems &items) const
    {
      for (const auto &[theta, solver] : solvers)
        solver->memory_consumption(items);
    }

  private:
    const Parameters::Solver parameters;
    /** The parameters with the plan's choices, which the solvers keep. */
    Parameters::Solver planned_parameters;
    /** What the solvers are made for: the planned parameters, c_t. */
    ContactProblem<dim> problem;

    std::map<double, std::unique_ptr<ContactSolver<dim>>> solvers;
    SolverPlan                                            solver_plan;
  };
} // namespace DynamicContact

#endif
