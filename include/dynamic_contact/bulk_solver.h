#ifndef dynamic_contact_bulk_solver_h
#define dynamic_contact_bulk_solver_h

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/parameters.h>

#include <memory>
#include <utility>
#include <vector>

class Amesos_BaseSolver;
class Epetra_LinearProblem;

namespace DynamicContact
{
  /**
   * The algebraic multigrid settings for the bulk matrix K0 (elliptic, two
   * smoother sweeps, aggregation threshold 0.02, the rigid-body
   * @p constant_modes): one place for both Newton implementations.
   */
  TrilinosWrappers::PreconditionAMG::AdditionalData
  bulk_amg_data(const std::vector<std::vector<bool>> &constant_modes,
                const bool                             higher_order_elements);

  using Vector_t = dealii::TrilinosWrappers::MPI::Vector;
  using Matrix_t = dealii::TrilinosWrappers::SparseMatrix;

  /**
   * Solves with one (symmetric positive definite) matrix, many times: a
   * sparse direct factorization (Trilinos Amesos, MUMPS or KLU) made once,
   * or CG with algebraic multigrid built once. Unlike deal.II's
   * TrilinosWrappers::SolverDirect it solves blocks of right-hand sides in
   * one call, which a direct solver does at the speed of dense matrix
   * products rather than one triangular solve after the other.
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
     * Factorize @p matrix (or build the AMG preconditioner, with the
     * @p constant_modes of the problem). The matrix must outlive the solver.
     */
    void
    initialize(const Matrix_t &                        matrix,
               const std::vector<std::vector<bool>> &constant_modes,
               const bool                             higher_order_elements);

    /** x = A^{-1} b. */
    void
    solve(const Vector_t &b, Vector_t &x);

    /**
     * Solve A X = B for the columns of B and return, for each column c,
     * the entries of X at @p rows (rows owned by this process):
     * values[c][i] = X(rows[i], c). Collective; every process passes the
     * same columns (each sets the entries it owns).
     */
    void
    solve_columns(const std::vector<SparseColumn> &                columns,
                  const std::vector<dealii::types::global_dof_index> &rows,
                  std::vector<std::vector<double>> &                values);

  private:
    const Parameters::Solver parameters;
    const Matrix_t *         matrix = nullptr;

    std::unique_ptr<Epetra_LinearProblem>                    problem;
    std::unique_ptr<Amesos_BaseSolver>                       direct;
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
  };
} // namespace DynamicContact

#endif
