#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/bulk/discretization.h>

#include <Epetra_Import.h>

#include <set>

namespace DynamicContact
{
  template <int dim>
  Discretization<dim>::Discretization(const MPI_Comm     comm,
                                      const unsigned int degree)
    : comm(comm)
    , triangulation(comm,
                    typename Triangulation<dim>::MeshSmoothing(
                      Triangulation<dim>::smoothing_on_refinement |
                      Triangulation<dim>::smoothing_on_coarsening))
    , fe(FE_Q<dim>(degree), dim)
    , scalar_fe(degree)
    , dof_handler(triangulation)
    , scalar_dof_handler(triangulation)
  {}


  template <int dim>
  void
  Discretization<dim>::memory_consumption(MemoryItems &items) const
  {
    items.push_back(
      {"mesh (with p4est)", double(triangulation.memory_consumption()), false});
    items.push_back({"DoF handlers and index sets",
                     double(dof_handler.memory_consumption() +
                            scalar_dof_handler.memory_consumption() +
                            locally_owned.memory_consumption() +
                            locally_relevant.memory_consumption() +
                            scalar_locally_owned.memory_consumption() +
                            scalar_locally_relevant.memory_consumption()),
                     false});
    items.push_back({"constraints",
                     double(constraints.memory_consumption() +
                            hanging_node_constraints.memory_consumption()),
                     false});
  }


  template <int dim>
  void
  Discretization<dim>::add_boundary_constraints(
    const DoFHandler<dim>     &dofs,
    AffineConstraints<double> &target) const
  {
    for (const auto id : boundary_conditions.clamped)
      VectorTools::interpolate_boundary_values(mapping,
                                               dofs,
                                               id,
                                               Functions::ZeroFunction<dim>(
                                                 dim),
                                               target);
    if (!boundary_conditions.roller.empty())
      {
        const std::set<types::boundary_id> roller(
          boundary_conditions.roller.begin(), boundary_conditions.roller.end());
        VectorTools::compute_no_normal_flux_constraints(
          dofs, 0, roller, target, mapping);
      }
  }


  template <int dim>
  void
  Discretization<dim>::setup_dofs(
    const Parameters::BoundaryConditions &boundary_conditions)
  {
    dof_handler.distribute_dofs(fe);
    scalar_dof_handler.distribute_dofs(scalar_fe);
    locally_owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant);
    scalar_locally_owned = scalar_dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(scalar_dof_handler,
                                            scalar_locally_relevant);

    hanging_node_constraints.clear();
    hanging_node_constraints.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler,
                                            hanging_node_constraints);
    hanging_node_constraints.close();

    constraints.clear();
    constraints.reinit(locally_relevant);
    constraints.merge(hanging_node_constraints);
    this->boundary_conditions = boundary_conditions;
    add_boundary_constraints(dof_handler, constraints);
    constraints.close();

    bool plain_zeros = true;
    for (const auto &line : constraints.get_lines())
      plain_zeros =
        plain_zeros && line.entries.empty() && line.inhomogeneity == 0.;
    constraints_need_distribute =
      Utilities::MPI::logical_or(!plain_zeros, comm);

    owned_prototype.reinit(locally_owned, comm);
    ghosted_prototype.reinit(locally_owned, locally_relevant, comm);
    owned_to_relevant.reset();
  }


  template <int dim>
  void
  Discretization<dim>::expand(const Vector_t &master_form,
                              Vector_t       &ghosted) const
  {
    const Vector_t *source = &master_form;
    Vector_t        distributed;
    if (constraints_need_distribute)
      {
        distributed = master_form;
        constraints.distribute(distributed);
        source = &distributed;
      }
    // What Vector_t's assignment does, with the exchange pattern kept.
    if (!owned_to_relevant)
      owned_to_relevant =
        std::make_shared<Epetra_Import>(ghosted.trilinos_partitioner(),
                                        source->trilinos_partitioner());
    Assert(owned_to_relevant->TargetMap().NumMyElements() ==
               ghosted.trilinos_partitioner().NumMyElements() &&
             owned_to_relevant->SourceMap().NumMyElements() ==
               source->trilinos_partitioner().NumMyElements(),
           ExcInternalError());
    const int error =
      ghosted.trilinos_vector().Import(source->trilinos_vector(),
                                       *owned_to_relevant,
                                       Insert);
    AssertThrow(error == 0, ExcTrilinosError(error));
  }


  template <int dim>
  double
  Discretization<dim>::minimal_cell_diameter() const
  {
    double h = std::numeric_limits<double>::max();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        h = std::min(h, cell->minimum_vertex_distance());
    return Utilities::MPI::min(h, comm);
  }


  template <int dim>
  void
  Discretization<dim>::interpolate(const Function<dim> &function,
                                   Vector_t            &vector) const
  {
    VectorTools::interpolate(mapping, dof_handler, function, vector);
    constraints.set_zero(vector);
  }


  template class Discretization<2>;
  template class Discretization<3>;
} // namespace DynamicContact
