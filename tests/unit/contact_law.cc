// The node-wise contact laws of doc/theory.md sections 3 and 5 on hand-made
// ContactNodes: the normal response p(u_nu) + q(w_nu) and its sets, the
// friction classification (free, stick, slip, reversed slip velocity), the
// slip linearization (2D: finite differences; 3D: the linearized slip
// condition holds to O(eps^2)), projected_friction_force and linearize_node
// (its checks in contact_law_linearization.h).
//
// Data: c_nu = 2, c3 = 3 (kink 1.5), d_nu = 0.5, c4 = 0.25 (kink 0.5),
// k = 0.1, m = 0.5, mu = 0.4, c = c_t k = 2 (so c m = 1). Vectors are given
// in the node's frame (n, t) or (n, t1, t2); the reference point
//   u_old = 0.978 n + 0.3 t1,  w = 0.22 n + ...
// has u_nu = 0.978 + k 0.22 = 1, w_nu = 0.22: p = 2, q = 0.11, pressure
// 2.11, dpressure/dw_nu = k c_nu + d_nu = 0.7, threshold
// g = mu m 2.11 = 0.422, dg/dw = mu m 0.7 n = 0.14 n.

#include <deal.II/base/tensor.h>

#include <dynamic_contact/laws/contact_law.h>

#include "test_tools.h"

using namespace DynamicContact;
using test_tools::check;
using test_tools::digits;
using test_tools::out;

namespace
{
  const double k = 0.1, m = 0.5, mu = 0.4, c = 2.;

  Tensor<1, 2>
  vec(const double x, const double y)
  {
    Tensor<1, 2> v;
    v[0] = x;
    v[1] = y;
    return v;
  }

  Tensor<1, 3>
  vec(const double x, const double y, const double z)
  {
    Tensor<1, 3> v;
    v[0] = x;
    v[1] = y;
    v[2] = z;
    return v;
  }

  Foundation
  make_foundation(const bool only_in_contact = false)
  {
    return Foundation(CappedRamp(2., 3.),
                      CappedRamp(0.5, 0.25),
                      only_in_contact);
  }

  /** 2D: n = (0.6, -0.8), t = (-n_y, n_x) = (0.8, 0.6). */
  ContactNode<2>
  node_2d()
  {
    ContactNode<2> node{};
    node.constraint_map = unit_symmetric_tensor<2>();
    node.unconstrained  = true;
    node.normal         = vec(0.6, -0.8);
    node.tangents[0]    = vec(0.8, 0.6);
    node.weight         = m;
    node.gap            = 0;
    return node;
  }

  /** 3D: n = (0, 0.6, -0.8), t1 = (1, 0, 0), t2 = t1 x n = (0, 0.8, 0.6). */
  ContactNode<3>
  node_3d()
  {
    ContactNode<3> node{};
    node.constraint_map = unit_symmetric_tensor<3>();
    node.unconstrained  = true;
    node.normal         = vec(0., 0.6, -0.8);
    node.tangents[0]    = vec(1., 0., 0.);
    node.tangents[1]    = cross_product_3d(node.tangents[0], node.normal);
    node.weight         = m;
    node.gap            = 0;
    return node;
  }

  /** a n + b t1 (+ c t2). */
  template <int dim>
  Tensor<1, dim>
  frame(const ContactNode<dim> &node,
        const double            a,
        const double            b,
        const double            c2 = 0)
  {
    Tensor<1, dim> v = a * node.normal + b * node.tangents[0];
    if (dim == 3)
      v += c2 * node.tangents[dim - 2];
    return v;
  }

  /** The components of v in the node's frame, "(n, t1[, t2])". */
  template <int dim>
  std::string
  in_frame(const ContactNode<dim> &node, const Tensor<1, dim> &v)
  {
    auto clean = [](const double x) {
      return digits(std::abs(x) < 1e-13 ? 0. : x, 6);
    };
    std::string s = "(" + clean(v * node.normal);
    for (const auto &t : node.tangents)
      s += ", " + clean(v * t);
    return s + ")";
  }

  /** The matrix (a . J b) in the node's frame, rows n, t1[, t2]. */
  template <int dim>
  std::string
  in_frame(const ContactNode<dim> &node,
           const Tensor<2, dim>   &J,
           const double            zero_below = 1e-13)
  {
    std::vector<Tensor<1, dim>> basis = {node.normal};
    for (const auto &t : node.tangents)
      basis.push_back(t);
    std::string s = "[";
    for (unsigned int a = 0; a < dim; ++a)
      {
        Tensor<1, dim> row;
        for (unsigned int b = 0; b < dim; ++b)
          row[b] = basis[a] * (J * basis[b]);
        s += (a == 0 ? "" : "; ");
        for (unsigned int b = 0; b < dim; ++b)
          s += (b == 0 ? "" : " ") +
               digits(std::abs(row[b]) < zero_below ? 0. : row[b], 6);
      }
    return s + "]";
  }

  template <int dim>
  bool
  near(const Tensor<1, dim> &a, const Tensor<1, dim> &b, const double tol)
  {
    return (a - b).norm() <= tol;
  }

  template <int dim>
  bool
  near(const Tensor<2, dim> &a, const Tensor<2, dim> &b, const double tol)
  {
    return (a - b).norm() <= tol;
  }

  /** The friction response at (u_old, w, lambda), normal law included. */
  template <int dim>
  FrictionResponse<dim>
  respond(const ContactNode<dim> &node,
          const Tensor<1, dim>   &u_old,
          const Tensor<1, dim>   &w,
          const Tensor<1, dim>   &lambda,
          const double            mu_i       = mu,
          const Foundation       &foundation = make_foundation())
  {
    return friction_response(
      node, normal_response(foundation, node, u_old, w, k), w, lambda, mu_i, c);
  }



  void
  test_normal_response()
  {
    out() << "--- normal_response" << std::endl;
    const Foundation f = make_foundation();
    struct Row
    {
      double       u, w, pressure, dpressure;
      unsigned int signature;
    };
    // signature = compliance active + 2 saturated + 4 damping active
    //             + 8 damping saturated
    const std::vector<Row> rows = {{-0.1, -0.1, 0., 0., 0},
                                   {0., 0., 0., 0., 0},
                                   {1., 0.2, 2.1, 0.7, 5},
                                   {2., 0.2, 3.1, 0.5, 7},
                                   {1.5, 0.2, 3.1, 0.5, 7},
                                   {1., 1., 2.25, 0.2, 13},
                                   {2., 1., 3.25, 0., 15},
                                   {-0.1, 0.2, 0.1, 0.5, 4}};
    for (const Row &row : rows)
      {
        const NormalResponse r = normal_response(f, row.u, row.w, k);
        out() << "u_nu = " << digits(row.u, 6)
              << "  w_nu = " << digits(row.w, 6)
              << "  pressure = " << digits(r.pressure, 6)
              << "  dpressure/dw = " << digits(r.dpressure_dw, 6)
              << "  sets = " << r.set_signature() << std::endl;
        check(r.u_nu == row.u && r.w_nu == row.w &&
                std::abs(r.pressure - row.pressure) <= 1e-14 &&
                std::abs(r.dpressure_dw - row.dpressure) <= 1e-14 &&
                r.set_signature() == row.signature,
              "u_nu = " + digits(row.u, 3) + ", w_nu = " + digits(row.w, 3) +
                ": pressure, k p' + q', sets");
      }
    {
      const NormalResponse r = normal_response(f, 2., 0.2, k);
      check(r.compliance_active && r.compliance_saturated && r.damping_active &&
              !r.damping_saturated,
            "u_nu = 2, w_nu = 0.2: compliance saturated, damping active");
    }

    const Foundation     g              = make_foundation(true);
    const NormalResponse out_of_contact = normal_response(g, -0.1, 0.2, k);
    check(out_of_contact.pressure == 0 && out_of_contact.dpressure_dw == 0 &&
            out_of_contact.set_signature() == 0,
          "damping only in contact: u_nu = -0.1, w_nu = 0.2: no pressure, "
          "no sets");
    const NormalResponse in_contact = normal_response(g, 1., 0.2, k);
    check(std::abs(in_contact.pressure - 2.1) <= 1e-14 &&
            std::abs(in_contact.dpressure_dw - 0.7) <= 1e-14 &&
            in_contact.set_signature() == 5,
          "damping only in contact: u_nu = 1, w_nu = 0.2: as before");

    // The nodal version: u = u_old + k w, u_nu = u . n - g0, w_nu = w . n.
    const ContactNode<2> n2 = node_2d();
    const NormalResponse r2 =
      normal_response(f, n2, frame(n2, 0.978, 0.3), frame(n2, 0.22, 0.6), k);
    out() << "2D node: u_nu = " << digits(r2.u_nu, 6)
          << "  w_nu = " << digits(r2.w_nu, 6)
          << "  pressure = " << digits(r2.pressure, 6) << std::endl;
    check(std::abs(r2.u_nu - 1.) <= 1e-14 &&
            std::abs(r2.w_nu - 0.22) <= 1e-14 &&
            std::abs(r2.pressure - 2.11) <= 1e-14 &&
            std::abs(r2.dpressure_dw - 0.7) <= 1e-14,
          "2D node: u_nu = 1, w_nu = 0.22, pressure 2.11, k p' + q' = 0.7");
    ContactNode<2> gapped   = n2;
    gapped.gap              = 0.5;
    const NormalResponse rg = normal_response(
      f, gapped, frame(n2, 0.978, 0.3), frame(n2, 0.22, 0.6), k);
    check(std::abs(rg.u_nu - 0.5) <= 1e-14 &&
            std::abs(rg.pressure - 1.11) <= 1e-14,
          "2D node, gap 0.5: u_nu = 0.5, pressure 1.11");
    const ContactNode<3> n3 = node_3d();
    const NormalResponse r3 = normal_response(
      f, n3, frame(n3, 0.978, 0.3, -0.2), frame(n3, 0.22, 0.6, 0.4), k);
    check(std::abs(r3.u_nu - 1.) <= 1e-14 &&
            std::abs(r3.w_nu - 0.22) <= 1e-14 &&
            std::abs(r3.pressure - 2.11) <= 1e-14,
          "3D node: u_nu = 1, w_nu = 0.22, pressure 2.11");
  }


  template <int dim>
  void
  print(const ContactNode<dim> &node, const FrictionResponse<dim> &r)
  {
    out() << "  state = " << to_string(r.state)
          << "  g = " << digits(r.threshold, 6)
          << "  value = " << in_frame(node, r.value) << std::endl;
  }


  void
  test_friction_2d_slip_and_stick()
  {
    out() << "--- friction_response, 2D" << std::endl;
    const ContactNode<2> node  = node_2d();
    const Tensor<1, 2>   u_old = frame(node, 0.978, 0.3);
    const Tensor<1, 2>   zero;

    // Slip: z = 0 + 1 * 0.6 t, |z| = 0.6 > g = 0.422.
    const auto slip = respond(node, u_old, frame(node, 0.22, 0.6), zero);
    out() << "slip, w_tau = 0.6 t:" << std::endl;
    print(node, slip);
    out() << "  jacobian = " << in_frame(node, slip.jacobian) << std::endl;
    check(slip.state == FrictionState::slip &&
            std::abs(slip.threshold - 0.422) <= 1e-14 &&
            near(slip.direction, frame(node, 0., 1.), 1e-14) &&
            near(slip.value, frame(node, 0., 0.422), 1e-14),
          "2D: slip, g = 0.422, t, value g t");
    check(near(slip.jacobian,
               outer_product(frame(node, 0., 1.), frame(node, 0.14, 0.)),
               1e-14),
          "2D: slip jacobian t (x) dg, dg = 0.14 n");

    const auto backwards = respond(node, u_old, frame(node, 0.22, -0.6), zero);
    check(backwards.state == FrictionState::slip &&
            near(backwards.value, frame(node, 0., -0.422), 1e-14),
          "2D: slip with w_tau = -0.6 t: value -g t");

    // Stick: w_tau = 0, |lambda_tau| = 0.3 <= g; the normal part of lambda
    // is dropped.
    const auto stick =
      respond(node, u_old, frame(node, 0.22, 0.), frame(node, 5., 0.3));
    out() << "stick, w_tau = 0, lambda = 5 n + 0.3 t:" << std::endl;
    print(node, stick);
    check(stick.state == FrictionState::stick &&
            near(stick.value, frame(node, 0., 0.3), 1e-14) &&
            stick.jacobian.norm() == 0,
          "2D: stick, value lambda_tau = 0.3 t, no jacobian");
    const auto small =
      respond(node, u_old, frame(node, 0.22, 0.1), frame(node, 0., 0.3));
    check(small.state == FrictionState::stick,
          "2D: |0.3 t + 0.1 t| = 0.4 <= g: stick");
    const auto larger =
      respond(node, u_old, frame(node, 0.22, 0.13), frame(node, 0., 0.3));
    check(larger.state == FrictionState::slip,
          "2D: |0.3 t + 0.13 t| = 0.43 > g: slip");

    // Reversed slip velocity: |z| = |1 t - 0.3 t| = 0.7 > g, but
    // lambda . w_tau < 0: stick predicted, lambda kept.
    const auto reversed =
      respond(node, u_old, frame(node, 0.22, -0.3), frame(node, 0., 1.));
    out() << "reversed, w_tau = -0.3 t, lambda = t:" << std::endl;
    print(node, reversed);
    check(reversed.state == FrictionState::stick &&
            near(reversed.value, frame(node, 0., 1.), 1e-14),
          "2D: lambda . w_tau < 0: stick, value lambda");
    const auto forward =
      respond(node, u_old, frame(node, 0.22, 0.3), frame(node, 0., 1.));
    check(forward.state == FrictionState::slip &&
            near(forward.value, frame(node, 0., 0.422), 1e-14),
          "2D: same |z|, lambda . w_tau > 0: slip, value g t");
  }


  /** Free: no contact, no friction coefficient, constrained node. */
  void
  test_friction_2d_free()
  {
    const ContactNode<2> node  = node_2d();
    const Tensor<1, 2>   u_old = frame(node, 0.978, 0.3);
    const Tensor<1, 2>   zero;
    const auto           free = respond(node,
                              frame(node, -0.5, 0.),
                              frame(node, -0.1, 0.6),
                              frame(node, 0., 1.));
    out() << "free, u_nu = -0.51, w_nu = -0.1:" << std::endl;
    print(node, free);
    check(free.state == FrictionState::free && free.threshold == 0 &&
            free.value.norm() == 0 && free.jacobian.norm() == 0,
          "2D: out of contact: free, g = 0, value 0");
    check(respond(node, u_old, frame(node, 0.22, 0.6), zero, 0.).state ==
            FrictionState::free,
          "2D: mu = 0: free");
    ContactNode<2> constrained = node;
    constrained.unconstrained  = false;
    const auto clamped =
      respond(constrained, u_old, frame(node, 0.22, 0.6), frame(node, 0., 1.));
    check(clamped.state == FrictionState::free && clamped.value.norm() == 0,
          "2D: constrained node: free, value 0");
    // q acts out of contact by default (u_nu = -0.5, w_nu = 0.22): g =
    // mu m q = 0.022; not with "damping only in contact".
    const auto damped =
      respond(node, frame(node, -0.522, 0.), frame(node, 0.22, 0.6), zero);
    check(damped.state == FrictionState::slip &&
            std::abs(damped.threshold - 0.022) <= 1e-14,
          "2D: approaching node, damping acts: slip with g = 0.022");
    const auto undamped = respond(node,
                                  frame(node, -0.522, 0.),
                                  frame(node, 0.22, 0.6),
                                  zero,
                                  mu,
                                  make_foundation(true));
    check(undamped.state == FrictionState::free,
          "2D: approaching node, damping only in contact: free");
  }


  /**
   * The slip jacobian against central differences of lambda(w) = g(w) t,
   * below and beyond the compliance cap.
   */
  void
  test_friction_2d_jacobian()
  {
    const ContactNode<2> node = node_2d();
    const Tensor<1, 2>   zero;
    out() << "slip jacobian vs. finite differences:" << std::endl;
    for (const double u_old_nu : {0.978, 1.978})
      {
        const Tensor<1, 2> u0        = frame(node, u_old_nu, 0.3);
        const Tensor<1, 2> w         = frame(node, 0.22, 0.8);
        const auto         r         = respond(node, u0, w, zero);
        const auto         lambda_of = [&](const Tensor<1, 2> &v) {
          return respond(node, u0, v, zero).value;
        };
        const Tensor<2, 2> fd = test_tools::finite_difference<2>(lambda_of, w);
        out() << "  u_nu = " << digits(u_old_nu + 0.022, 6)
              << "  jacobian = " << in_frame(node, r.jacobian)
              << "  finite differences = " << in_frame(node, fd, 1e-8)
              << std::endl;
        check(r.state == FrictionState::slip && near(r.jacobian, fd, 1e-8),
              "2D: slip jacobian = finite differences to 1e-8 at u_nu = " +
                digits(u_old_nu + 0.022, 3));
      }
  }


  /**
   * The linearized slip condition from a point on the slip manifold: the
   * residual |lambda' - g(w') z'/|z'|| of the linearized lambda' at
   * w' = w + eps dw, for eps, eps/2, eps/4, eps/8.
   */
  std::vector<double>
  slip_residuals(const ContactNode<3> &node,
                 const Tensor<1, 3>   &u_old,
                 const Tensor<1, 3>   &w,
                 const Tensor<1, 3>   &lambda,
                 const Tensor<1, 3>   &dw,
                 const bool            direction_term)
  {
    const Foundation f = make_foundation();
    const auto       r = respond(node, u_old, w, lambda);
    // Without the 3D term: lambda' = g' t with t frozen, the 2D law.
    const Tensor<2, 3> J =
      direction_term ? r.jacobian :
                       outer_product(r.direction, (mu * m * 0.7) * node.normal);
    std::vector<double> residuals;
    for (const double eps : {1e-2, 5e-3, 2.5e-3, 1.25e-3})
      {
        const Tensor<1, 3>   w_new      = w + eps * dw;
        const Tensor<1, 3>   lambda_new = r.value + J * (eps * dw);
        const NormalResponse normal_new =
          normal_response(f, node, u_old, w_new, k);
        const double       g_new = mu * m * normal_new.pressure;
        const Tensor<1, 3> z_new =
          lambda_new + (c * m) * node.tangential(w_new);
        residuals.push_back(
          (lambda_new - (g_new / z_new.norm()) * z_new).norm());
      }
    return residuals;
  }


  void
  test_friction_3d()
  {
    out() << "--- friction_response, 3D" << std::endl;
    const ContactNode<3> node  = node_3d();
    const Tensor<1, 3>   u_old = frame(node, 0.978, 0.3, -0.2);
    const Tensor<1, 3>   zero;
    check(std::abs(node.tangents[1] * node.normal) <= 1e-15 &&
            near(node.tangents[1], vec(0., 0.8, 0.6), 1e-15),
          "3D: t2 = t1 x n = (0, 0.8, 0.6)");

    const auto along_t2 =
      respond(node, u_old, frame(node, 0.22, 0., 0.6), zero);
    check(along_t2.state == FrictionState::slip &&
            near(along_t2.value, frame(node, 0., 0., 0.422), 1e-14),
          "3D: slip with w_tau = 0.6 t2: value g t2");

    // Off the manifold: lambda = 0.1 t1, w_tau = 0.3 t1 + 0.4 t2,
    // z = 0.4 (t1 + t2), alpha = g/|z| = 0.745998, alpha/(1-alpha) = 2.93697:
    // value = g t - alpha/(1-alpha) P lambda, P lambda = 0.05 (t1 - t2),
    //       = (0.298399 - 0.146849) t1 + (0.298399 + 0.146849) t2;
    // jacobian = t (x) 0.14 n + beta P, beta/2 = 1.46849.
    const auto slip = respond(node,
                              u_old,
                              frame(node, 0.22, 0.3, 0.4),
                              frame(node, 0., 0.1, 0.));
    out() << "slip, lambda = 0.1 t1, w_tau = 0.3 t1 + 0.4 t2:" << std::endl;
    print(node, slip);
    out() << "  direction = " << in_frame(node, slip.direction) << std::endl;
    out() << "  jacobian = " << in_frame(node, slip.jacobian) << std::endl;
    const double s = 1 / std::sqrt(2.);
    check(slip.state == FrictionState::slip &&
            near(slip.direction, frame(node, 0., s, s), 1e-14),
          "3D: slip, t = (t1 + t2)/sqrt(2)");
    check(near(slip.value, frame(node, 0., 0.151550486, 0.445247637), 1e-8),
          "3D: value g t - alpha/(1-alpha) P lambda by hand");
    Tensor<2, 3> J =
      outer_product(frame(node, 0., s, s), frame(node, 0.14, 0., 0.));
    J += 1.468485757 *
         outer_product(frame(node, 0., 1., -1.), frame(node, 0., 1., -1.));
    check(near(slip.jacobian, J, 1e-8),
          "3D: jacobian t (x) dg + beta P by hand");

    const auto stick = respond(node,
                               u_old,
                               frame(node, 0.22, 0., 0.),
                               frame(node, 0., 0.2, -0.3));
    check(stick.state == FrictionState::stick &&
            near(stick.value, frame(node, 0., 0.2, -0.3), 1e-14),
          "3D: w_tau = 0, |lambda| = 0.361 <= g: stick, value lambda");
    const auto reversed = respond(node,
                                  u_old,
                                  frame(node, 0.22, -0.1, 0.2),
                                  frame(node, 0., 1., 0.));
    check(reversed.state == FrictionState::stick &&
            near(reversed.value, frame(node, 0., 1., 0.), 1e-14),
          "3D: |z| = 0.922 > g but lambda . w_tau = -0.1 < 0: stick");
    const auto free = respond(node,
                              frame(node, -0.5, 0., 0.),
                              frame(node, -0.1, 0.3, 0.4),
                              frame(node, 0., 1., 0.));
    check(free.state == FrictionState::free && free.value.norm() == 0,
          "3D: out of contact: free, value 0");
  }


  /**
   * On the slip manifold: w_tau = 0.6 t, lambda = g t, t = cos 0.7 t1 +
   * sin 0.7 t2, so z = (g + 0.6) t.
   */
  void
  test_friction_3d_manifold()
  {
    const ContactNode<3> node  = node_3d();
    const Tensor<1, 3>   u_old = frame(node, 0.978, 0.3, -0.2);
    out() << "on the slip manifold:" << std::endl;
    const Tensor<1, 3> t      = frame(node, 0., std::cos(0.7), std::sin(0.7));
    const Tensor<1, 3> w      = 0.22 * node.normal + 0.6 * t;
    const Tensor<1, 3> lambda = 0.422 * t;
    const auto         r      = respond(node, u_old, w, lambda);
    check(r.state == FrictionState::slip && near(r.direction, t, 1e-14) &&
            near(r.value, lambda, 1e-14),
          "3D manifold: slip, t, value = lambda");
    check((node.normal * r.jacobian).norm() <= 1e-14,
          "3D manifold: n . jacobian = 0 (lambda' tangential)");
    // The exact slip solution near w: lambda*(w) = g(w) w_tau/|w_tau|.
    const auto exact = [&](const Tensor<1, 3> &v) {
      const Tensor<1, 3> v_tau = node.tangential(v);
      return (mu * m *
              normal_response(make_foundation(), node, u_old, v, k).pressure /
              v_tau.norm()) *
             v_tau;
    };
    const Tensor<2, 3> fd = test_tools::finite_difference<3>(exact, w);
    check(near(r.jacobian, fd, 1e-8),
          "3D manifold: jacobian = finite differences of g(w) w_tau/|w_tau|");

    const Tensor<1, 3>        dw = vec(0.3, -0.5, 0.7);
    const std::vector<double> linearized =
      slip_residuals(node, u_old, w, lambda, dw, true);
    const std::vector<double> frozen =
      slip_residuals(node, u_old, w, lambda, dw, false);
    double eps = 1e-2;
    for (unsigned int i = 0; i < linearized.size(); ++i, eps /= 2)
      out() << "  eps = " << digits(eps, 3)
            << "  residual = " << digits(linearized[i], 4)
            << "  residual/eps^2 = " << digits(linearized[i] / (eps * eps), 3)
            << "  (t frozen: " << digits(frozen[i], 4) << ")" << std::endl;
    bool quadratic = true, linear = true;
    for (unsigned int i = 0; i + 1 < linearized.size(); ++i)
      {
        const double ratio        = linearized[i] / linearized[i + 1];
        quadratic                 = quadratic && ratio > 3.5 && ratio < 4.5;
        const double frozen_ratio = frozen[i] / frozen[i + 1];
        linear = linear && frozen_ratio > 1.8 && frozen_ratio < 2.2;
      }
    check(quadratic && linearized[0] < 1e-3,
          "3D manifold: halving eps quarters the slip residual (ratios in "
          "[3.5, 4.5])");
    check(linear,
          "3D manifold: with t frozen only halves it (the test can tell)");
  }


  void
  test_projection()
  {
    out() << "--- projected_friction_force" << std::endl;
    const ContactNode<2> node = node_2d();
    const double         g    = 0.422;
    // In the frame: w = 0.22 n + w_tau t, lambda = lambda_tau t; the
    // projection expected_tau t.
    struct Case
    {
      std::string name;
      double      w_tau, lambda_tau, expected_tau;
      bool        solution;
    };
    const std::vector<Case> cases = {
      {"stick solution", 0., 0.3, 0.3, true},
      {"slip solution", 0.6, 0.422, 0.422, true},
      {"lambda = 0, w_tau = 0.6 t", 0.6, 0., 0.422, false},
      {"lambda = 0.3 t, w_tau = 0.05 t", 0.05, 0.3, 0.35, false},
      {"lambda = g t, w_tau = -0.6 t", -0.6, 0.422, -0.178, false}};
    for (const Case &x : cases)
      {
        const Tensor<1, 2> lambda = frame(node, 0., x.lambda_tau);
        const Tensor<1, 2> p      = projected_friction_force(
          node, g, frame(node, 0.22, x.w_tau), lambda, c);
        out() << x.name << ": " << in_frame(node, p) << std::endl;
        check(near(p, frame(node, 0., x.expected_tau), 1e-14) &&
                (near(p, lambda, 1e-14) == x.solution),
              x.name + (x.solution ? ": equals lambda" : ": differs"));
      }
    check(projected_friction_force(
            node, 0., frame(node, 0.22, 0.6), frame(node, 0., 0.3), c)
              .norm() == 0,
          "threshold 0: zero");
    ContactNode<2> constrained = node;
    constrained.unconstrained  = false;
    check(projected_friction_force(
            constrained, g, frame(node, 0.22, 0.6), frame(node, 0., 0.3), c)
              .norm() == 0,
          "constrained node: zero");

    const ContactNode<3> n3 = node_3d();
    const Tensor<1, 3>   t  = frame(n3, 0., std::cos(0.7), std::sin(0.7));
    const Tensor<1, 3>   w  = 0.22 * n3.normal + 0.6 * t;
    check(near(projected_friction_force(n3, g, w, Tensor<1, 3>(g * t), c),
               Tensor<1, 3>(g * t),
               1e-14),
          "3D slip solution (g t, w_tau = 0.6 t): equals lambda");
    const Tensor<1, 3> off = frame(n3, 0., 0.1, 0.);
    const Tensor<1, 3> p3 =
      projected_friction_force(n3, g, frame(n3, 0.22, 0.3, 0.4), off, c);
    check(near(p3,
               frame(n3, 0., g / std::sqrt(2.), g / std::sqrt(2.)),
               1e-14) &&
            !near(p3, off, 1e-3),
          "3D lambda = 0.1 t1, w_tau = 0.3 t1 + 0.4 t2: g (t1 + t2)/sqrt(2), "
          "differs");
  }
} // namespace

// The linearize_node checks, which use the helpers above.
#include "contact_law_linearization.h"


int
main(int argc, char *argv[])
{
  return test_tools::run_tests(argc,
                               argv,
                               {test_normal_response,
                                test_friction_2d_slip_and_stick,
                                test_friction_2d_free,
                                test_friction_2d_jacobian,
                                test_friction_3d,
                                test_friction_3d_manifold,
                                test_projection,
                                test_linearize_slip_2d,
                                test_linearize_saturated_stick_free_2d,
                                test_linearize_slip_3d});
}
