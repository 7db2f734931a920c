#ifndef dynamic_contact_tests_unit_contact_law_linearization_h
#define dynamic_contact_tests_unit_contact_law_linearization_h

// The linearize_node checks of contact_law.cc: the force and the block
// (its derivative in w) of a node, 2D slip (below and beyond the compliance
// cap), stick and free, and 3D slip on the slip manifold, by hand and
// against finite differences. Not a header of its own: contact_law.cc
// includes it after its reference data and helpers (k, m, mu, c,
// make_foundation, node_2d, node_3d, frame, in_frame, near), which these
// checks use.

#include <deal.II/base/tensor.h>

#include <dynamic_contact/laws/contact_law.h>

#include "test_tools.h"

namespace
{
  /**
   * Slip: force = m 2.11 n + g t = 1.055 n + 0.422 t,
   * block = m 0.7 n (x) n + t (x) 0.14 n.
   */
  void
  test_linearize_slip_2d()
  {
    out() << "--- linearize_node" << std::endl;
    const Foundation     f     = make_foundation();
    const ContactNode<2> node  = node_2d();
    const Tensor<1, 2>   u_old = frame(node, 0.978, 0.3);
    const Tensor<1, 2>   zero;
    const Tensor<1, 2>   w = frame(node, 0.22, 0.6);
    const auto l = linearize_node(f, node, u_old, w, k, true, zero, mu, c);
    out() << "slip: force = " << in_frame(node, l.force)
          << "  block = " << in_frame(node, l.block) << std::endl;
    check(l.friction.state == FrictionState::slip && l.active() &&
            near(l.force, frame(node, 1.055, 0.422), 1e-14),
          "2D slip: force 1.055 n + 0.422 t");
    Tensor<2, 2> block =
      outer_product(frame(node, 0.35, 0.), frame(node, 1., 0.));
    block += outer_product(frame(node, 0., 1.), frame(node, 0.14, 0.));
    check(near(l.block, block, 1e-14),
          "2D slip: block 0.35 n (x) n + 0.14 t (x) n");
    const auto force_of = [&](const Tensor<1, 2> &v) {
      return linearize_node(f, node, u_old, v, k, true, zero, mu, c).force;
    };
    check(near(l.block, test_tools::finite_difference<2>(force_of, w), 1e-8),
          "2D slip: block = finite differences of the force");

    const auto normal_only =
      linearize_node(f, node, u_old, w, k, false, zero, mu, c);
    check(normal_only.friction.state == FrictionState::free &&
            near(normal_only.force, frame(node, 1.055, 0.), 1e-14) &&
            near(normal_only.block,
                 Tensor<2, 2>(0.35 * outer_product(node.normal, node.normal)),
                 1e-14),
          "2D without friction: force 1.055 n, block 0.35 n (x) n");
  }


  void
  test_linearize_saturated_stick_free_2d()
  {
    const Foundation     f     = make_foundation();
    const ContactNode<2> node  = node_2d();
    const Tensor<1, 2>   u_old = frame(node, 0.978, 0.3);
    const Tensor<1, 2>   zero;
    // Beyond the compliance cap (u_nu = 2): p = 3, p' = 0, g = 0.622 <
    // |z| = 0.8: force m 3.11 n + 0.622 t, block 0.25 n (x) n + t (x) 0.1 n.
    {
      const Tensor<1, 2> u0 = frame(node, 1.978, 0.3);
      const Tensor<1, 2> w  = frame(node, 0.22, 0.8);
      const auto l = linearize_node(f, node, u0, w, k, true, zero, mu, c);
      out() << "saturated slip: force = " << in_frame(node, l.force)
            << "  block = " << in_frame(node, l.block) << std::endl;
      Tensor<2, 2> block =
        outer_product(frame(node, 0.25, 0.), frame(node, 1., 0.));
      block += outer_product(frame(node, 0., 1.), frame(node, 0.1, 0.));
      check(l.friction.state == FrictionState::slip &&
              near(l.force, frame(node, 1.555, 0.622), 1e-14) &&
              near(l.block, block, 1e-14),
            "2D saturated slip: force 1.555 n + 0.622 t, block by hand");
    }
    // Stick: force = 1.055 n + lambda_tau, block = normal part only.
    {
      const auto l = linearize_node(f,
                                    node,
                                    u_old,
                                    frame(node, 0.22, 0.),
                                    k,
                                    true,
                                    frame(node, 0., 0.3),
                                    mu,
                                    c);
      out() << "stick: force = " << in_frame(node, l.force)
            << "  block = " << in_frame(node, l.block) << std::endl;
      check(l.friction.state == FrictionState::stick && l.active() &&
              near(l.force, frame(node, 1.055, 0.3), 1e-14) &&
              near(l.block,
                   Tensor<2, 2>(0.35 * outer_product(node.normal, node.normal)),
                   1e-14),
            "2D stick: force 1.055 n + 0.3 t, block 0.35 n (x) n");
    }
    // Free: nothing.
    {
      const auto l = linearize_node(f,
                                    node,
                                    frame(node, -0.5, 0.),
                                    frame(node, -0.1, 0.6),
                                    k,
                                    true,
                                    frame(node, 0., 0.3),
                                    mu,
                                    c);
      check(l.friction.state == FrictionState::free && !l.active() &&
              l.force.norm() == 0 && l.block.norm() == 0,
            "2D out of contact: free, no force, no block, not active");
    }
  }


  /**
   * 3D on the slip manifold: force = 1.055 n + g t, block = the
   * derivative of m p n + g(w) w_tau/|w_tau|.
   */
  void
  test_linearize_slip_3d()
  {
    const Foundation     f   = make_foundation();
    const ContactNode<3> n3  = node_3d();
    const Tensor<1, 3>   u0  = frame(n3, 0.978, 0.3, -0.2);
    const Tensor<1, 3>   t   = frame(n3, 0., std::cos(0.7), std::sin(0.7));
    const Tensor<1, 3>   w   = 0.22 * n3.normal + 0.6 * t;
    const Tensor<1, 3>   lam = 0.422 * t;
    const auto           l = linearize_node(f, n3, u0, w, k, true, lam, mu, c);
    out() << "3D slip: force = " << in_frame(n3, l.force) << std::endl;
    check(l.friction.state == FrictionState::slip &&
            near(l.force, Tensor<1, 3>(1.055 * n3.normal + lam), 1e-14),
          "3D slip: force 1.055 n + g t");
    const auto force_of = [&](const Tensor<1, 3> &v) {
      const NormalResponse r     = normal_response(f, n3, u0, v, k);
      const Tensor<1, 3>   v_tau = n3.tangential(v);
      return Tensor<1, 3>(m * r.pressure * n3.normal +
                          (mu * m * r.pressure / v_tau.norm()) * v_tau);
    };
    check(near(l.block, test_tools::finite_difference<3>(force_of, w), 1e-8),
          "3D slip: block = finite differences of m p n + g w_tau/|w_tau|");
  }
} // namespace

#endif
