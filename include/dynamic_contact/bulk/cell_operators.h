#ifndef dynamic_contact_cell_operators_h
#define dynamic_contact_cell_operators_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <dynamic_contact/bulk/bulk_kernel.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/material.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The bulk forms of the scheme, applied cell by cell from the mesh
   * (deal.II's MatrixFree, as in step-37) instead of from stored matrices:
   *
   * - mass:       (x, y)               (M, without rho),
   * - elasticity: (E eps(x), eps(y))   (B),
   * - viscosity:  (C eps(x), eps(y))   (A),
   * - strain:     (eps(x), eps(y))     (the inner product of V),
   *
   * as products x^T F y and as F x, for vectors in master form (constrained
   * entries zero), with the quadrature the matrices were assembled with.
   * They are what the matrices assembled and condensed with the mesh's
   * constraints give, to round-off: the hanging nodes and the other
   * constraints are resolved as condensation resolves them (their
   * inhomogeneities play no part), and a constrained row of F x is zero.
   * The cells are visited in a fixed order on one thread.
   */
  /**
   * Copy the owned entries between a Trilinos vector and a deal.II vector
   * of the same DoFs (both keep them in one contiguous range, in the same
   * order); ghost entries are not touched.
   */
  void
  copy_owned(const Vector_t                                   &source,
             LinearAlgebra::distributed::Vector<double>       &target);
  void
  copy_owned(const LinearAlgebra::distributed::Vector<double> &source,
             Vector_t                                         &target);


  /**
   * Set up @p matrix_free for the vector field of @p dof_handler as the
   * bulk forms apply it: values, gradients and JxW at QGauss(p + 1), the
   * cells in a fixed order on one thread (sums that do not depend on the
   * threads).
   */
  template <int dim>
  void
  reinit_cell_data(MatrixFree<dim, double>         &matrix_free,
                   const Mapping<dim>              &mapping,
                   const DoFHandler<dim>           &dof_handler,
                   const AffineConstraints<double> &constraints);


  template <int dim>
  class CellOperators
  {
  public:
    enum class Form
    {
      mass,
      elasticity,
      viscosity,
      strain
    };

    CellOperators(const Discretization<dim>      &discretization,
                  const KelvinVoigtMaterial<dim> &material);

    /** Set up the cell data of the current mesh (after setup_dofs). */
    void
    reinit();

    /** Free the cell data (a mesh on which the forms are stored). */
    void
    clear();

    /**
     * x^T F y (collective); with @p x and @p y the same object, one
     * evaluation serves both.
     */
    double
    product(const Form form, const Vector_t &x, const Vector_t &y) const;

    /** @p dst = F @p src (collective). */
    void
    vmult(const Form form, Vector_t &dst, const Vector_t &src) const;

    /** @p dst = K0 @p src for the integrand @p kernel (collective). */
    void
    vmult(const BulkKernel<dim> &kernel,
          Vector_t              &dst,
          const Vector_t        &src) const;

    /** The cell data (as reinit_cell_data() sets them up). */
    const MatrixFree<dim, double> &
    cell_data() const
    {
      return matrix_free;
    }

    /** The cell data and the work vectors on this process, in bytes. */
    double
    memory_consumption() const;

  private:
    using Work_t = LinearAlgebra::distributed::Vector<double>;
    using Tensor4_t = SymmetricTensor<4, dim, VectorizedArray<double>>;

    const Discretization<dim> &discretization;
    const Tensor4_t            elasticity, viscosity;
    MatrixFree<dim, double>    matrix_free;
    mutable Work_t             x_work, y_work;

    /** The tensor of @p form (elasticity or viscosity). */
    const Tensor4_t &
    tensor(const Form form) const;

    /**
     * @p dst = F @p src with F given by @p apply(phi) on each cell batch
     * (evaluate, submit, integrate).
     */
    template <typename Apply>
    void
    apply_cells(const Apply &apply, Vector_t &dst, const Vector_t &src) const;

    /** @p target = @p source, with the ghost entries the cells read. */
    void
    import(const Vector_t &source, Work_t &target) const;
  };
} // namespace DynamicContact

#endif
