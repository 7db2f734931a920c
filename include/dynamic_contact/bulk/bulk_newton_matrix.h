#ifndef dynamic_contact_bulk_newton_matrix_h
#define dynamic_contact_bulk_newton_matrix_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/bulk/bulk_kernel.h>
#include <dynamic_contact/bulk/cell_operators.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/material.h>

#include <array>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  template <int dim>
  class StoredForms;

  /**
   * The bulk Newton matrix K0 = (rho/k) M + theta A + theta^2 k B of
   * BulkOperator: its integrand for the last time scheme (BulkKernel), and,
   * where K0 is stored, its sparsity pattern (shared with the stored forms)
   * and the matrix, summed from the stored forms or assembled cell by cell.
   * Applied as the stored matrix or cell by cell (the forms' cell data);
   * its dim x dim blocks at nodes read from either.
   */
  template <int dim>
  class BulkNewtonMatrix
  {
  public:
    /** @p forms: the forms' cell data, for K0 not stored. */
    BulkNewtonMatrix(const Discretization<dim>      &discretization,
                     const KelvinVoigtMaterial<dim> &material,
                     const CellOperators<dim>       &forms)
      : discretization(discretization)
      , material(material)
      , forms(forms)
    {}

    /**
     * With @p store, set up K0's pattern and K0 on it on the current mesh;
     * else free both.
     */
    void
    reinit(const bool store);

    /** Whether K0 is a stored matrix. */
    bool
    stored() const
    {
      return stored_matrix;
    }

    /**
     * Form K0 for @p scheme: its integrand, and the stored K0 summed from
     * @p stored_forms if given, else assembled cell by cell if stored.
     */
    void
    set_time_step(const TimeScheme       &scheme,
                  const StoredForms<dim> *stored_forms);

    /** The stored K0. */
    const Matrix_t &
    matrix() const
    {
      return bulk_matrix;
    }

    /** K0's pattern (empty where K0 is not stored). */
    const TrilinosWrappers::SparsityPattern &
    sparsity_pattern() const
    {
      return pattern;
    }

    /** @p dst = K0 @p src (collective): the stored K0, or cell by cell. */
    void
    vmult(Vector_t &dst, const Vector_t &src) const;

    /** K0's dim x dim blocks at nodes: BulkOperator::newton_blocks(). */
    std::vector<Tensor<2, dim>>
    node_blocks(
      const std::vector<std::array<types::global_dof_index, dim>> &dofs) const;

  private:
    const Discretization<dim>      &discretization;
    const KelvinVoigtMaterial<dim> &material;
    const CellOperators<dim>       &forms;

    bool                              stored_matrix = true;
    TrilinosWrappers::SparsityPattern pattern;
    Matrix_t                          bulk_matrix;
    /** K0's integrand for the last time scheme (set_time_step()). */
    BulkKernel<dim> kernel;

    /** K0 assembled cell by cell. */
    void
    assemble(const TimeScheme &scheme);

    /**
     * K0's matrix on each cell that @p take (called on the owned and ghost
     * cells) accepts, for the time scheme of @p kernel: @p cell_done(local,
     * dofs).
     */
    template <typename Take, typename CellDone>
    void
    for_each_cell_matrix(const BulkKernel<dim> &kernel,
                         const Take            &take,
                         const CellDone        &cell_done) const;
  };
} // namespace DynamicContact

#endif
