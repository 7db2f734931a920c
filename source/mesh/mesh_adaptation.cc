#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/error_estimator.h>

#include <dynamic_contact/mesh/mesh_adaptation.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace DynamicContact
{
  template <int dim>
  MeshAdaptation<dim>::MeshAdaptation(
    const Parameters::MeshRefinement &parameters,
    const Scene<dim>                 &scene,
    Discretization<dim>              &discretization,
    ParameterHandler                 &prm)
    : parameters(parameters)
    , scene(scene)
    , discretization(discretization)
    , strategies(RefinementStrategy<dim>::create(prm, parameters.strategies))
  {}


  template <int dim>
  unsigned int
  MeshAdaptation<dim>::lookahead_steps() const
  {
    unsigned int steps = 0;
    for (const auto &strategy : strategies)
      steps = std::max(steps, strategy->lookahead_steps());
    return steps > 0 ? steps : parameters.refine_every;
  }


  template <int dim>
  bool
  MeshAdaptation<dim>::needs_contact_points() const
  {
    for (const auto &strategy : strategies)
      if (strategy->needs_contact_points())
        return true;
    return false;
  }


  template <int dim>
  bool
  MeshAdaptation<dim>::flag_cells(const double                   t0,
                                  const double                   t1,
                                  const double                   k,
                                  const std::vector<Point<dim>> &contact_points,
                                  const Vector_t                &u,
                                  const Vector_t                &w)
  {
    auto              &tria      = discretization.triangulation;
    const unsigned int min_level = parameters.minimum_level;

    // The levels each strategy asks for (collective, once per cycle).
    const AdaptationContext<dim> context{
      scene, discretization, t0, t1, k, contact_points, u, w};
    std::vector<typename RefinementStrategy<dim>::Levels> levels;
    for (const auto &strategy : strategies)
      levels.push_back(strategy->levels(context));

    // The level each cell asks for, with the finest level lowered until the
    // estimated number of cells fits the budget.
    std::map<unsigned int, unsigned int> desired;
    for (unsigned int max_level = parameters.maximum_level;; --max_level)
      {
        desired.clear();
        double estimate = 0;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              int level = min_level;
              for (const auto &asked : levels)
                level = std::max(level, asked(cell, max_level));
              level                              = std::clamp(level,
                                 static_cast<int>(min_level),
                                 static_cast<int>(max_level));
              desired[cell->active_cell_index()] = level;
              estimate +=
                std::pow(2., dim * (level - static_cast<int>(cell->level())));
            }
        estimate = Utilities::MPI::sum(estimate, discretization.comm);
        if (parameters.cell_budget == 0 || estimate <= parameters.cell_budget ||
            max_level <= min_level)
          break;
      }

    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int level = desired[cell->active_cell_index()];
          if (level > static_cast<unsigned int>(cell->level()))
            cell->set_refine_flag();
          else if (level < static_cast<unsigned int>(cell->level()))
            cell->set_coarsen_flag();
        }
    tria.prepare_coarsening_and_refinement();

    unsigned int flagged = 0;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned() &&
          (cell->refine_flag_set() || cell->coarsen_flag_set()))
        ++flagged;
    return Utilities::MPI::sum(flagged, discretization.comm) > 0;
  }


  template <int dim>
  std::pair<types::global_cell_index, double>
  MeshAdaptation<dim>::fingerprint() const
  {
    double levels = 0;
    for (const auto &cell :
         discretization.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        levels += cell->level();
    return {discretization.triangulation.n_global_active_cells(),
            Utilities::MPI::sum(levels, discretization.comm)};
  }


  template <int dim>
  void
  refine_and_transfer(Discretization<dim>           &d,
                      const std::vector<Vector_t *> &fields,
                      const std::function<void()>   &after_refinement)
  {
    FieldTransfer<dim, Vector_t> transfer(d, fields);
    transfer.prepare();
    d.triangulation.execute_coarsening_and_refinement();
    after_refinement();
    transfer.finish();
  }


  template class MeshAdaptation<2>;
  template class MeshAdaptation<3>;
  template void
  refine_and_transfer<2>(Discretization<2> &,
                         const std::vector<Vector_t *> &,
                         const std::function<void()> &);
  template void
  refine_and_transfer<3>(Discretization<3> &,
                         const std::vector<Vector_t *> &,
                         const std::function<void()> &);
} // namespace DynamicContact
