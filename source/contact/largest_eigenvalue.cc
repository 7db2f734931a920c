#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/contact/largest_eigenvalue.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  namespace
  {
    /** The largest eigenvalue of the symmetric tridiagonal (alpha, beta). */
    double
    largest_ritz_value(const std::vector<double> &alpha,
                       const std::vector<double> &beta)
    {
      const unsigned int                m = alpha.size();
      dealii::LAPACKFullMatrix<double> T(m, m);
      for (unsigned int i = 0; i < m; ++i)
        {
          T(i, i) = alpha[i];
          if (i + 1 < m)
            T(i, i + 1) = T(i + 1, i) = beta[i];
        }
      dealii::Vector<double>    values;
      dealii::FullMatrix<double> vectors;
      T.compute_eigenvalues_symmetric(-1e300, 1e300, 0., values, vectors);
      double largest = 0;
      for (unsigned int i = 0; i < values.size(); ++i)
        largest = std::max(largest, values(i));
      return largest;
    }
  } // namespace


  double
  largest_eigenvalue(
    const std::function<void(const std::vector<double> &,
                             std::vector<double> &)> &apply,
    const std::vector<double>                        &start,
    const std::function<double(double)>              &sum,
    const double                                      tolerance,
    const unsigned int                                max_steps)
  {
    const std::size_t n   = start.size();
    const auto        dot = [&](const std::vector<double> &a,
                         const std::vector<double> &b) {
      double local = 0;
      for (std::size_t i = 0; i < n; ++i)
        local += a[i] * b[i];
      return sum(local);
    };
    const double norm = std::sqrt(dot(start, start));
    if (!(norm > 0))
      return 0;

    std::vector<std::vector<double>> Q;
    std::vector<double>              alpha, beta, q(start), r(n);
    for (auto &v : q)
      v /= norm;
    double estimate = 0;
    for (unsigned int step = 0; step < max_steps; ++step)
      {
        apply(q, r);
        Q.push_back(q);
        alpha.push_back(dot(q, r));
        // r -= alpha q + beta q_prev, then again against every basis
        // vector (full reorthogonalization: a few dozen vectors at most).
        for (int pass = 0; pass < 2; ++pass)
          for (const auto &v : Q)
            {
              const double c = dot(v, r);
              for (std::size_t i = 0; i < n; ++i)
                r[i] -= c * v[i];
            }
        const double b         = std::sqrt(dot(r, r));
        const double new_value = largest_ritz_value(alpha, beta);
        const bool   exhausted = !(b > 1e-12 * std::abs(new_value));
        if (step > 0 &&
            std::abs(new_value - estimate) <= tolerance * std::abs(new_value))
          return new_value;
        estimate = new_value;
        if (exhausted)
          return estimate;
        beta.push_back(b);
        for (std::size_t i = 0; i < n; ++i)
          q[i] = r[i] / b;
      }
    return estimate;
  }
} // namespace DynamicContact
