#ifndef dynamic_contact_mixed_precision_lu_h
#define dynamic_contact_mixed_precision_lu_h

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/lapack_support.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * Solves with a dense matrix A (the condensed solver's reduced Newton
   * system, kept in double) by an LU factorization in single precision of
   * the equilibrated matrix R A S (R, S diagonal: rows, then columns scaled
   * to a largest entry of 1) and iterative refinement in double, as
   * LAPACK's dsgesv does: the factorization, O(n^3), runs at about twice
   * the speed of double; each sweep of the refinement is O(n^2). The sweeps
   * stop when the residual of the equilibrated system is at the round-off
   * of the double matrix, |R (b - A x)| <= sqrt(n) eps |R A S| |S^{-1} x|
   * (infinity norms; in unscaled norms the rows of the condensed solver's
   * spring nodes, 1e7 times the others, would hide the rest). If that takes
   * more than 10 sweeps or the correction stops shrinking (single
   * precision cannot resolve the matrix), A is factorized in double after
   * all and the solve done with that. Either way the answer is that of a
   * solve in double, to round-off.
   *
   * Matrices of fewer than @p min_size rows are factorized in double: the
   * sweeps cost about what single precision saves (the paper's scene, at
   * most 2 x 127 unknowns: no faster; the 3D rail 80 x 8 x 8, 600 to 1050
   * unknowns: the condensed solver's boundary iteration faster).
   */
  class MixedPrecisionLU
  {
  public:
    /** Factorize @p A, which must outlive this object and not change. */
    explicit MixedPrecisionLU(const LAPACKFullMatrix<double> &A,
                              const unsigned int              min_size = 512);

    /** x = A^{-1} x. */
    void
    solve(Vector<double> &x);

    /**
     * Solve with @p B from now on (same size, outliving this object): the
     * factorization of the matrix before serves as the refinement's
     * preconditioner while the refinement converges with it to B's
     * round-off (B close to the old matrix: a chord method whose answer
     * is still that of a solve with B); at the first solve where it does
     * not, B is factorized afresh. A factorization in double (small
     * matrices) is always made afresh.
     */
    void
    reuse_for(const LAPACKFullMatrix<double> &B);

    /**
     * The number of solves made with the factorization of an earlier
     * matrix (after reuse_for(), without factorizing afresh).
     */
    unsigned int
    stale_solves() const
    {
      return n_stale_solves;
    }

    /** A is (now) factorized in double, not in single precision. */
    bool
    in_double_precision() const
    {
      return in_double;
    }

    /** The bytes of the factor and its scalings. */
    double
    memory_consumption() const
    {
      return lu.size() * sizeof(float) +
             (row_scale.size() + column_scale.size()) * sizeof(double);
    }

  private:
    const LAPACKFullMatrix<double> *A;
    const types::blas_int           n;
    const unsigned int              min_size;
    bool                            stale          = false;
    unsigned int                    n_stale_solves = 0;
    std::vector<double>             row_scale, column_scale;
    /** |R A S| (largest row sum). */
    double                       norm = 0;
    std::vector<float>           lu;
    std::vector<types::blas_int> pivots;
    bool                         in_double = false;
    LAPACKFullMatrix<double>     double_lu;

    void
    factorize_in_double();

    /** Equilibrate and factorize *A (in single precision if large). */
    void
    factorize();

    /** The refinement sweeps; false if they did not converge. */
    bool
    refine(const Vector<double> &b, Vector<double> &x);
  };
} // namespace DynamicContact

#endif
