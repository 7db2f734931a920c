#ifndef dynamic_contact_bulk_solver_h
#define dynamic_contact_bulk_solver_h

#include <deal.II/fe/mapping.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/bulk_multigrid.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/parameters/parameters.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class Amesos_BaseSolver;
class Epetra_LinearProblem;

namespace DynamicContact
{
  class Cholesky;

  /**
   * CG on K0 stopped at Solver/Maximum linear iterations (@p
   * max_iterations) before its tolerance for the right-hand side @p b:
   * throws a StepFailure that says so (the time loop tries a shorter step).
   */
  [[noreturn]] void
  throw_cg_failure(const SolverControl::NoConvergence &e,
                   const unsigned int                   max_iterations,
                   const Vector_t                      &b);

  /**
   * Algebraic multigrid for the bulk matrix K0 (Trilinos ML, smoothed
   * aggregation, elliptic settings, Chebyshev smoother of degree 2,
   * aggregation threshold 0: no connection of the elasticity matrix is
   * dropped as weak), with the rigid-body modes of the mesh as near null
   * space: dim translations and the rotations, 3 modes in 2D and 6 in 3D.
   * Both choices are measured by benchmarks/amg-comparison (CG on K0 to
   * 1e-10; benchmarks/results/amg_comparison*.txt): a threshold above 0,
   * or the translations alone as near null space, take several times more
   * iterations. Built once per K0 (mesh and time step) and used for every
   * solve with it and, as the preconditioner of the whole Newton system,
   * for every Newton iteration.
   */
  class BulkAMG : public BulkPreconditioner
  {
  public:
    /**
     * Build the preconditioner for @p matrix on the mesh of @p discretization
     * with the rigid-body modes as near null space, or with the dim
     * translations only if @p with_rotations is false (for the comparison
     * in benchmarks/amg-comparison); by smoothed aggregation, or plain
     * aggregation if @p smoothed is false (Solver/AMG/Aggregation).
     */
    template <int dim>
    void
    initialize(const Matrix_t            &matrix,
               const Discretization<dim> &discretization,
               const bool                 with_rotations = true,
               const bool                 smoothed       = true);

    /** The same for a matrix of the DoFs of @p dof_handler (a level). */
    template <int dim>
    void
    initialize(const Matrix_t        &matrix,
               const Mapping<dim>    &mapping,
               const DoFHandler<dim> &dof_handler,
               const bool             with_rotations = true,
               const bool             smoothed       = true);

    void
    vmult(Vector_t &dst, const Vector_t &src) const override
    {
      amg.vmult(dst, src);
    }

    /** The same for deal.II's own vectors (a multigrid level's). */
    void
    vmult(dealii::LinearAlgebra::distributed::Vector<double>       &dst,
          const dealii::LinearAlgebra::distributed::Vector<double> &src) const
    {
      amg.vmult(dst, src);
    }

    /**
     * What the hierarchy holds on this process: the growth of the heap in
     * use while ML built it, and the near null space.
     */
    double
    memory_consumption() const override
    {
      return hierarchy_bytes + modes.size() * sizeof(double);
    }

    bool
    memory_measured() const override
    {
      return true;
    }

  private:
    /** The near null space, column-major over the owned rows. */
    std::vector<double>                       modes;
    dealii::TrilinosWrappers::PreconditionAMG amg;
    double                                    hierarchy_bytes = 0;
  };

  /**
   * The rigid-body modes of the mesh at the locally owned DoFs of the vector
   * field: dim translations, then the rotations (1 in 2D; about the x, y and
   * z axes in 3D), column-major, one column of locally_owned.n_elements()
   * entries per mode. If @p coordinates is given, it receives the coordinate
   * of each owned DoF's node in that DoF's own direction (what PETSc's
   * MatNullSpaceCreateRigidBody wants for a Q1 field, whose DoFs are
   * numbered node by node).
   */
  template <int dim>
  std::vector<double>
  rigid_body_modes(const Discretization<dim> &discretization,
                   std::vector<double>       *coordinates = nullptr);

  /** The same for the DoFs of @p dof_handler (a multigrid level). */
  template <int dim>
  std::vector<double>
  rigid_body_modes(const dealii::Mapping<dim>    &mapping,
                   const dealii::DoFHandler<dim> &dof_handler,
                   std::vector<double>           *coordinates = nullptr);

  /**
   * The Trilinos Amesos package of Solver/Direct solver package ('auto':
   * MUMPS, where bulk_factorization() does not choose CHOLMOD).
   */
  inline std::string
  amesos_package(const Parameters::Solver &parameters)
  {
    return parameters.direct_solver_package == "auto" ?
             std::string("Amesos_Mumps") :
             parameters.direct_solver_package;
  }


  /**
   * Solves with one (symmetric positive definite) matrix, many times: a
   * sparse direct factorization made once, or CG with algebraic multigrid
   * built once. How it factorizes is bulk_factorization()'s choice
   * (bulk_factorization.h): a supernodal Cholesky factorization (SuiteSparse
   * CHOLMOD) on one process, or of the whole matrix on every process of
   * several, else Trilinos Amesos (MUMPS or KLU) over the processes. Unlike
   * deal.II's TrilinosWrappers::SolverDirect it solves blocks of
   * right-hand sides in one call, which a direct solver does at the speed
   * of dense matrix products rather than one triangular solve after the
   * other.
   */
  class BulkSolver
  {
  public:
    /** A sparse right-hand side: (global row, value) pairs. */
    using SparseColumn =
      std::vector<std::pair<dealii::types::global_dof_index, double>>;

    explicit BulkSolver(const Parameters::Solver &parameters);
    ~BulkSolver();

    /**
     * Factorize @p matrix (or build the AMG preconditioner on the mesh of
     * @p discretization). The matrix must outlive the solver. With the
     * Cholesky factorization, the rows @p trailing_rows (distinct) are
     * eliminated last, so that inverse_block() can give the block of the
     * inverse at them, unless that would more than double the factor (then
     * inverse_block() returns false); the other solvers ignore them.
     */
    template <int dim>
    void
    initialize(
      const Matrix_t                                     &matrix,
      const Discretization<dim>                          &discretization,
      const std::vector<dealii::types::global_dof_index> &trailing_rows = {});

    /** x = A^{-1} b. */
    void
    solve(const Vector_t &b, Vector_t &x);

    /**
     * x_c = A^{-1} b_c for several right-hand sides: with a Cholesky factor
     * in one pass over it (the solve reads the factor from memory once for
     * all of them), else one after the other.
     */
    void
    solve(const std::vector<const Vector_t *> &b,
          const std::vector<Vector_t *>       &x);

    /**
     * Solve A X = B for the columns of B and return, for each column c,
     * the entries of X at @p rows (rows owned by this process):
     * values[c][i] = X(rows[i], c). If @p store is given, it is called with
     * each column's index and its owned entries (in the order of the owned
     * rows). The columns are solved in blocks of @p block (bounding the
     * memory); a block's round-off depends on its composition. Collective;
     * every process passes the same columns (each sets the entries it
     * owns).
     */
    void
    solve_columns(
      const std::vector<SparseColumn>                         &columns,
      const std::vector<dealii::types::global_dof_index>      &rows,
      std::vector<std::vector<double>>                        &values,
      const std::function<void(unsigned int, const double *)> &store = {},
      const unsigned int                                       block = 64);

    /**
     * The block of A^{-1} at the trailing rows of initialize(), in their
     * order, column-major in @p inverse (m^2 entries for m rows), the
     * inverse of their Schur complement, O(m^3) dense work instead of m
     * solves: with the Cholesky factorization from the trailing block of
     * the factor; with MUMPS (several processes) from a distributed
     * factorization of its own that returns the Schur complement (if its
     * m^2 entries fit in schur_budget bytes, and if it agrees with a solve
     * to a tenth of the Newton tolerance). Collective; the block on every
     * process, or with the Cholesky factor on process 0 alone if not
     * @p on_every_process (MUMPS gives it everywhere). False without
     * trailing rows, with AMG, if MUMPS fails or the check does not pass
     * (and then for this factorization without trying again).
     */
    bool
    inverse_block(std::vector<double> &inverse,
                  const bool           on_every_process = true);

    /**
     * About how many numbers a solve with one right-hand side reads (the
     * factor twice, forward and backward): what decides whether a sum of
     * stored solutions is cheaper than a solve. Infinite where unknown
     * (MUMPS, AMG).
     */
    double
    solve_cost() const;

    /**
     * What the factorization (or the AMG) of the last initialize() holds
     * on this process, as an item named @p name plus the method.
     */
    void
    memory_consumption(const std::string &name, MemoryItems &items) const;

  private:
    const Parameters::Solver parameters;
    const Matrix_t          *matrix = nullptr;

    /**
     * The trailing rows of initialize() (Amesos only; emptied when the
     * Schur complement could not serve).
     */
    std::vector<dealii::types::global_dof_index> schur_rows;
    static constexpr std::size_t schur_budget = std::size_t(1) << 30;

    std::unique_ptr<Epetra_LinearProblem> problem;
    std::unique_ptr<Amesos_BaseSolver>    direct;
    std::unique_ptr<BulkPreconditioner>   amg;
    /** The CHOLMOD factorization (of the whole matrix on every process). */
    std::unique_ptr<Cholesky> cholesky;
    /**
     * The largest growth of the heap in use measured while a
     * factorization was made (a refactorization that frees the factor it
     * replaces measures only the difference).
     */
    double factorization_bytes = 0;
  };
} // namespace DynamicContact

#endif
