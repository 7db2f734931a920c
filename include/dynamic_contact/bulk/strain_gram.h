#ifndef dynamic_contact_strain_gram_h
#define dynamic_contact_strain_gram_h

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The inner product of V, (eps(x), eps(y)) over the body, of two vectors
   * in master form (constrained entries zero), evaluated cell by cell from
   * the mesh (deal.II's MatrixFree, as in step-37) instead of from a stored
   * Gram matrix: x^T S y for S assembled and condensed with the mesh's
   * constraints, without S's values (8 bytes per entry of K0's pattern).
   * The hanging nodes and the other constraints are resolved as the
   * condensed matrix resolves them (their inhomogeneities play no part).
   */
  template <int dim>
  class StrainGram
  {
  public:
    explicit StrainGram(const Discretization<dim> &discretization);

    /** Set up the cell data of the current mesh (after setup_dofs). */
    void
    reinit();

    /**
     * (eps(x), eps(y))_{L^2} (collective); with @p x and @p y the same
     * object, one evaluation serves both.
     */
    double
    product(const Vector_t &x, const Vector_t &y) const;

    /** The cell data and the two work vectors on this process, in bytes. */
    double
    memory_consumption() const;

  private:
    using Work_t = LinearAlgebra::distributed::Vector<double>;

    const Discretization<dim> &discretization;
    MatrixFree<dim, double>    matrix_free;
    mutable Work_t             x_work, y_work;

    /** @p target = @p source, with the ghost entries the cells read. */
    void
    import(const Vector_t &source, Work_t &target) const;
  };
} // namespace DynamicContact

#endif
