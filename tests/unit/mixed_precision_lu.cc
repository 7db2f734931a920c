// MixedPrecisionLU, the condensed solver's solve of its reduced Newton
// systems: single-precision LU of the equilibrated matrix with refinement in
// double. Against LAPACK's double LU on (a) a 600 x 600 system with rows
// 1e7 times the others (the spring nodes' rows), which the mixed path must
// solve to double round-off, (b) a system single precision cannot resolve
// (1 + 1e-9 on the diagonal of a matrix of ones: it falls back to double
// and still agrees), (c) a matrix below the size where single precision
// pays (factorized in double), (d) an empty one, and (e) the factorization
// kept for a nearby matrix (reuse_for(): the next Newton iteration's) and
// replaced for an unrelated one.

#include <dynamic_contact/contact/mixed_precision_lu.h>

#include <random>

#include "test_tools.h"

using namespace DynamicContact;
using test_tools::check;

namespace
{
  /** max_i |x_i - y_i| / max_i |y_i|. */
  double
  relative_difference(const Vector<double> &x, const Vector<double> &y)
  {
    Vector<double> d = x;
    d -= y;
    return d.linfty_norm() / y.linfty_norm();
  }

  /** x from LAPACK's LU in double. */
  Vector<double>
  double_solve(const LAPACKFullMatrix<double> &A, const Vector<double> &b)
  {
    LAPACKFullMatrix<double> lu = A;
    lu.compute_lu_factorization();
    Vector<double> x = b;
    lu.solve(x);
    return x;
  }

  /**
   * x from MixedPrecisionLU; @p in_double: whether it factorized in double
   * (small, or the fallback).
   */
  Vector<double>
  mixed_solve(const LAPACKFullMatrix<double> &A,
              const Vector<double>           &b,
              bool                           &in_double)
  {
    MixedPrecisionLU lu(A);
    Vector<double>   x = b;
    lu.solve(x);
    in_double = lu.in_double_precision();
    return x;
  }

  /** The n x n matrix of entry(i, j), row by row. */
  template <typename Entry>
  LAPACKFullMatrix<double>
  matrix_of(const unsigned int n, const Entry &entry)
  {
    LAPACKFullMatrix<double> A(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        A(i, j) = entry(i, j);
    return A;
  }

  Vector<double>
  random_vector(const unsigned int n, std::mt19937 &random)
  {
    std::uniform_real_distribution<double> u(-1, 1);
    Vector<double>                         v(n);
    for (unsigned int i = 0; i < n; ++i)
      v[i] = u(random);
    return v;
  }

  using Uniform = std::uniform_real_distribution<double>;

  /**
   * (e) The factorization @p lu of @p A kept for a nearby matrix (the next
   * Newton iteration's: every entry off by up to 1e-3 relative) ...
   */
  void
  check_reuse(MixedPrecisionLU               &lu,
              const LAPACKFullMatrix<double> &A,
              const Vector<double>           &b,
              std::mt19937                   &random,
              Uniform                        &u)
  {
    const unsigned int       n    = A.m();
    LAPACKFullMatrix<double> near = A;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        near(i, j) *= 1. + 1e-3 * u(random);
    lu.reuse_for(near);
    Vector<double> x3 = b;
    lu.solve(x3);
    check(lu.stale_solves() == 1,
          "a matrix within 1e-3 of A: solved with A's factorization");
    check(relative_difference(x3, double_solve(near, b)) < 1e-12,
          "a matrix within 1e-3 of A: agrees with LAPACK's double LU of it "
          "to 1e-12");
    // ... and for one it does not resolve: factorized afresh.
    const LAPACKFullMatrix<double> far =
      matrix_of(n, [&](const unsigned int i, const unsigned int j) {
        return (i == j ? 1. : 0.) + 2. * u(random) / std::sqrt(double(n));
      });
    lu.reuse_for(far);
    Vector<double> x4 = b;
    lu.solve(x4);
    check(lu.stale_solves() == 1 && !lu.in_double_precision(),
          "an unrelated matrix: factorized afresh (in single precision)");
    check(relative_difference(x4, double_solve(far, b)) < 1e-12,
          "an unrelated matrix: agrees with LAPACK's double LU of it to "
          "1e-12");
  }

  /**
   * (a) A nonsymmetric system like the reduced Newton systems: identity
   * plus a coupling, the first 9 rows 1e7 times larger; then (e).
   */
  void
  check_scaled_rows(std::mt19937 &random, Uniform &u)
  {
    const unsigned int       n = 600;
    LAPACKFullMatrix<double> A =
      matrix_of(n, [&](const unsigned int i, const unsigned int j) {
        return (i == j ? 1. : 0.) + 0.5 * u(random) / std::sqrt(double(n));
      });
    for (unsigned int i = 0; i < 9; ++i)
      for (unsigned int j = 0; j < n; ++j)
        A(i, j) *= 1e7;
    const Vector<double> b = random_vector(n, random);
    MixedPrecisionLU     lu(A);
    Vector<double>       x = b;
    lu.solve(x);
    check(!lu.in_double_precision(),
          "600 x 600 with rows of 1e7: solved in single precision with "
          "refinement");
    check(relative_difference(x, double_solve(A, b)) < 1e-12,
          "600 x 600 with rows of 1e7: agrees with LAPACK's double LU to "
          "1e-12");
    // A second right-hand side with the same factorization.
    const Vector<double> b2 = random_vector(n, random);
    Vector<double>       x2 = b2;
    lu.solve(x2);
    check(relative_difference(x2, double_solve(A, b2)) < 1e-12,
          "a second right-hand side: agrees to 1e-12");
    check_reuse(lu, A, b, random, u);
  }

  /**
   * (b) Ones plus 1e-9 on the diagonal: 1 + 1e-9 is 1 in single precision,
   * so the float factorization cannot resolve the matrix.
   */
  void
  check_unresolved(std::mt19937 &random)
  {
    const unsigned int             n = 600;
    const LAPACKFullMatrix<double> A =
      matrix_of(n, [](const unsigned int i, const unsigned int j) {
        return 1. + (i == j ? 1e-9 : 0.);
      });
    const Vector<double> b = random_vector(n, random);
    bool                 in_double;
    const Vector<double> x = mixed_solve(A, b, in_double);
    check(in_double, "ones + 1e-9 I: falls back to LU in double");
    check(relative_difference(x, double_solve(A, b)) < 1e-12,
          "ones + 1e-9 I: agrees with LAPACK's double LU to 1e-12");
  }

  /** (c) Below the size where single precision pays. */
  void
  check_small(std::mt19937 &random, Uniform &u)
  {
    const unsigned int             n = 100;
    const LAPACKFullMatrix<double> A =
      matrix_of(n, [&](const unsigned int i, const unsigned int j) {
        return (i == j ? 2. : 0.) + u(random) / n;
      });
    const Vector<double> b = random_vector(n, random);
    bool                 in_double;
    const Vector<double> x = mixed_solve(A, b, in_double);
    check(in_double, "100 x 100: factorized in double");
    check(relative_difference(x, double_solve(A, b)) == 0,
          "100 x 100: the same answer as LAPACK's double LU");
  }

  /** (d) No unknowns (no active node). */
  void
  check_empty()
  {
    LAPACKFullMatrix<double> A(0, 0);
    MixedPrecisionLU         lu(A);
    Vector<double>           x;
    lu.solve(x);
    check(x.size() == 0, "0 x 0: nothing to solve");
  }
} // namespace

int
main()
{
  std::mt19937                           random(42);
  std::uniform_real_distribution<double> u(-1, 1);
  check_scaled_rows(random, u);
  check_unresolved(random);
  check_small(random, u);
  check_empty();
}
