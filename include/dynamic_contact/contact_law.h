#ifndef dynamic_contact_contact_law_h
#define dynamic_contact_contact_law_h

#include <deal.II/base/tensor.h>

#include <dynamic_contact/contact_boundary.h>
#include <dynamic_contact/foundation.h>

namespace DynamicContact
{
  using namespace dealii;

  /** Where a node of Gamma_3 stands with respect to friction. */
  enum class ContactState : unsigned char
  {
    free  = 0, // no normal force: no friction
    stick = 1, // w_tau = 0, |lambda| <= mu N
    slip  = 2  // lambda = mu N w_tau/|w_tau|
  };

  const char *
  to_string(const ContactState state);


  /**
   * The normal law at one node for the scheme's unknown w (model.md
   * sections 2, 3): u = u_{n-1} + k w, u_nu = u . nu - g0, w_nu = w . nu,
   * pressure p(u_nu) + q(w_nu), and its derivative with respect to w_nu,
   * k p'(u_nu) + q'(w_nu), as semismooth Newton uses it.
   */
  struct NormalResponse
  {
    double u_nu;
    double w_nu;
    double pressure;
    double dpressure_dw;
    bool   compliance_active;
    bool   compliance_saturated;
    bool   damping_active;
    bool   damping_saturated;

    /** The sets this node belongs to, for "did the active sets change?". */
    unsigned int
    set_signature() const
    {
      return compliance_active + 2 * compliance_saturated +
             4 * damping_active + 8 * damping_saturated;
    }
  };

  NormalResponse
  normal_response(const Foundation &foundation,
                  const double      u_nu,
                  const double      w_nu,
                  const double      k);

  /** The normal response of @p node for the nodal u_{n-1} and w. */
  template <int dim>
  NormalResponse
  normal_response(const Foundation &      foundation,
                  const ContactNode<dim> &node,
                  const Tensor<1, dim> &  u_old,
                  const Tensor<1, dim> &  w,
                  const double            k)
  {
    const Tensor<1, dim> u = u_old + k * w;
    return normal_response(foundation,
                           u * node.normal - node.gap,
                           w * node.normal,
                           k);
  }
} // namespace DynamicContact

#endif
