#ifndef dynamic_contact_largest_eigenvalue_h
#define dynamic_contact_largest_eigenvalue_h

#include <deal.II/base/tensor.h>

#include <dynamic_contact/contact/contact_boundary.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace DynamicContact
{
  /**
   * The largest eigenvalue of a symmetric positive semidefinite operator
   * A by the Lanczos iteration (with full reorthogonalization) from the
   * vector @p start: the largest Ritz value, once it changes by less than
   * @p tolerance (relative) from one step to the next, the Krylov space is
   * exhausted, or @p max_steps steps are taken. A Ritz value is never above
   * the largest eigenvalue, and the largest converges first and fast: the
   * uniqueness measures of a step (doc/theory.md section 5.2) need a few
   * digits, but to the default tolerance they are the same whatever the
   * number of processes (a run resumed on another number of processes
   * repeats them).
   *
   * @p apply(x, y) sets y = A x. The vectors may be distributed over the
   * processes: @p sum turns a process's part of a dot product into the
   * whole (the identity where every process holds all of it). Returns 0 if
   * @p start or A start is zero. Where @p ritz_vector is given, it is set
   * to the Ritz vector of the value returned (unit length; this process's
   * part).
   */
  double
  largest_eigenvalue(const std::function<void(const std::vector<double> &,
                                              std::vector<double> &)> &apply,
                     const std::vector<double>                        &start,
                     const std::function<double(double)>              &sum,
                     const double         tolerance   = 1e-10,
                     const unsigned int   max_steps   = 60,
                     std::vector<double> *ritz_vector = nullptr);


  /**
   * An upper bound of the largest eigenvalue of a symmetric matrix A, from
   * the matrix |A| of its entries' magnitudes (Collatz and Wielandt): for
   * every x with positive entries, lambda_max(A) <= rho(|A|) <= max_i
   * (|A| x)_i / x_i. The bound is the smallest over the vectors @p x (each
   * with positive entries); @p apply_abs(xs, ys) sets ys[v] = |A| xs[v]
   * for all of them at once. The Lanczos value of largest_eigenvalue() is a
   * lower estimate; this is what certifies it from above (the uniqueness
   * bound of doc/theory.md section 5.2). Where A's entries are mostly of one
   * sign, an x near the Ritz vector's magnitudes makes it tight; x = 1
   * gives the largest absolute row sum.
   */
  double
  collatz_upper_bound(
    const std::function<void(const std::vector<std::vector<double>> &,
                             std::vector<std::vector<double>> &)> &apply_abs,
    const std::vector<std::vector<double>>                        &x);


  /**
   * A largest eigenvalue as the Lanczos iteration estimates it, and an
   * upper bound of it where one was computed (-1 where not).
   */
  struct SpectralEstimate
  {
    double lanczos = 0;
    double upper   = -1;
  };


  /** Node @p i's entries of a vector of dim entries per node. */
  template <int dim>
  dealii::Tensor<1, dim>
  nodal_entries(const std::vector<double> &x, const unsigned int i)
  {
    dealii::Tensor<1, dim> v;
    for (unsigned int c = 0; c < dim; ++c)
      v[c] = x[dim * i + c];
    return v;
  }

  /** Set node @p i's entries of a vector of dim entries per node. */
  template <int dim>
  void
  set_nodal_entries(const dealii::Tensor<1, dim> &v,
                    const unsigned int            i,
                    std::vector<double>          &x)
  {
    for (unsigned int c = 0; c < dim; ++c)
      x[dim * i + c] = v[c];
  }

  /**
   * The start of the Lanczos iteration at a node: its first tangent plus
   * half a unit tangent at a pseudo-random angle that depends on the
   * node's first DoF only (the same whatever the processes and the order
   * of the nodes), so that no eigenvector of interest is orthogonal to it.
   */
  template <int dim>
  dealii::Tensor<1, dim>
  lanczos_start(const ContactNode<dim> &node)
  {
    std::uint64_t z = node.dofs[0] * 0x9E3779B97F4A7C15ull + 1;
    z               = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z               = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    const double angle = 6.283185307179586 * (z >> 11) * 0x1.0p-53;
    dealii::Tensor<1, dim> r = node.tangents[0] * (1 + 0.5 * std::cos(angle));
    if (dim == 3)
      r += (0.5 * std::sin(angle)) * node.tangents[dim - 2];
    return r;
  }
} // namespace DynamicContact

#endif
