#include <dynamic_contact/time/planned_solvers.h>

namespace DynamicContact
{
  template <int dim>
  void
  PlannedSolvers<dim>::reinit(const double        complementarity_constant,
                              const unsigned int  steps_per_matrix,
                              const MemoryBudget &memory)
  {
    problem.c_t        = complementarity_constant;
    solver_plan        = plan_solver(parameters,
                              dim,
                              problem.discretization.dof_handler.n_dofs(),
                              problem.boundary.n_global_nodes(),
                              steps_per_matrix,
                              problem.discretization.comm,
                              memory);
    planned_parameters = solver_plan.solver_parameters(parameters);
    problem.details << "  solver plan: " << solver_plan.description()
                    << std::endl;
    solvers.clear();
  }


  template <int dim>
  ContactSolver<dim> &
  PlannedSolvers<dim>::solver_for(const TimeScheme &scheme)
  {
    auto &solver = solvers[scheme.theta()];
    if (!solver)
      {
        solver =
          planned_parameters.contact_solver_plugin(solver_plan.contact_solver)
            .create(problem);
        solver->reinit();
      }
    return *solver;
  }


  template class PlannedSolvers<2>;
  template class PlannedSolvers<3>;
} // namespace DynamicContact
