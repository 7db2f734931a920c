#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/run/field_io.h>
#include <dynamic_contact/run/mesh_life_cycle.h>

#include <cstdio>
#include <exception>

namespace DynamicContact
{
  template <int dim>
  void
  FieldIO<dim>::save_checkpoint(OutputDirectory             &directory,
                                const RunState              &state,
                                const std::string           &parameters_of_run,
                                const unsigned int           keep,
                                const std::function<void()> &before_commit)
  {
    CarriedFields<dim> carried(u,
                               w,
                               false,
                               parameters.friction.slip_length.active());
    carried.take(contact_state, discretization, contact_boundary);
    write_checkpoint(directory,
                     discretization,
                     carried.vectors(),
                     state,
                     parameters_of_run,
                     keep,
                     before_commit);
  }


  template <int dim>
  void
  FieldIO<dim>::load_checkpoint(const std::string           &path,
                                const std::function<void()> &setup_dofs,
                                const std::function<void()> &setup_operators)
  {
    CarriedFields<dim> carried(u,
                               w,
                               false,
                               parameters.friction.slip_length.active());
    DynamicContact::load_checkpoint<dim>(path,
                                         discretization,
                                         carried.vectors(),
                                         setup_dofs);
    setup_operators();
    carried.give_back(contact_state, contact_boundary);
  }


  template <int dim>
  void
  FieldIO<dim>::write_contact_csv(OutputDirectory   &directory,
                                  const unsigned int n,
                                  const double       t) const
  {
    char name[64];
    std::snprintf(name, sizeof(name), "contact_%05u.csv", n);
    DynamicContact::write_contact_csv(directory,
                                      name,
                                      t,
                                      contact_boundary,
                                      contact_state.nodes,
                                      u,
                                      w,
                                      friction,
                                      comm);
  }


  template <int dim>
  void
  FieldIO<dim>::write_vtu(VtuWriter<dim>    &writer,
                          const unsigned int n,
                          const double       t) const
  {
    writer.write(n,
                 t,
                 discretization,
                 material,
                 contact_boundary,
                 contact_state.nodes,
                 u,
                 w,
                 friction);
  }


  template <int dim>
  Tensor<1, dim>
  FieldIO<dim>::point_displacement(const Point<dim> &point) const
  {
    const Vector_t ghosted = discretization.expanded(u);
    Vector<double> value(dim);
    double         found = 0;
    try
      {
        const auto cell =
          GridTools::find_active_cell_around_point(discretization.mapping,
                                                   discretization.dof_handler,
                                                   point);
        if (cell.first->is_locally_owned())
          {
            VectorTools::point_value(discretization.mapping,
                                     discretization.dof_handler,
                                     ghosted,
                                     point,
                                     value);
            found = 1;
          }
      }
    catch (const std::exception &)
      {}
    const double n_found = Utilities::MPI::sum(found, comm);
    AssertThrow(n_found > 0, ExcMessage("The point is not inside the body."));
    Tensor<1, dim> result;
    for (unsigned int c = 0; c < dim; ++c)
      result[c] = Utilities::MPI::sum(found * value(c), comm) / n_found;
    return result;
  }


  template class FieldIO<2>;
  template class FieldIO<3>;
} // namespace DynamicContact
