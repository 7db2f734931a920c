#include <deal.II/lac/lapack_templates.h>

#include <dynamic_contact/contact/mixed_precision_lu.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace DynamicContact
{
  MixedPrecisionLU::MixedPrecisionLU(const LAPACKFullMatrix<double> &A,
                                     const unsigned int              min_size)
    : A(&A)
    , n(A.m())
    , min_size(min_size)
  {
    factorize();
  }


  void
  MixedPrecisionLU::reuse_for(const LAPACKFullMatrix<double> &B)
  {
    Assert(static_cast<types::blas_int>(B.m()) == n, ExcInternalError());
    A     = &B;
    stale = true;
  }


  void
  MixedPrecisionLU::factorize()
  {
    const LAPACKFullMatrix<double> &A = *this->A;
    in_double                         = false;
    stale                             = false;
    if (n < static_cast<types::blas_int>(min_size))
      {
        factorize_in_double();
        return;
      }
    // Column by column (A is stored so): R, then S.
    row_scale.assign(n, 0.);
    column_scale.assign(n, 0.);
    for (types::blas_int j = 0; j < n; ++j)
      for (types::blas_int i = 0; i < n; ++i)
        row_scale[i] = std::max(row_scale[i], std::abs(A(i, j)));
    for (types::blas_int i = 0; i < n; ++i)
      row_scale[i] = row_scale[i] > 0 ? 1. / row_scale[i] : 1.;
    for (types::blas_int j = 0; j < n; ++j)
      {
        for (types::blas_int i = 0; i < n; ++i)
          column_scale[j] =
            std::max(column_scale[j], std::abs(row_scale[i] * A(i, j)));
        column_scale[j] = column_scale[j] > 0 ? 1. / column_scale[j] : 1.;
      }
    lu.resize(std::size_t(n) * n);
    std::vector<double> row_sum(n, 0.);
    for (types::blas_int j = 0; j < n; ++j)
      for (types::blas_int i = 0; i < n; ++i)
        {
          const double a             = row_scale[i] * A(i, j) * column_scale[j];
          lu[i + std::size_t(j) * n] = static_cast<float>(a);
          row_sum[i] += std::abs(a);
        }
    norm = *std::max_element(row_sum.begin(), row_sum.end());
    pivots.resize(n);
    types::blas_int info = 0;
    getrf(&n, &n, lu.data(), &n, pivots.data(), &info);
    if (info != 0)
      factorize_in_double();
  }


  void
  MixedPrecisionLU::solve(Vector<double> &x)
  {
    if (n == 0)
      return;
    const Vector<double> b = x;
    // The factorization of an earlier matrix (reuse_for()) first.
    if (stale && !in_double && refine(b, x))
      {
        ++n_stale_solves;
        return;
      }
    if (stale)
      factorize(); // A's own
    if (!in_double)
      {
        if (refine(b, x))
          return;
        // Single precision cannot resolve A: in double.
        factorize_in_double();
      }
    x = b;
    double_lu.solve(x);
  }


  bool
  MixedPrecisionLU::refine(const Vector<double> &b, Vector<double> &x)
  {
    const LAPACKFullMatrix<double> &A        = *this->A;
    Vector<double>                  residual = b, product(n);
    std::vector<float>              d(n);
    x                        = 0;
    double       last_change = std::numeric_limits<double>::max();
    const double epsilon     = std::numeric_limits<double>::epsilon();
    for (unsigned int sweep = 0; sweep < 10; ++sweep)
      {
        // The correction from the equilibrated system (R A S) d = R r.
        for (types::blas_int i = 0; i < n; ++i)
          d[i] = static_cast<float>(row_scale[i] * residual[i]);
        types::blas_int one = 1, info = 0;
        getrs("N", &n, &one, lu.data(), &n, pivots.data(), d.data(), &n, &info);
        double change = 0, scaled_x = 0, scaled_residual = 0;
        for (types::blas_int i = 0; i < n; ++i)
          {
            x[i] += column_scale[i] * d[i];
            change   = std::max(change, std::abs(double(d[i])));
            scaled_x = std::max(scaled_x, std::abs(x[i] / column_scale[i]));
          }
        A.vmult(product, x);
        residual = b;
        residual -= product;
        for (types::blas_int i = 0; i < n; ++i)
          scaled_residual =
            std::max(scaled_residual, std::abs(row_scale[i] * residual[i]));
        if (scaled_residual <= std::sqrt(double(n)) * epsilon * norm * scaled_x)
          return true;
        if (!(change < 0.5 * last_change))
          break;
        last_change = change;
      }
    return false;
  }


  void
  MixedPrecisionLU::factorize_in_double()
  {
    double_lu = *A;
    if (n > 0)
      double_lu.compute_lu_factorization();
    in_double = true;
  }
} // namespace DynamicContact
