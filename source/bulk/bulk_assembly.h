#ifndef dynamic_contact_source_bulk_bulk_assembly_h
#define dynamic_contact_source_bulk_bulk_assembly_h

// The bulk assembly's patterns and loop over the cells, shared by the stored
// forms (stored_forms.cc) and K0 (bulk_newton_matrix.cc): a header of those
// files, not of the library.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/table.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <dynamic_contact/bulk/discretization.h>

#include <functional>
#include <vector>

namespace DynamicContact
{
  namespace
  {
    /**
     * The couplings of the components: every component with every other
     * (K0 and the stiffness matrices), or, with @p each_with_itself, each
     * component with itself alone (M: phi_i . phi_j vanishes between
     * components).
     */
    template <int dim>
    Table<2, DoFTools::Coupling>
    component_couplings(const bool each_with_itself)
    {
      Table<2, DoFTools::Coupling> couplings(dim, dim);
      for (unsigned int c = 0; c < dim; ++c)
        for (unsigned int d = 0; d < dim; ++d)
          couplings(c, d) =
            (!each_with_itself || c == d ? DoFTools::always : DoFTools::none);
      return couplings;
    }


    /**
     * @p p on the current mesh for the @p couplings, condensed with the
     * mesh's constraints (collective).
     */
    template <int dim>
    void
    make_pattern(const Discretization<dim>          &discretization,
                 const Table<2, DoFTools::Coupling> &couplings,
                 TrilinosWrappers::SparsityPattern  &p)
    {
      p.reinit(discretization.locally_owned,
               discretization.locally_owned,
               discretization.locally_relevant,
               discretization.comm);
      DoFTools::make_sparsity_pattern(discretization.dof_handler,
                                      couplings,
                                      p,
                                      discretization.constraints,
                                      /*keep_constrained_dofs=*/false,
                                      Utilities::MPI::this_mpi_process(
                                        discretization.comm));
      p.compress();
    }


    /**
     * The bulk assembly's loop: on each locally owned cell (each owned or
     * ghost cell that @p take accepts, if given), @p point(value, eps, JxW)
     * at each point of the quadrature QGauss(p + 1) with the shape
     * functions' values and symmetric gradients, then @p cell(dofs).
     */
    template <int dim, typename Point, typename Cell>
    void
    for_each_point(
      const Discretization<dim> &discretization,
      const Point               &point,
      const Cell                &cell_done,
      const std::function<bool(
        const typename DoFHandler<dim>::active_cell_iterator &)> &take = {})
    {
      const auto       &fe = discretization.fe;
      const QGauss<dim> quadrature(fe.degree + 1);
      FEValues<dim>     fe_values = discretization.cell_values(
        quadrature, update_values | update_gradients | update_JxW_values);
      const unsigned int                   n = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> dofs(n);
      std::vector<SymmetricTensor<2, dim>> eps(n);
      std::vector<Tensor<1, dim>>          value(n);
      const FEValuesExtractors::Vector     displacement(0);
      for (const auto &cell :
           discretization.dof_handler.active_cell_iterators())
        if (take ? (!cell->is_artificial() && take(cell)) :
                   cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                for (unsigned int i = 0; i < n; ++i)
                  {
                    eps[i]   = fe_values[displacement].symmetric_gradient(i, q);
                    value[i] = fe_values[displacement].value(i, q);
                  }
                point(value, eps, fe_values.JxW(q));
              }
            cell->get_dof_indices(dofs);
            cell_done(dofs);
          }
    }
  } // namespace
} // namespace DynamicContact

#endif
