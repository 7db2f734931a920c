#include <dynamic_contact/laws/contact_law.h>

namespace DynamicContact
{
  const char *
  to_string(const FrictionState state)
  {
    switch (state)
      {
        case FrictionState::free:
          return "free";
        case FrictionState::stick:
          return "stick";
        case FrictionState::slip:
          return "slip";
      }
    return "?";
  }


  NormalResponse
  normal_response(const Foundation &foundation,
                  const double      u_nu_old,
                  const double      u_nu,
                  const double      w_nu,
                  const TimeScheme &scheme)
  {
    if (scheme.is_backward_euler())
      return normal_response(foundation, u_nu, w_nu, scheme.time_step());
    const ResponseLaw &p = foundation.compliance();
    const ResponseLaw &q = foundation.damping();
    NormalResponse     r;
    r.u_nu                 = u_nu;
    r.w_nu                 = w_nu;
    r.compliance_active    = p.active(u_nu) || p.active(u_nu_old);
    r.compliance_saturated = p.saturated(u_nu);
    const bool damping     = foundation.damping_acts(u_nu);
    r.damping_active       = damping && q.active(w_nu);
    r.damping_saturated    = damping && q.saturated(w_nu);
    r.pressure             = scheme.compliance_force(p.value(u_nu),
                                         p.discrete_gradient(u_nu_old, u_nu)) +
                 (damping ? q.value(w_nu) : 0.);
    // d u_n/d w_n = theta k, d w_e/d w_n = theta.
    r.dpressure_dw =
      scheme.displacement_derivative() *
        scheme.compliance_force(p.derivative(u_nu),
                                p.discrete_gradient_derivative(u_nu_old,
                                                               u_nu)) +
      (damping ? scheme.effective_derivative() * q.derivative(w_nu) : 0.);
    return r;
  }


  NormalResponse
  normal_response(const Foundation &foundation,
                  const double      u_nu,
                  const double      w_nu,
                  const double      k)
  {
    const ResponseLaw &p = foundation.compliance();
    const ResponseLaw &q = foundation.damping();
    NormalResponse     r;
    r.u_nu                 = u_nu;
    r.w_nu                 = w_nu;
    r.compliance_active    = p.active(u_nu);
    r.compliance_saturated = p.saturated(u_nu);
    const bool damping     = foundation.damping_acts(u_nu);
    r.damping_active       = damping && q.active(w_nu);
    r.damping_saturated    = damping && q.saturated(w_nu);
    r.pressure             = foundation.pressure(u_nu, w_nu);
    r.dpressure_dw =
      k * p.derivative(u_nu) + (damping ? q.derivative(w_nu) : 0.);
    return r;
  }


  template <int dim>
  Tensor<1, dim>
  projected_friction_force(const ContactNode<dim> &node,
                           const double            threshold,
                           const Tensor<1, dim>   &w,
                           const Tensor<1, dim>   &lambda,
                           const double            c)
  {
    if (threshold <= 0 || !node.unconstrained)
      return Tensor<1, dim>();
    const Tensor<1, dim> z =
      node.tangential(lambda) + (c * node.weight) * node.tangential(w);
    const double norm = z.norm();
    return norm <= threshold ? z : (threshold / norm) * z;
  }


  namespace
  {
    /**
     * The part of d g / d w that comes from mu = mu(|w_tau|) of the
     * iterate: mu'(s) m (p + q) theta w_tau/s (t at s = 0), its slope
     * capped at -@p weakening_limit (then r.limited is set).
     */
    template <int dim>
    Tensor<1, dim>
    weakening_gradient(const ContactNode<dim> &node,
                       const NormalResponse   &normal,
                       const Tensor<1, dim>   &lambda_tau,
                       const Tensor<1, dim>   &w_tau,
                       const double            c_node,
                       const double            effective_derivative,
                       const double            dmu_ds,
                       const double            weakening_limit,
                       FrictionResponse<dim>  &r)
    {
      // d|w_tau|/dw_tau = w_tau/|w_tau|; where the slip velocity does
      // not matter in z (round-off at the onset of slip, as for the
      // reversal rule above) the slip force's direction t stands for it.
      const double slip = w_tau.norm();
      const bool   slipping =
        c_node * slip > 1e-6 * std::max(r.threshold, lambda_tau.norm());
      double slope =
        dmu_ds * node.weight * normal.pressure * effective_derivative;
      if (-slope > weakening_limit)
        {
          slope     = -weakening_limit;
          r.limited = true;
        }
      return slope * (slipping ? w_tau / slip : r.direction);
    }


    /**
     * In 3D, the change of the slip direction t = z/|z| (@p norm = |z|)
     * with lambda and w_tau, added to the slip response @p r.
     */
    template <int dim>
    void
    add_direction_change(const ContactNode<dim> &node,
                         const Tensor<1, dim>   &lambda_tau,
                         const double            norm,
                         const double            c_node,
                         const double            effective_derivative,
                         FrictionResponse<dim>  &r)
    {
      // The direction t = z/|z| changes with lambda and w_tau. Solving
      // the linearized slip condition for the new lambda gives, with
      // alpha = g/|z| < 1 and P the projection in the tangent plane
      // orthogonal to t:
      //   lambda' = t (g + dg.dw) + beta P dw_tau - alpha/(1-alpha) P lambda,
      //   beta = alpha c m_i/(1-alpha).
      const double   alpha = r.threshold / norm;
      const double   beta = effective_derivative * alpha * c_node / (1 - alpha);
      Tensor<2, dim> P    = unit_symmetric_tensor<dim>();
      P -= outer_product(node.normal, node.normal);
      P -= outer_product(r.direction, r.direction);
      r.value -= (alpha / (1 - alpha)) * (P * lambda_tau);
      Tensor<2, dim> tangential_projection = unit_symmetric_tensor<dim>();
      tangential_projection -= outer_product(node.normal, node.normal);
      r.jacobian += beta * P * tangential_projection;
    }
  } // namespace


  template <int dim>
  FrictionResponse<dim>
  friction_response(const ContactNode<dim> &node,
                    const NormalResponse   &normal,
                    const Tensor<1, dim>   &w,
                    const Tensor<1, dim>   &lambda,
                    const double            mu,
                    const double            c,
                    const double            effective_derivative,
                    const double            dmu_ds,
                    const double            weakening_limit)
  {
    FrictionResponse<dim> r;
    r.threshold = mu * node.weight * normal.pressure;
    if (r.threshold <= 0 || !node.unconstrained)
      return r; // free: lambda = 0

    // lambda is a nodal force; c m_i w_tau is one too (c = c_t k).
    const double         c_node     = c * node.weight;
    const Tensor<1, dim> lambda_tau = node.tangential(lambda);
    const Tensor<1, dim> z          = lambda_tau + c_node * node.tangential(w);
    const double         norm       = z.norm();
    // A slip velocity against the friction force cannot be part of a
    // solution (lambda . w_tau >= 0: friction dissipates): the iterate has
    // crossed w_tau = 0, and stick is the prediction. Without this rule the
    // active sets of neighbouring nodes can ping-pong between the two slip
    // directions; with it a genuine reversal costs one more iteration. It
    // only applies to a slip velocity that matters in z: at a stick solution
    // w_tau is round-off of either sign, and a multiplier above the
    // threshold must then be allowed to slip.
    const Tensor<1, dim> w_tau = node.tangential(w);
    const bool           reversed =
      lambda_tau * w_tau < 0 &&
      c_node * w_tau.norm() > 1e-6 * std::max(r.threshold, lambda_tau.norm());
    if (norm <= r.threshold || reversed)
      {
        r.state = FrictionState::stick;
        r.value = lambda_tau;
        return r;
      }

    r.state     = FrictionState::slip;
    r.direction = z / norm;
    // d g / d w = mu m (k p' + q') nu, and with mu = mu(|w_tau|) of the
    // iterate also mu'(s) m (p + q) theta w_tau/s (t at s = 0).
    Tensor<1, dim> dg = (mu * node.weight * normal.dpressure_dw) * node.normal;
    if (dmu_ds != 0)
      dg += weakening_gradient(node,
                               normal,
                               lambda_tau,
                               w_tau,
                               c_node,
                               effective_derivative,
                               dmu_ds,
                               weakening_limit,
                               r);
    r.value    = r.threshold * r.direction;
    r.jacobian = outer_product(r.direction, dg);
    if (dim == 3)
      add_direction_change(
        node, lambda_tau, norm, c_node, effective_derivative, r);
    return r;
  }


  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                                     \
  template Tensor<1, dim> projected_friction_force(const ContactNode<dim> &, \
                                                   const double,             \
                                                   const Tensor<1, dim> &,   \
                                                   const Tensor<1, dim> &,   \
                                                   const double);            \
  template FrictionResponse<dim> friction_response(const ContactNode<dim> &, \
                                                   const NormalResponse &,   \
                                                   const Tensor<1, dim> &,   \
                                                   const Tensor<1, dim> &,   \
                                                   const double,             \
                                                   const double,             \
                                                   const double,             \
                                                   const double,             \
                                                   const double);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
