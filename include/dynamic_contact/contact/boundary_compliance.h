#ifndef dynamic_contact_boundary_compliance_h
#define dynamic_contact_boundary_compliance_h

#include <dynamic_contact/base/leading_process.h>
#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/contact/compliance_measures.h>
#include <dynamic_contact/contact/compliance_springs.h>
#include <dynamic_contact/contact/compliance_table.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>

#include <functional>
#include <vector>

namespace DynamicContact
{
  /**
   * The compliance (Delassus) matrix of Gamma_3, the first part of the
   * condensed solver (CondensedSolver): with K0 factorized, the velocity
   * a force f_j at node j causes at node i is C_ij f_j, C_ij = P_i
   * [K0'^{-1}]_ij P_j^T, and everything off Gamma_3 is linear.
   *
   * What is factorized is K0' = K0 + S, S stiff springs (s I, s the largest
   * diagonal entry of K0 there) at two (2D) or three (3D) extreme nodes of
   * Gamma_3: a body held only by the foundation has rigid motions that K0
   * restrains by inertia alone, and K0 is then too ill-conditioned for the
   * condensation to reach a tight tolerance. The springs are removed again
   * exactly: their nodes enter the dense system with the force f - S w and
   * the block B - S (spring_stiffness()), and apply_k0() gives the
   * compliance of K0 itself by the Woodbury identity.
   *
   * With a CHOLMOD factor (one process, or the whole factor on every
   * process) C is the inverse of the Schur complement of K0' on Gamma_3,
   * all of it at once (the factorization eliminates the DoFs of Gamma_3
   * last: BulkSolver::inverse_block()); with MUMPS in 3D likewise from
   * MUMPS's Schur complement where it agrees with the solves; else the
   * columns of C are computed when a node first becomes active (dim solves
   * with the factorized K0 each). C is kept while K0 is unchanged.
   *
   * The tables are over the nodes of GatheredBoundary, in its order. C is
   * held by rank 0 of the contact boundary's processes alone, which does
   * the dense work with it (on_leader(): the condensed solver's dense
   * iterations, the uniqueness measure, the weakening limits); the other
   * processes compute its columns with it and know which exist.
   *
   * It owns K0' and its factorization, and asks for the columns; its parts
   * are the table of C and the whole responses (ComplianceTable), the
   * springs and their Woodbury correction (ComplianceSprings), and what is
   * measured from the compliance of K0 (ComplianceMeasures).
   */
  template <int dim>
  class BoundaryCompliance
  {
  public:
    using Result = ContactSolveResult;

    BoundaryCompliance(const ContactProblem<dim>   &problem,
                       const GatheredBoundary<dim> &gathered)
      : problem(problem)
      , gathered(gathered)
      , bulk_solver(problem.parameters)
      , table(problem, gathered)
      , stiff_springs(problem, gathered)
      , measures(*this)
    {}

    /** After GatheredBoundary::reinit() (collective). */
    void
    reinit();

    /**
     * Factorize K0' (or build AMG) if K0 changed, and forget C if so;
     * true if it did (collective).
     */
    bool
    prepare(Result &result);

    /** x = K0'^{-1} b. */
    void
    solve(const Vector_t &b, Vector_t &x, Result &result);

    /** x_c = K0'^{-1} b_c, in one block solve where that is cheaper. */
    void
    solve(const std::vector<const Vector_t *> &b,
          const std::vector<Vector_t *>       &x,
          Result                              &result);

    /**
     * Make sure C_:j exists for every j of @p nodes (one block solve).
     * Collective, but inside on_leader() on rank 0 alone (it then asks the
     * others to compute the columns with it).
     */
    void
    compute_columns(const std::vector<unsigned int> &nodes, Result &result);

    /** Whether C_:j exists for every j of @p nodes. */
    bool
    has_columns(const std::vector<unsigned int> &nodes) const
    {
      return table.has_columns(nodes);
    }

    /**
     * Collective: @p work, which uses C, on rank 0 alone (LeadingProcess);
     * the others compute the columns it asks for with it. A failure of the
     * work is thrown on every process. What the work found, the caller
     * sends to the others (LeadingProcess::share()).
     */
    void
    on_leader(Result &result, const std::function<void()> &work);

    /**
     * Collective: rank 0's @p value (a number, or a vector of numbers or
     * tensors) on every process, after on_leader().
     */
    template <typename T>
    void
    share(T &value) const
    {
      LeadingProcess(problem.boundary.get_mpi_communicator(), nullptr)
        .share(value);
    }

    /** Whether this process holds C (rank 0). */
    bool
    holds_tables() const;

    /** C_:j, every node (compute_columns() first; rank 0 only). */
    const std::vector<Tensor<2, dim>> &
    column(const unsigned int j) const
    {
      return table.column(j);
    }

    /** The spring's stiffness at every node (0 where there is none). */
    double
    spring_stiffness(const unsigned int i) const
    {
      return stiff_springs.stiffness(i);
    }

    /** w_i -= sum_j C_ij f_j over the nodes @p nodes (rank 0 only). */
    void
    subtract(const std::vector<Tensor<1, dim>> &forces,
             const std::vector<unsigned int>   &nodes,
             std::vector<Tensor<1, dim>>       &w) const;

    /**
     * w_i = w_free,i - sum_j C_ij f_j over the nodes with a force (rank 0
     * only).
     */
    void
    response(const std::vector<Tensor<1, dim>> &w_free,
             const std::vector<Tensor<1, dim>> &forces,
             const std::vector<unsigned int>   &with_force,
             std::vector<Tensor<1, dim>>       &w) const;

    /**
     * x = K0'^{-1} sum_{j in nodes} P_j^T f_j from the stored whole columns;
     * false (and x untouched) if some column is not stored. The same answer
     * on every process.
     */
    bool
    apply_full_columns(const std::vector<Tensor<1, dim>> &f,
                       const std::vector<unsigned int>   &nodes,
                       Vector_t                          &x) const
    {
      return table.apply_full_columns(f, nodes, x);
    }

    /**
     * The compliance of K0 itself (not of K0' = K0 + S) between nodes of
     * Gamma_3: @p v[a] = sum_b [K0^{-1}]_{nodes[a] nodes[b]} @p f[b], from
     * C' = K0'^{-1} (the table) and the springs removed by the Woodbury
     * identity, K0^{-1} = C' + C' P^T (S^{-1} - P C' P^T)^{-1} P C' (P the
     * springs' DoFs): what the uniqueness measures and the weakening limit
     * see, as the assembled solver does. Makes the columns it needs
     * (rank 0 only, inside on_leader() where there are several processes).
     */
    void
    apply_k0(const std::vector<unsigned int>   &nodes,
             const std::vector<Tensor<1, dim>> &f,
             std::vector<Tensor<1, dim>>       &v,
             Result                            &result);

    /**
     * The coupled linearization's limits of every node (WeakeningLimit),
     * measured again if K0 changed (collective).
     */
    const std::vector<double> &
    weakening_limits(Result &result);

    /**
     * The largest eigenvalue of R C R^T over the nodes with a root R_i in
     * @p roots (one per owned node; collective), and where @p certify and
     * the Lanczos value is below 1 an upper bound of it
     * (collatz_upper_bound() over the entries of R C R^T, from C's columns
     * and the Woodbury correction: rigorous to C's round-off).
     */
    SpectralEstimate
    radius(const std::vector<Tensor<2, dim>> &roots, const bool certify);

    /**
     * What it holds on this process: K0' (its values; the pattern is K0's),
     * its factorization, C and the whole responses.
     */
    void
    memory_consumption(MemoryItems &items) const;

  private:
    const ContactProblem<dim>   &problem;
    const GatheredBoundary<dim> &gathered;

    /** K0' = K0 + S, factorized by bulk_solver. */
    Matrix_t   regularized;
    BulkSolver bulk_solver;
    TimeScheme prepared_scheme;

    /** For each node of all_nodes(): its index among the owned nodes, or -1. */
    std::vector<int> owned_index;

    /** C and the whole responses. */
    ComplianceTable<dim> table;
    /** The springs S and their Woodbury correction. */
    ComplianceSprings<dim> stiff_springs;
    /** The weakening limits and the spectral radius. */
    ComplianceMeasures<dim> measures;
    friend class ComplianceMeasures<dim>;

    /** Inside on_leader() on rank 0: compute_columns() asks through it. */
    LeadingProcess *leading = nullptr;
  };
} // namespace DynamicContact

#endif
