// The algebraic multigrid of the bulk matrix (BulkAMG) and the rigid-body
// modes of a mesh that it takes as near null space.

#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>

#include <dynamic_contact/bulk/bulk_solver.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  template <int dim>
  std::vector<double>
  rigid_body_modes(const Discretization<dim> &discretization,
                   std::vector<double>       *coordinates)
  {
    return rigid_body_modes(discretization.mapping,
                            discretization.dof_handler,
                            coordinates);
  }


  template <int dim>
  std::vector<double>
  rigid_body_modes(const Mapping<dim>    &mapping,
                   const DoFHandler<dim> &dof_handler,
                   std::vector<double>   *coordinates)
  {
    // From each owned DoF's component and support point (every owned DoF
    // lies on an owned cell).
    const IndexSet      owned   = dof_handler.locally_owned_dofs();
    const unsigned int  n       = owned.n_elements();
    const unsigned int  n_modes = (dim == 2 ? 3 : 6);
    std::vector<double> modes(n_modes * n, 0.);
    if (coordinates != nullptr)
      coordinates->assign(n, 0.);
    const auto                          &fe = dof_handler.get_fe();
    FEValues<dim>                        fe_values(mapping,
                            fe,
                            Quadrature<dim>(fe.get_unit_support_points()),
                            update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (owned.is_element(dofs[i]))
              {
                const unsigned int r = owned.index_within_set(dofs[i]);
                const unsigned int c = fe.system_to_component_index(i).first;
                const Point<dim>  &x = fe_values.quadrature_point(i);
                modes[c * n + r]     = 1;
                if (coordinates != nullptr)
                  (*coordinates)[r] = x[c];
                if constexpr (dim == 2)
                  modes[2 * n + r] = (c == 0 ? -x[1] : x[0]);
                else
                  {
                    // Rotations about the x, y and z axes.
                    modes[3 * n + r] = (c == 1 ? -x[2] : c == 2 ? x[1] : 0);
                    modes[4 * n + r] = (c == 0 ? x[2] : c == 2 ? -x[0] : 0);
                    modes[5 * n + r] = (c == 0 ? -x[1] : c == 1 ? x[0] : 0);
                  }
              }
        }
    return modes;
  }


  template <int dim>
  void
  BulkAMG::initialize(const Matrix_t            &matrix,
                      const Discretization<dim> &discretization,
                      const bool                 with_rotations,
                      const bool                 smoothed)
  {
    initialize(matrix,
               discretization.mapping,
               discretization.dof_handler,
               with_rotations,
               smoothed);
  }


  template <int dim>
  void
  BulkAMG::initialize(const Matrix_t        &matrix,
                      const Mapping<dim>    &mapping,
                      const DoFHandler<dim> &dof_handler,
                      const bool             with_rotations,
                      const bool             smoothed)
  {
    modes = rigid_body_modes(mapping, dof_handler);
    // The translations are the first dim columns.
    const unsigned int n_modes = (with_rotations ? (dim == 2 ? 3 : 6) : dim);
    const auto        &fe      = dof_handler.get_fe();

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = fe.degree > 1;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.;
    Teuchos::ParameterList              list;
    std::unique_ptr<Epetra_MultiVector> unused;
    data.set_parameters(list, unused, matrix);
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", static_cast<int>(n_modes));
    list.set("null space: vectors", modes.data());
    // Plain aggregation: the tentative prolongator of the aggregates, not
    // smoothed by a Jacobi step with the matrix (whose products with the
    // matrix make smoothed aggregation's hierarchy large).
    if (!smoothed)
      list.set("aggregation: damping factor", 0.);
    const HeapGrowth growth;
    amg.initialize(matrix, list);
    hierarchy_bytes = growth.measured();
    return_free_memory();
  }


  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                                        \
  template std::vector<double> rigid_body_modes(const Mapping<dim> &,           \
                                                const DoFHandler<dim> &,        \
                                                std::vector<double> *);         \
  template void                BulkAMG::initialize(const Matrix_t &,            \
                                    const Mapping<dim> &,        \
                                    const DoFHandler<dim> &,     \
                                    bool,                        \
                                    bool);                       \
  template std::vector<double> rigid_body_modes(const Discretization<dim> &,    \
                                                std::vector<double> *);         \
  template void                BulkAMG::initialize(const Matrix_t &,            \
                                    const Discretization<dim> &, \
                                    bool,                        \
                                    bool);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
