#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/contact/largest_eigenvalue.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace DynamicContact
{
  namespace
  {
    /**
     * The largest eigenvalue of the symmetric tridiagonal (alpha, beta),
     * and in @p y its eigenvector where asked.
     */
    double
    largest_ritz_value(const std::vector<double> &alpha,
                       const std::vector<double> &beta,
                       std::vector<double>       *y = nullptr)
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
      double       largest = 0;
      unsigned int which   = 0;
      for (unsigned int i = 0; i < values.size(); ++i)
        if (values(i) > largest)
          {
            largest = values(i);
            which   = i;
          }
      if (y != nullptr)
        {
          y->assign(m, 0.);
          if (values.size() > 0)
            for (unsigned int i = 0; i < m; ++i)
              (*y)[i] = vectors(i, which);
        }
      return largest;
    }
  } // namespace


  double
  largest_eigenvalue(const std::function<void(const std::vector<double> &,
                                              std::vector<double> &)> &apply,
                     const std::vector<double>                        &start,
                     const std::function<double(double)>              &sum,
                     const double         tolerance,
                     const unsigned int   max_steps,
                     std::vector<double> *ritz_vector)
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
    if (ritz_vector != nullptr)
      ritz_vector->assign(n, 0.);
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
        std::vector<double> y;
        const double        new_value =
          largest_ritz_value(alpha, beta, ritz_vector ? &y : nullptr);
        const bool exhausted = !(b > 1e-12 * std::abs(new_value));
        const bool converged = step > 0 && std::abs(new_value - estimate) <=
                                             tolerance * std::abs(new_value);
        estimate = new_value;
        if (ritz_vector != nullptr)
          {
            // The Ritz vector Q y of the basis so far.
            ritz_vector->assign(n, 0.);
            for (std::size_t j = 0; j < Q.size(); ++j)
              for (std::size_t i = 0; i < n; ++i)
                (*ritz_vector)[i] += y[j] * Q[j][i];
          }
        if (converged || exhausted)
          return estimate;
        beta.push_back(b);
        for (std::size_t i = 0; i < n; ++i)
          q[i] = r[i] / b;
      }
    return estimate;
  }


  double
  collatz_upper_bound(
    const std::function<void(const std::vector<std::vector<double>> &,
                             std::vector<std::vector<double>> &)> &apply_abs,
    const std::vector<std::vector<double>>                        &x)
  {
    std::vector<std::vector<double>> y(x.size());
    for (std::size_t v = 0; v < x.size(); ++v)
      y[v].assign(x[v].size(), 0.);
    apply_abs(x, y);
    double bound = std::numeric_limits<double>::infinity();
    for (std::size_t v = 0; v < x.size(); ++v)
      {
        double largest = 0;
        for (std::size_t i = 0; i < x[v].size(); ++i)
          {
            Assert(x[v][i] > 0, dealii::ExcMessage("x must be positive."));
            largest = std::max(largest, y[v][i] / x[v][i]);
          }
        bound = std::min(bound, largest);
      }
    return bound;
  }
} // namespace DynamicContact
