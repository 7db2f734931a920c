#ifndef dynamic_contact_bulk_multigrid_h
#define dynamic_contact_bulk_multigrid_h

#include <deal.II/matrix_free/matrix_free.h>

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/material.h>

#include <memory>

namespace DynamicContact
{
  /**
   * An approximate inverse of the bulk matrix K0 = (rho/k) M + theta A +
   * theta^2 k B, applied as a preconditioner (one V-cycle): the iterative
   * solver's, for the solves with K0 and, as the preconditioner of the
   * whole Newton system, for every Newton iteration. Built once per K0
   * (mesh and time scheme).
   */
  class BulkPreconditioner
  {
  public:
    virtual ~BulkPreconditioner() = default;

    /** @p dst = P^{-1} @p src (collective). */
    virtual void
    vmult(Vector_t &dst, const Vector_t &src) const = 0;

    /** What it holds on this process, in bytes. */
    virtual double
    memory_consumption() const = 0;

    /** Whether memory_consumption() is measured (heap growth) or counted. */
    virtual bool
    memory_measured() const = 0;
  };


  /**
   * The most DoFs of a coarsest level that the multigrid factorizes (KLU):
   * 50000 in 2D, 5000 in 3D (whose factors fill in far more).
   */
  constexpr unsigned int
  largest_factorized_coarse_level(const unsigned int dim)
  {
    return dim == 2 ? 50000u : 5000u;
  }


  /**
   * Geometric multigrid of K0 on the mesh hierarchy (Solver/Preconditioner =
   * GMG): the coarser meshes are the current one with its finest level of
   * cells removed, then the next, down to the coarse mesh (deal.II's
   * global-coarsening transfer, as in step-75), each with the same
   * element and the same
   * clamped, roller and hanging-node constraints. On each level K0 is
   * applied cell by cell (MatrixFree), except on the finest where a stored
   * K0 is used if there is one; the smoother is Chebyshev iteration with
   * the inverse diagonal (degree 2, on the upper 1/20 of the spectrum); the
   * coarsest level's matrix is assembled and factorized (KLU) if it has at
   * most largest_factorized_coarse_level() DoFs, else approximated by one
   * V-cycle of algebraic multigrid. Unlike the AMG of K0 it stores no
   * prolongators and no coarse matrices beyond the coarsest: about the cell
   * data of the levels (a seventh of the finest mesh's in 3D) and a few
   * vectors per level.
   *
   * Made for Q1 and Q2 elements (create_bulk_multigrid()).
   *
   * @p finest_matrix: the stored K0, if there is one. @p finest_cell_data:
   * the cell data of the mesh's bulk forms (BulkOperator::cell_data()), if
   * they are set up; the finest level uses them instead of setting up its
   * own, a second copy as large (benchmarks/memory measures both:
   * benchmarks/results/memory.csv, the rows "bulk forms" and "GMG of K0").
   */
  template <int dim>
  std::unique_ptr<BulkPreconditioner>
  create_bulk_multigrid(
    const Discretization<dim>      &discretization,
    const KelvinVoigtMaterial<dim> &material,
    const TimeScheme               &scheme,
    const Matrix_t                 *finest_matrix,
    const MatrixFree<dim, double>  *finest_cell_data = nullptr);
} // namespace DynamicContact

#endif
