#ifndef dynamic_contact_contact_law_h
#define dynamic_contact_contact_law_h

#include <deal.II/base/tensor.h>

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/laws/contact_node.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>

#include <limits>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /** Where a node of Gamma_3 stands with respect to friction. */
  enum class FrictionState : unsigned char
  {
    free  = 0, // no normal force: no friction
    stick = 1, // w_tau = 0, |lambda| <= mu N
    slip  = 2  // lambda = mu N w_tau/|w_tau|
  };

  const char *
  to_string(const FrictionState state);


  /**
   * The normal law at one node for the scheme's unknown w (doc/theory.md
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
      return compliance_active + 2 * compliance_saturated + 4 * damping_active +
             8 * damping_saturated;
    }
  };

  /** What the solver knows about one (owned) node of Gamma_3 after a step. */
  template <int dim>
  struct ContactNodeState
  {
    NormalResponse normal{};
    /** Friction force lambda_i (a nodal force: m_i times the traction). */
    Tensor<1, dim> friction_force;
    /** The frozen friction coefficient mu_i of the last iterate. */
    double        mu    = 0;
    FrictionState state = FrictionState::free;
    /** w_e,tau, the tangential part of w_e (w_e = w_n for backward Euler). */
    Tensor<1, dim> slip_velocity;
    /** |w_e,tau|. */
    double slip_rate = 0;

    /** Normal nodal force N_i = m_i (p + q). */
    double
    normal_force(const double weight) const
    {
      return weight * normal.pressure;
    }
  };


  NormalResponse
  normal_response(const Foundation &foundation,
                  const double      u_nu,
                  const double      w_nu,
                  const double      k);

  /**
   * The normal law of the theta-scheme (Time/Scheme): u_n = u_{n-1} + k w_e
   * with the effective velocity w_e = theta w_n + (1 - theta) w_{n-1}; q acts
   * on w_e,nu, and the compliance force is p(u_n) for theta = 1 (backward
   * Euler), the discrete gradient (Pi(u_n) - Pi(u_{n-1}))/(u_n - u_{n-1})
   * for theta = 1/2 (the energy-consistent trapezoidal scheme) and their
   * combination TimeScheme::compliance_force in between. dpressure_dw
   * is the derivative with respect to w_n,nu; w_nu is w_e,nu.
   */
  NormalResponse
  normal_response(const Foundation &foundation,
                  const double      u_nu_old,
                  const double      u_nu,
                  const double      w_nu_effective,
                  const TimeScheme &scheme);

  /** The normal response of @p node for the nodal u_{n-1} and w. */
  template <int dim>
  NormalResponse
  normal_response(const Foundation       &foundation,
                  const ContactNode<dim> &node,
                  const Tensor<1, dim>   &u_old,
                  const Tensor<1, dim>   &w,
                  const double            k)
  {
    const Tensor<1, dim> u = u_old + k * w;
    return normal_response(foundation,
                           u * node.normal - node.gap,
                           w * node.normal,
                           k);
  }

  /** The same for the theta-scheme, given w_{n-1} at the node too. */
  template <int dim>
  NormalResponse
  normal_response(const Foundation       &foundation,
                  const ContactNode<dim> &node,
                  const Tensor<1, dim>   &u_old,
                  const Tensor<1, dim>   &w_old,
                  const Tensor<1, dim>   &w,
                  const TimeScheme       &scheme)
  {
    const Tensor<1, dim> w_e = scheme.weighted(w, w_old);
    const Tensor<1, dim> u   = scheme.displacement(u_old, w_e);
    return normal_response(foundation,
                           u_old * node.normal - node.gap,
                           u * node.normal - node.gap,
                           w_e * node.normal,
                           scheme);
  }


  /**
   * Friction at one node for a frozen coefficient mu_i (doc/theory.md section
   * 5), from the complementarity form lambda = P_B(0, g)(lambda + c m_i w_tau),
   * g = mu_i N_i(u_nu, w_nu), lambda the nodal friction force and c = c_t k,
   * c_t ~ E/h, so that c m_i w_tau is a nodal force (c_t times the slip
   * increment k w_tau): free where g = 0, stick where |lambda + c_t w_tau| <=
   * g, slip otherwise. On slip nodes the friction force is linearized in w (the
   * threshold g through u_nu and w_nu, and in 3D the direction, after Hueber,
   * Stadler & Wohlmuth 2008): lambda(w') = value + jacobian (w' - w). On stick
   * nodes lambda is a multiplier of the constraint w_tau = 0 and value is the
   * lambda given.
   */
  template <int dim>
  struct FrictionResponse
  {
    FrictionState  state     = FrictionState::free;
    double         threshold = 0; // g
    Tensor<1, dim> direction;     // t (slip)
    Tensor<1, dim> value;
    Tensor<2, dim> jacobian;
    /** The weakening limit cut the slip-rate term of the Jacobian. */
    bool limited = false;
  };

  /**
   * @p lambda is the current friction force, @p normal the normal response
   * at w, @p c = c_t k the complementarity constant. With the theta-scheme
   * @p w is the effective velocity w_e (friction acts on its slip) and the
   * Jacobian is with respect to w_n = (w_e - (1-theta) w_{n-1})/theta (the
   * direction term scaled by @p effective_derivative = d w_e/d w_n = theta,
   * TimeScheme::effective_derivative(); normal.dpressure_dw already is).
   * Nodes with a constrained
   * component are frictionless (their tangential motion is prescribed).
   *
   * @p dmu_ds is the derivative mu'(s) of the coefficient at the slip rate
   * s = |w_tau| of @p w when @p mu is mu(s) of the iterate itself (the
   * coupled linearization, doc/theory.md section 5.1): the threshold g =
   * mu(s) m (p + q) then also depends on w_tau, dg/dw_tau = mu'(s) m (p +
   * q) w_tau/s (times effective_derivative), and on slip nodes that term
   * enters the Jacobian (at s = 0 the direction t of the slip force stands
   * for w_tau/s: a Clarke derivative). 0 for a frozen coefficient.
   */
  template <int dim>
  FrictionResponse<dim>
  friction_response(const ContactNode<dim> &node,
                    const NormalResponse   &normal,
                    const Tensor<1, dim>   &w,
                    const Tensor<1, dim>   &lambda,
                    const double            mu,
                    const double            c,
                    const double            effective_derivative = 1,
                    const double            dmu_ds               = 0,
                    const double            weakening_limit =
                      std::numeric_limits<double>::infinity());

  /**
   * The friction force the law assigns to (lambda, w): the projection of
   * lambda + c m_i w_tau onto the ball of radius g. At a solution it equals
   * lambda; the difference measures how far the law is from holding.
   */
  template <int dim>
  Tensor<1, dim>
  projected_friction_force(const ContactNode<dim> &node,
                           const double            threshold,
                           const Tensor<1, dim>   &w,
                           const Tensor<1, dim>   &lambda,
                           const double            c);


  /**
   * The friction coefficients of one Newton solve (Friction/Linearization,
   * doc/theory.md sections 4 and 5.1). Frozen: mu_i = frozen[i] at every
   * iterate, the convexification loop's coefficients (the nodes in the
   * order of the solver's node vectors). Coupled (@p law set): mu_i =
   * mu(|w_e,tau,i|) of the iterate itself, whose derivative enters the
   * Newton linearization, so that one solve lands on the fixed point of
   * the loop; frozen is then not used. With a slip length, the coupled
   * coefficient is the step's mu_e of the node's state (SlipLength).
   */
  struct FrictionCoefficients
  {
    std::vector<double> frozen;
    const FrictionLaw  *law = nullptr;
    /**
     * Coupled: the largest weakening -mu'(s) m (p + q) theta (a force per
     * velocity) the linearization takes at node i, empty for no limit.
     */
    std::vector<double> weakening_limit;
    /** Coupled with a slip length: the states mu~_i at the step's start. */
    std::vector<double> state;
    SlipLength          slip_length;

    bool
    coupled() const
    {
      return law != nullptr;
    }

    /** Coupled: the coefficient of node @p i at the slip rate @p s, and its
     * derivative in s. */
    std::pair<double, double>
    coupled_coefficient(const unsigned int i,
                        const double       s,
                        const TimeScheme  &scheme) const
    {
      return slip_length.step_coefficient(*law,
                                          slip_length.active() ? state[i] : 0.,
                                          s,
                                          scheme);
    }
  };


  /**
   * Everything the Newton iteration needs of one node at an iterate
   * (w, lambda): the normal and friction responses, the nodal force
   *   f = N nu + lambda   (N = m (p + q); lambda the slip value or the
   *                       stick multiplier, 0 if free),
   * and its derivative with respect to w (the nodal Newton block)
   *   m (k p' + q') nu (x) nu + d lambda/dw (slip only).
   * Forces and blocks are in the node's actual coordinates.
   */
  template <int dim>
  struct NodeLinearization
  {
    NormalResponse        normal;
    FrictionResponse<dim> friction;
    Tensor<1, dim>        force;
    Tensor<2, dim>        block;

    /** The node takes part in the Newton system (force or stick). */
    bool
    active() const
    {
      return force.norm_square() > 0 || block.norm_square() > 0 ||
             friction.state == FrictionState::stick;
    }
  };

  template <int dim>
  NodeLinearization<dim>
  linearize_node(const Foundation       &foundation,
                 const ContactNode<dim> &node,
                 const Tensor<1, dim>   &u_old,
                 const Tensor<1, dim>   &w,
                 const double            k,
                 const bool              friction,
                 const Tensor<1, dim>   &lambda,
                 const double            mu,
                 const double            c,
                 const double            dmu_ds = 0)
  {
    return linearize_node(foundation,
                          node,
                          u_old,
                          w,
                          w,
                          TimeScheme(k),
                          friction,
                          lambda,
                          mu,
                          c,
                          dmu_ds);
  }

  /**
   * The theta-scheme version: @p w_old is w_{n-1} at the node, the laws act
   * on u_n and w_e = theta w + (1 - theta) w_old, the block is the derivative
   * with respect to w (= w_n). @p dmu_ds: friction_response().
   */
  template <int dim>
  NodeLinearization<dim>
  linearize_node(const Foundation       &foundation,
                 const ContactNode<dim> &node,
                 const Tensor<1, dim>   &u_old,
                 const Tensor<1, dim>   &w_old,
                 const Tensor<1, dim>   &w,
                 const TimeScheme       &scheme,
                 const bool              friction,
                 const Tensor<1, dim>   &lambda,
                 const double            mu,
                 const double            c,
                 const double            dmu_ds = 0,
                 const double            weakening_limit =
                   std::numeric_limits<double>::infinity())
  {
    NodeLinearization<dim> l;
    const Tensor<1, dim>   w_e = scheme.weighted(w, w_old);
    l.normal       = normal_response(foundation, node, u_old, w_old, w, scheme);
    const double N = node.weight * l.normal.pressure;
    l.force        = N * node.normal;
    l.block        = (node.weight * l.normal.dpressure_dw) *
              outer_product(node.normal, node.normal);
    if (friction)
      {
        l.friction = friction_response(node,
                                       l.normal,
                                       w_e,
                                       lambda,
                                       mu,
                                       c,
                                       scheme.effective_derivative(),
                                       dmu_ds,
                                       weakening_limit);
        l.force += l.friction.value;
        l.block += l.friction.jacobian;
      }
    return l;
  }
} // namespace DynamicContact

#endif
