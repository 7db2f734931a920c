#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/run/discrete_operators.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  template <int dim>
  void
  DiscreteOperators<dim>::setup(const double start_time,
                                const double memory_per_process,
                                const bool   adaptive_mesh)
  {
    // c_t of the friction complementarity function, like E/h.
    const double c_t = parameters.friction.complementarity_constant > 0 ?
                         parameters.friction.complementarity_constant :
                         parameters.material.young_modulus /
                           discretization.minimal_cell_diameter();
    MemoryBudget memory;
    memory.bytes_per_process = memory_per_process;
    memory.degree            = parameters.finite_element.degree;
    // The coarsest level's share of the DoFs as its share of the cells.
    const auto &tria = discretization.triangulation;
    memory.coarse_dofs =
      static_cast<double>(discretization.dof_handler.n_dofs()) *
      (tria.n_global_levels() > 1 ?
         static_cast<double>(tria.n_cells(0)) /
           static_cast<double>(tria.n_global_active_cells()) :
         1.);
    step_solver.reinit(c_t,
                       steps_per_matrix(start_time, adaptive_mesh),
                       memory);
    // The bulk forms stored for the condensed solver, applied from the
    // cells for the assembled solver (BulkOperator); K0 stored unless the
    // plan applies it cell by cell.
    const SolverPlan &plan = step_solver.solver_plan();
    bulk.reinit(plan.condensed, !plan.matrix_free_bulk());
    force_balance.reinit();
  }


  template <int dim>
  unsigned int
  DiscreteOperators<dim>::steps_per_matrix(const double start_time,
                                           const bool   adaptive_mesh) const
  {
    const auto &time = parameters.time;
    if (time.adaptive)
      return 1;
    const double left  = std::max(time.end_time - start_time, 0.);
    unsigned int steps = static_cast<unsigned int>(
      std::max(1., std::ceil(left / time.time_step - 1e-9)));
    if (adaptive_mesh)
      steps = std::min(steps, parameters.mesh_refinement.refine_every);
    return steps;
  }


  template <int dim>
  std::string
  DiscreteOperators<dim>::memory_table(const double field_bytes) const
  {
    MemoryItems items;
    discretization.memory_consumption(items);
    bulk.memory_consumption(items);
    step_solver.memory_consumption(items);
    items.push_back({"the step's fields and work vectors", field_bytes, false});
    return DynamicContact::memory_table(items,
                                        discretization.dof_handler.n_dofs(),
                                        discretization.comm);
  }


  template class DiscreteOperators<2>;
  template class DiscreteOperators<3>;
} // namespace DynamicContact
