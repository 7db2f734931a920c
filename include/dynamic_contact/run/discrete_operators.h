#ifndef dynamic_contact_discrete_operators_h
#define dynamic_contact_discrete_operators_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/time/energy_balance.h>
#include <dynamic_contact/time/force_balance.h>
#include <dynamic_contact/time/step_solver.h>

#include <limits>
#include <string>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The operators of the discrete problem on the current mesh: the bulk
   * forms (BulkOperator), the solver of a step's contact problem
   * (StepSolver, with the foundation's law), and the measures of a step,
   * the energy and the force balance. setup() makes them for a new mesh
   * and the steps it is planned for. The StepIntegrator works with them
   * (StepOperators); they are members here so that the Simulator's parts
   * can be named: the discretization, the operators, the fields.
   */
  template <int dim>
  class DiscreteOperators
  {
  public:
    DiscreteOperators(const RunParameters            &parameters,
                      const Scene<dim>               &scene,
                      const KelvinVoigtMaterial<dim> &material,
                      const Discretization<dim>      &discretization,
                      const ContactBoundary<dim>     &contact_boundary,
                      ContactState<dim>              &contact_state,
                      const MPI_Comm                  comm,
                      TimerOutput                    &timer,
                      const ConditionalOStream       &details)
      : foundation(*parameters.foundation.law)
      , bulk(discretization,
             material,
             StepSolver<dim>::runs_convexification_loop(
               parameters.friction.law.get()))
      , step_solver(discretization,
                    bulk,
                    contact_boundary,
                    contact_state,
                    foundation,
                    parameters.friction.law.get(),
                    parameters.solver,
                    parameters.friction,
                    timer,
                    details)
      , energy_balance(bulk,
                       contact_boundary,
                       foundation,
                       material.density(),
                       comm)
      , force_balance(discretization, material, scene)
      , parameters(parameters)
      , discretization(discretization)
    {}

    /**
     * For the current mesh: the bulk matrices, the solvers, the solver
     * plan for the steps from @p start_time on (steps_per_matrix()) with
     * @p memory_per_process bytes per process (check_resources()),
     * @p adaptive_mesh: whether the mesh adapts every Mesh
     * refinement/Refine every steps.
     */
    void
    setup(const double start_time,
          const double memory_per_process,
          const bool   adaptive_mesh);

    /**
     * What the run holds, by part (collective): the mesh and DoFs, the
     * bulk operator's pattern and matrices, the contact solvers'
     * factorizations, preconditioners and tables, and @p field_bytes of
     * the step's fields and work vectors.
     */
    std::string
    memory_table(const double field_bytes) const;

    const Foundation           foundation;
    BulkOperator<dim>          bulk;
    StepSolver<dim>            step_solver;
    EnergyBalance<dim>         energy_balance;
    ForceBalanceEvaluator<dim> force_balance;

  private:
    const RunParameters       &parameters;
    const Discretization<dim> &discretization;

    /**
     * The steps from @p start_time on that one bulk matrix K0 is expected to
     * serve: those left, at most Mesh refinement/Refine every where the
     * mesh adapts (@p adaptive_mesh), one where the time step adapts (K0
     * changes with it).
     */
    unsigned int
    steps_per_matrix(const double start_time, const bool adaptive_mesh) const;
  };
} // namespace DynamicContact

#endif
