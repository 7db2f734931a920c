#ifndef dynamic_contact_cholesky_h
#define dynamic_contact_cholesky_h

#include <deal.II/base/mpi.h>

#include <suitesparse/cholmod.h>

#include <Epetra_CrsMatrix.h>

#include <cstddef>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * K0 factorized by CHOLMOD (supernodal Cholesky, fill-reducing ordering
   * of its choice), on one process. The analysis (ordering and symbolic
   * factorization) is kept while the sparsity pattern is unchanged, so a
   * new time step costs the numeric factorization only.
   *
   * Given a set of trailing rows (the DoFs of Gamma_3), the rows are
   * eliminated in CHOLMOD's fill-reducing order with these rows moved to
   * the end, in the order given. The trailing block L_22 of the factor is
   * then the Cholesky factor of the Schur complement S = A_22 - A_21
   * A_11^{-1} A_12, and the block of A^{-1} at these rows is S^{-1} =
   * L_22^{-T} L_22^{-1} (inverse_block()): the same factor the solves use,
   * so the two agree to round-off. This order is taken only while it at
   * most doubles the entries of the factor (see analyze_with_trailing_rows()).
   */
  class Cholesky
  {
  public:
    explicit Cholesky(const MPI_Comm comm);

    ~Cholesky();

    Cholesky(const Cholesky &) = delete;
    Cholesky &
    operator=(const Cholesky &) = delete;

    /**
     * Factorize @p A, with the rows @p trailing (global indices, distinct)
     * last if there are any. On several processes every process gathers
     * the whole matrix and factorizes it (collective).
     */
    void
    factorize(const Epetra_CrsMatrix              &A,
              const std::vector<SuiteSparse_long> &trailing);

    /** The factorization is repeated on every process of several. */
    bool
    replicated() const;

    /**
     * X = A^{-1} B for @p n_columns columns given by their owned entries,
     * @p n_owned per column, column-major (B and X may not overlap). On
     * several processes each column is gathered whole, solved and its
     * owned entries kept.
     */
    void
    solve_owned(const double      *B,
                double            *X,
                const unsigned int n_columns,
                const std::size_t  n_owned);

    /** The owned entries (in the order of the owned rows) of @p whole. */
    void
    owned_part(const double *whole, double *owned) const;

    /**
     * X = A^{-1} B for @p n_columns dense columns of length n, column-major
     * (B and X may not overlap).
     */
    void
    solve(const double *B, double *X, const unsigned int n_columns);

    /**
     * The factor has the trailing rows given to factorize() last (unless
     * that grew it more than max_growth times).
     */
    bool
    has_trailing_rows() const;

    /** The number of entries of the factor. */
    double
    factor_entries() const;

    /**
     * The block of A^{-1} at the trailing rows given to factorize(), in
     * their order, column-major in @p inverse (m x m): S^{-1} by the two
     * triangular solves with L_22 for the identity (LAPACK potrs; an
     * explicit inverse by potri is as fast but was not what a solve with
     * the factor gives: its compliance left stick nodes of the
     * critical-speed stress scene less accurate). Computed by process 0;
     * with the factor on every process, collective, and the block then on
     * every process, or on process 0 alone if not @p on_every_process
     * (the others get an empty vector).
     */
    void
    inverse_block(std::vector<double> &inverse,
                  const bool           on_every_process = true) const;

  private:
    const MPI_Comm     comm;
    const unsigned int n_processes, rank;
    /**
     * The global rows in the order of an MPI_Allgatherv of every process's
     * owned entries (counts and displacements per process), and whether
     * that order is the global one.
     */
    std::vector<SuiteSparse_long> gathered_rows;
    std::vector<int>              counts, displacements;
    bool                          in_order = true;
    /** Work space of gather() and solve_owned() (kept between solves). */
    std::vector<double> gather_buffer, whole_B, whole_X;

    cholmod_common                common;
    cholmod_factor               *factor = nullptr;
    cholmod_dense                *x = nullptr, *y = nullptr, *e = nullptr;
    std::vector<SuiteSparse_long> pattern_start, pattern_index;
    std::vector<double>           values;
    std::vector<SuiteSparse_long> trailing_rows;
    /** The factor has the trailing rows last (see factorize()). */
    bool trailing_used = false;
    /** The most the trailing rows may grow the factor by. */
    static constexpr double max_growth = 2;

    /**
     * Replace the analysis just made (CHOLMOD's fill-reducing order) by one
     * in that order with the trailing rows moved to the end: the order
     * given as it is (no postordering, which could move rows of the block
     * that nothing couples to the others, such as constrained ones, away
     * from the end), supernodal, so that the trailing block of the factor
     * can be read (inverse_block()).
     */
    void
    analyze_with_trailing_rows(cholmod_sparse &S);

    /** The whole vector from every process's owned entries (collective). */
    void
    gather(const double *owned, double *whole);

    void
    free_workspace();
  };
} // namespace DynamicContact

#endif
