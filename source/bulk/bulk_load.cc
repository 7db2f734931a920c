#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <dynamic_contact/bulk/bulk_load.h>

namespace DynamicContact
{
  template <int dim>
  BulkLoad<dim>::BulkLoad(const Discretization<dim> &d)
    : discretization(d)
    , face_quadrature(d)
  {}


  template <int dim>
  void
  BulkLoad<dim>::assemble(const Scene<dim> &scene,
                          const double      t,
                          Vector_t         &load) const
  {
    load                  = 0;
    const bool body_force = scene.has_body_force();
    const bool traction =
      scene.has_traction() && !scene.boundary_conditions().traction.empty();
    const bool source = scene.has_contact_source() &&
                        !scene.boundary_conditions().contact.empty();
    if (!body_force && !traction && !source)
      return;
    scene.set_time(t);

    const auto        &fe = discretization.fe;
    const unsigned int n  = fe.n_dofs_per_cell();
    const QGauss<dim>  quadrature(fe.degree + 2);
    FEValues<dim>      fe_values = discretization.cell_values(
      quadrature, update_values | update_quadrature_points | update_JxW_values);
    Vector<double>                       local(n);
    Vector<double>                       value(dim);
    std::vector<types::global_dof_index> dofs(n);

    if (loaded_cells_scene != &scene)
      {
        loaded_cells.clear();
        loaded_faces.clear();
        loaded_face_cell.clear();
        for (const auto &cell :
             discretization.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && scene.carries_load(cell))
            {
              for (const auto f : cell->face_indices())
                if (Function<dim> *const g = scene.face_load(cell, f))
                  {
                    loaded_faces.push_back({cell, f, g});
                    loaded_face_cell.push_back(loaded_cells.size());
                  }
              loaded_cells.push_back(cell);
            }
        loaded_cells_scene = &scene;
      }
    // The surface loads, face by face, to their tolerance (collective).
    face_quadrature.integrate(scene, t, loaded_faces, face_values);
    unsigned int face = 0;
    for (unsigned int c = 0; c < loaded_cells.size(); ++c)
      {
        const auto &cell = loaded_cells[c];
        local            = 0;
        if (body_force)
          {
            fe_values.reinit(cell);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                scene.body_force().vector_value(fe_values.quadrature_point(q),
                                                value);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    const unsigned int c =
                      fe.system_to_component_index(i).first;
                    local(i) +=
                      value(c) * fe_values.shape_value(i, q) * fe_values.JxW(q);
                  }
              }
          }
        for (; face < loaded_faces.size() && loaded_face_cell[face] == c;
             ++face)
          local += face_values[face];
        // Every listed cell carries a load (a body force, a loaded face).
        cell->get_dof_indices(dofs);
        discretization.constraints.distribute_local_to_global(local,
                                                              dofs,
                                                              load);
      }
    load.compress(VectorOperation::add);
  }


  template class BulkLoad<2>;
  template class BulkLoad<3>;
} // namespace DynamicContact
