#ifndef dynamic_contact_contact_state_h
#define dynamic_contact_contact_state_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/laws/contact_law.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>

#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The solution on Gamma_3 beside the fields u and w: for each owned node
   * of the ContactBoundary (the same order as ContactBoundary::nodes()),
   * the frozen friction coefficient mu_i of the convexification loop, the
   * friction force lambda_i (the multiplier, a nodal force; the warm start
   * of the next step) and the node's state after the last solve (pressure,
   * friction state, slip). The StepSolver reads and writes it; the time
   * loop copies it as the restore point of a step (with u and w); a
   * checkpoint and a change of the mesh carry the friction forces as a
   * finite element field (friction_field(), set_friction_from_field()).
   *
   * A plain value: copying it copies the whole Gamma_3 solution.
   */
  template <int dim>
  class ContactState
  {
  public:
    /**
     * Size for the owned nodes of @p boundary (after a change of the mesh):
     * mu_i = @p initial_mu, lambda_i = 0, node states free.
     */
    void
    reinit(const ContactBoundary<dim> &boundary, const double initial_mu);

    /** The frozen friction coefficients mu_i. */
    std::vector<double> mu;
    /** The friction forces lambda_i (nodal forces: m_i times a traction). */
    std::vector<Tensor<1, dim>> lambda;
    /** The node states of the last solve. */
    std::vector<ContactNodeState<dim>> nodes;
    /**
     * With a slip length (SlipLength): the state mu~_i of each node at the
     * end of the last solve, where the next one starts (initial_mu after
     * reinit()).
     */
    std::vector<double> coefficient_state;

    /**
     * The total normal force sum_i N_i and the sum of |lambda_i| over
     * Gamma_3 (collective).
     */
    std::pair<double, double>
    force_sums(const ContactBoundary<dim> &boundary, const MPI_Comm comm) const;

    /**
     * The friction forces as a finite element field at the nodes of Gamma_3
     * (zero elsewhere), and back: with @p per_weight the traction
     * lambda_i/m_i, the form in which they survive a change of the mesh
     * (interpolated; back on the new mesh its tangential part times the
     * new weight); without, the nodal forces lambda_i themselves, which a
     * checkpoint stores exactly with the mesh.
     */
    Vector_t
    friction_field(const Discretization<dim>  &discretization,
                   const ContactBoundary<dim> &boundary,
                   const bool                  per_weight) const;
    void
    set_friction_from_field(const ContactBoundary<dim> &boundary,
                            const Vector_t             &field,
                            const bool                  per_weight);

    /**
     * The states mu~_i as a finite element field (the first component at
     * the nodes of Gamma_3, zero elsewhere), and back: a coefficient, which
     * a change of the mesh interpolates along Gamma_3 and a checkpoint
     * stores exactly.
     */
    Vector_t
    state_field(const Discretization<dim>  &discretization,
                const ContactBoundary<dim> &boundary) const;
    void
    set_state_from_field(const ContactBoundary<dim> &boundary,
                         const Vector_t             &field);

  private:
    /**
     * The field with @p value(i, c) at component c of node i of Gamma_3
     * and zero elsewhere.
     */
    template <typename NodalValue>
    static Vector_t
    nodal_field(const Discretization<dim>  &discretization,
                const ContactBoundary<dim> &boundary,
                const NodalValue           &value);
  };
} // namespace DynamicContact

#endif
