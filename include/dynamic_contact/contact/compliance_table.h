#ifndef dynamic_contact_compliance_table_h
#define dynamic_contact_compliance_table_h

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_solver.h>

#include <cstddef>
#include <vector>

namespace DynamicContact
{
  /**
   * The table of BoundaryCompliance: the columns C_:j of the compliance of
   * K0' on Gamma_3 and, beside them while they fit, the whole responses
   * K0'^{-1} P_j^T e_c, and how both are made with the factorized K0' (from
   * the inverse of the Schur complement of Gamma_3, or by dim solves per
   * node). Over the nodes of GatheredBoundary, in its order; C is held by
   * rank 0 of the contact boundary's processes alone
   * (holds_tables()), the other
   * processes compute its columns with it and know which exist. What asks
   * for the columns, and when, is BoundaryCompliance's.
   */
  template <int dim>
  class ComplianceTable
  {
  public:
    using Result = ContactSolveResult;

    ComplianceTable(const ContactProblem<dim>   &problem,
                    const GatheredBoundary<dim> &gathered)
      : problem(problem)
      , gathered(gathered)
    {}

    /** After GatheredBoundary::reinit() (collective): empty tables. */
    void
    reinit();

    /** Forget C and the whole responses (K0' changed). */
    void
    forget();

    /** Whether this process holds C (rank 0). */
    bool
    holds_tables() const;

    /** Whether C_:j exists for every j of @p nodes. */
    bool
    has_columns(const std::vector<unsigned int> &nodes) const
    {
      for (const unsigned int j : nodes)
        if (!made[j])
          return false;
      return true;
    }

    /** C_:j, every node (rank 0 only). */
    const std::vector<Tensor<2, dim>> &
    column(const unsigned int j) const
    {
      return columns[j];
    }

    /**
     * Make C_:j for every j of @p nodes that lacks it, in whole blocks of
     * nodes, with the factorization @p bulk_solver of K0' (collective).
     */
    void
    make(const std::vector<unsigned int> &nodes,
         BulkSolver                      &bulk_solver,
         Result                          &result);

    /** w_i -= sum_j C_ij f_j over the nodes @p nodes (rank 0 only). */
    void
    subtract(const std::vector<Tensor<1, dim>> &forces,
             const std::vector<unsigned int>   &nodes,
             std::vector<Tensor<1, dim>>       &w) const;

    /**
     * x = K0'^{-1} sum_{j in nodes} P_j^T f_j from the stored whole columns;
     * false (and x untouched) if some column is not stored.
     */
    bool
    apply_full_columns(const std::vector<Tensor<1, dim>> &f,
                       const std::vector<unsigned int>   &nodes,
                       Vector_t                          &x) const;

    /** C and the whole responses, as held on this process. */
    void
    memory_consumption(MemoryItems &items) const;

  private:
    const ContactProblem<dim>   &problem;
    const GatheredBoundary<dim> &gathered;

    /**
     * columns[j][i] = C_ij, empty until node j was first active (and on
     * every process but rank 0); made[j]: C_:j exists (every process).
     */
    std::vector<std::vector<Tensor<2, dim>>> columns;
    std::vector<bool>                        made;

    /**
     * The whole responses K0'^{-1} P_j^T e_c (owned entries, index
     * dim j + c), kept beside C while they fit in full_column_budget bytes
     * on every process and a sum of all of them reads fewer numbers than a
     * solve (BulkSolver::solve_cost(): with MUMPS; with a Cholesky factor a
     * solve is as fast or faster): with them a provisional velocity or a
     * whole-system step is a sum of columns instead of a solve with K0'.
     */
    std::vector<std::vector<double>> full_columns;
    std::size_t                      stored_full_columns = 0;
    /**
     * Node j's whole responses are stored (the same on every process: a
     * process that owns no DoF stores empty ones).
     */
    std::vector<bool> full_column_stored;
    /** The largest number of owned DoFs of a process. */
    types::global_dof_index      max_owned_dofs     = 0;
    static constexpr std::size_t full_column_budget = std::size_t(512) << 20;

    /** Columns from BulkSolver::inverse_block(), if it gives them. */
    bool
    columns_from_inverse_block(BulkSolver &bulk_solver);

    /** The columns of @p missing nodes by dim solves each. */
    void
    columns_by_solves(const std::vector<unsigned int> &missing,
                      const unsigned int               block_size,
                      BulkSolver                      &bulk_solver,
                      Result                          &result);
  };
} // namespace DynamicContact

#endif
