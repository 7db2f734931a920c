#ifndef dynamic_contact_weakening_limit_h
#define dynamic_contact_weakening_limit_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/bulk/linear_algebra.h>

#include <functional>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The safeguard of the coupled linearization (Friction/Linearization =
   * coupled, doc/theory.md section 5.1). Where a node slips near the onset
   * of slip, the weakening -mu'(s) m (p + q) theta of a steep law acts in
   * the Newton matrix like a negative spring along the slip, and one that
   * is stronger than the body's own tangential stiffness at the node makes
   * the step indefinite: Newton then jumps between stick and fast slip.
   * The linearization therefore takes at most a fraction kappa of the
   * node's tangential stiffness 1/c_i (c_i its tangential compliance under
   * K0, the response of its tangential velocity to its own tangential
   * force); the residual keeps the exact law, so the solution is the same,
   * and the iteration converges quadratically wherever the limit is not
   * reached (the nodes slipping well beyond the onset).
   *
   * Both contact solvers take the limit from the same data, so that they
   * compute the same iterates: 1/c_i is estimated from the diagonal block
   * of K0 at the node, k_i (its smallest stiffness in the tangent plane),
   * divided by one ratio r = max_j k_j c_j measured once per K0 at a few
   * sample nodes spread along Gamma_3 (the exact compliance there: from the
   * condensed solver's table, or by solves with K0). The ratio is about the
   * same along a uniform mesh, and far larger on the thin beam of the
   * paper's scene, whose cells are 20 times longer than high, than on the
   * 3D rail.
   */
  namespace WeakeningLimit
  {
    /**
     * kappa. Chosen on the 3D rail (80 x 8 x 8, 32 steps) with the exact
     * compliance: 0.25 to 1 give about the same Newton iterations per step
     * and no fallback, 2 more iterations and fallbacks, no limit a
     * fallback in most steps.
     */
    constexpr double fraction = 0.5;

    /** The number of sample nodes of the ratio r. */
    constexpr unsigned int n_samples = 8;

    /**
     * k_i: the smallest eigenvalue of the node's block @p K_ii of K0 (in
     * its actual coordinates, P K_ii P^T) in its tangent plane
     * (BulkOperator::newton_blocks()).
     */
    template <int dim>
    double
    tangential_stiffness(const ContactNode<dim> &node,
                         const Tensor<2, dim>   &K_ii);

    /**
     * The largest eigenvalue of the node's compliance block @p C_ii in its
     * tangent plane.
     */
    template <int dim>
    double
    tangential_compliance(const ContactNode<dim> &node,
                          const Tensor<2, dim>   &C_ii);

    /**
     * The sample nodes: for each of n_samples points spread along the
     * longest side of the bounding box of Gamma_3 (at the box's centre
     * across it), the node nearest to it (ties: the smallest first DoF).
     * @p nodes are this process's (distributed, @p comm reduces over the
     * processes) or all of them (@p comm = MPI_COMM_SELF); the answer is
     * the same set either way: for each point, the index into @p nodes of
     * its node, or -1 where another process owns it.
     */
    template <int dim>
    std::vector<int>
    sample(const std::vector<ContactNode<dim>> &nodes, const MPI_Comm comm);

    /**
     * The limits of @p nodes: fraction k_i / r, with k_i their tangential
     * stiffness @p stiffness[i] and r = max over the sample of
     * @p stiffness[j] @p compliance(j), where compliance(j) is the
     * tangential compliance of the sample node with index j into @p nodes
     * (called once per sample point on every process, with j = -1 where
     * another process owns the node: a collective place for solves; the
     * answer matters only where j >= 0). Infinite where the ratio cannot be
     * measured (no sample node with stiffness and compliance).
     */
    template <int dim>
    std::vector<double>
    limits(const std::vector<ContactNode<dim>>    &nodes,
           const std::vector<double>              &stiffness,
           const std::function<double(const int)> &compliance,
           const MPI_Comm                          comm);
  } // namespace WeakeningLimit
} // namespace DynamicContact

#endif
