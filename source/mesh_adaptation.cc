#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/error_estimator.h>

#include <dynamic_contact/mesh_adaptation.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace DynamicContact
{
  template <int dim>
  MeshAdaptation<dim>::MeshAdaptation(
    const Parameters::MeshRefinement &parameters,
    const Scene<dim> &                 scene,
    Discretization<dim> &              discretization)
    : parameters(parameters)
    , scene(scene)
    , discretization(discretization)
  {}


  template <int dim>
  std::vector<Point<dim>>
  MeshAdaptation<dim>::large_load_points(const double t0,
                                         const double t1,
                                         const double k) const
  {
    const auto &d  = discretization;
    const auto &bc = scene.boundary_conditions();
    const std::set<types::boundary_id> traction_ids(bc.traction.begin(),
                                                    bc.traction.end());
    const bool traction   = scene.has_traction() && !traction_ids.empty();
    const bool body_force = scene.has_body_force();

    std::vector<double> times;
    for (double t = t0; t <= t1 * (1 + 1e-12) + 1e-300; t += k)
      times.push_back(t);
    if (times.empty() || times.back() < t1)
      times.push_back(t1);

    // Sample the load magnitude at face (traction) and cell (body force)
    // quadrature points, at every time; keep each point's largest value.
    const QGauss<dim - 1> face_quadrature(2);
    const QGauss<dim>     quadrature(2);
    FEFaceValues<dim>     fe_face(d.mapping,
                              d.fe,
                              face_quadrature,
                              update_quadrature_points);
    FEValues<dim>         fe_values(d.mapping,
                            d.fe,
                            quadrature,
                            update_quadrature_points);
    std::vector<Point<dim>> points;
    std::vector<double>     magnitude;
    Vector<double>          value(dim);
    auto sample = [&](const Point<dim> &p, Function<dim> &f) {
      double largest = 0;
      for (const double t : times)
        {
          f.set_time(t);
          f.vector_value(p, value);
          largest = std::max(largest, value.l2_norm());
        }
      points.push_back(p);
      magnitude.push_back(largest);
    };
    for (const auto &cell : d.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          if (traction)
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  traction_ids.count(cell->face(f)->boundary_id()))
                {
                  fe_face.reinit(cell, f);
                  for (const auto &p : fe_face.get_quadrature_points())
                    sample(p, scene.traction());
                }
          if (body_force)
            {
              fe_values.reinit(cell);
              for (const auto &p : fe_values.get_quadrature_points())
                sample(p, scene.body_force());
            }
        }
    const double largest = Utilities::MPI::max(
      magnitude.empty() ? 0. : *std::max_element(magnitude.begin(),
                                                 magnitude.end()),
      d.comm);

    std::vector<Point<dim>> large;
    if (largest > 0)
      for (unsigned int i = 0; i < points.size(); ++i)
        if (magnitude[i] >= parameters.load_threshold * largest)
          large.push_back(points[i]);
    std::vector<Point<dim>> all;
    for (const auto &part : Utilities::MPI::all_gather(d.comm, large))
      all.insert(all.end(), part.begin(), part.end());
    return all;
  }


  template <int dim>
  bool
  MeshAdaptation<dim>::flag_cells(const double                   t0,
                                  const double                   t1,
                                  const double                   k,
                                  const std::vector<Point<dim>> &contact_points,
                                  const Vector_t &               u,
                                  const Vector_t &               w)
  {
    auto &             tria = discretization.triangulation;
    const unsigned int min_level = parameters.minimum_level;

    // Kelly's indicator: one level up for the largest, down for the
    // smallest (normalized sum of the indicators of u and w).
    std::map<unsigned int, int> kelly_change; // active cell index -> +-1
    if (parameters.error_indicator)
      {
        Vector<float> eu(tria.n_active_cells()), ew(tria.n_active_cells());
        const QGauss<dim - 1> q(discretization.fe.degree + 1);
        KellyErrorEstimator<dim>::estimate(discretization.mapping,
                                           discretization.dof_handler,
                                           q,
                                           {},
                                           u,
                                           eu);
        KellyErrorEstimator<dim>::estimate(discretization.mapping,
                                           discretization.dof_handler,
                                           q,
                                           {},
                                           w,
                                           ew);
        const double mu = Utilities::MPI::max(static_cast<double>(eu.linfty_norm()),
                                              discretization.comm);
        const double mw = Utilities::MPI::max(static_cast<double>(ew.linfty_norm()),
                                              discretization.comm);
        Vector<float> indicator(tria.n_active_cells());
        for (unsigned int i = 0; i < indicator.size(); ++i)
          indicator(i) = (mu > 0 ? eu(i) / mu : 0.) + (mw > 0 ? ew(i) / mw : 0.);
        parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
          tria,
          indicator,
          parameters.refine_fraction,
          parameters.coarsen_fraction);
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              if (cell->refine_flag_set())
                kelly_change[cell->active_cell_index()] = 1;
              else if (cell->coarsen_flag_set())
                kelly_change[cell->active_cell_index()] = -1;
              cell->clear_refine_flag();
              cell->clear_coarsen_flag();
            }
      }

    const std::vector<Point<dim>> load_points =
      parameters.load_following ? large_load_points(t0, t1, k) :
                                  std::vector<Point<dim>>();

    // Within a distance of a point set (cell centre, minus half the cell).
    auto near = [](const auto &cell,
                   const std::vector<Point<dim>> &points,
                   const double                   window) {
      const Point<dim> c = cell->center();
      const double     r = window + 0.5 * cell->diameter();
      for (const auto &p : points)
        if (c.distance_square(p) <= r * r)
          return true;
      return false;
    };

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
              if ((parameters.load_following &&
                   near(cell, load_points, parameters.load_window)) ||
                  (parameters.contact_following &&
                   near(cell, contact_points, parameters.contact_window)))
                level = max_level;
              const auto kelly = kelly_change.find(cell->active_cell_index());
              if (kelly != kelly_change.end())
                level = std::max(level, static_cast<int>(cell->level()) +
                                          kelly->second);
              else if (parameters.error_indicator)
                level = std::max(level, static_cast<int>(cell->level()));
              level = std::clamp(level,
                                 static_cast<int>(min_level),
                                 static_cast<int>(max_level));
              desired[cell->active_cell_index()] = level;
              estimate += std::pow(2., dim * (level - static_cast<int>(
                                                        cell->level())));
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
    for (const auto &cell : discretization.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        levels += cell->level();
    return {discretization.triangulation.n_global_active_cells(),
            Utilities::MPI::sum(levels, discretization.comm)};
  }


  template <int dim>
  void
  refine_and_transfer(Discretization<dim> &          d,
                      const std::vector<Vector_t *> &fields,
                      const std::function<void()> &  after_refinement)
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
