// The slip-rate law inside the Newton linearization (Friction/Linearization
// = coupled) and the uniqueness measures of a step (doc/theory.md sections
// 5.1 and 5.2):
//
// 1. The coupled slip Jacobian against finite differences of the friction
//    force lambda(w) = mu(|w_tau|) m (p + q) t: 2D, and 3D on the slip
//    manifold (with t = w_tau/|w_tau| there), for a law whose derivative
//    matters (mu(s) = 0.3 exp(-2 s) + 0.5 at s = 0.6); at the onset of slip
//    (w_tau = 0) the direction of the slip force stands for w_tau/|w_tau|;
//    the weakening limit cuts the slip-rate term to minus the limit.
// 2. largest_eigenvalue() on a matrix with known eigenvalues.
// 3. A block sliding at v0 = 2 m/s, sheared by T and pressed by P, on one
//    step (prm/sliding_block.prm with a slip-weakening law mu(s) = 0.2
//    exp(-alpha s) + 0.4, T = 4e5 Pa, P = 1e6 Pa): as a rigid body of mass
//    M, the step's slip rate s solves (M/k)(s - v0) = T - mu(s) N, and it
//    may stick if T + M v0/k <= mu(0) N. The bound rho(C Lambda) (Lambda_i
//    = L N_i + mu_max^2 m_i kappa_i/4) is a sufficient condition: where
//    its certificate is below 1 the step must have one solution; where it
//    is 1 or more nothing follows. Three cases:
//    - alpha = 2000, k = 0.01: three solutions (stick, a slip rate near
//      the onset, s = 2 m/s), bound about 2e4; the frozen loop finds the
//      fast slip, the coupled linearization from the same start the stick;
//    - alpha = 2000, k = 0.001: one solution (it can stick only for k >=
//      M v0/((a - b) N) = 2e-3 s) although the bound is about 2e3: both
//      linearizations end at the same slip rate;
//    - alpha = 0.01, k = 0.001, a soft foundation: one solution, proven
//      (certificate below 1, above the Lanczos value).
//    In each the bound lies at or somewhat above its rigid-body value (the
//    elastic block is more compliant than the rigid one), and the starts of
//    Friction/Count solutions find two solutions where there are three and
//    one where there is one.
// 4. The paper's small scene with the coupled linearization, on both contact
//    solvers: completed, the loop's stopping rule met at every step, two
//    passes a step (the coupled one and the frozen one that confirms it),
//    fewer passes than the frozen loop, the energy balance; with Friction/
//    Count solutions the same answers, and steps with several solutions
//    found. (Its Newton iterations are not fewer on this coarse scene, so
//    they are not checked.)

#include <deal.II/lac/full_matrix.h>

#include <dynamic_contact/contact/largest_eigenvalue.h>
#include <dynamic_contact/laws/contact_law.h>

#include "test_tools.h"

#include <cmath>

using namespace DynamicContact;
using test_tools::check;
using test_tools::digits;
using test_tools::out;

namespace
{
  const double k = 0.1, m = 0.5, c = 2.;

  Foundation
  foundation()
  {
    return Foundation(CappedRamp(2., 3.), CappedRamp(0.5, 0.25), false);
  }

  template <int dim>
  ContactNode<dim>
  make_node()
  {
    ContactNode<dim> node{};
    node.constraint_map = unit_symmetric_tensor<dim>();
    node.unconstrained  = true;
    node.weight         = m;
    node.gap            = 0;
    if (dim == 2)
      {
        node.normal[0]      = 0.6;
        node.normal[1]      = -0.8;
        node.tangents[0][0] = 0.8;
        node.tangents[0][1] = 0.6;
      }
    else
      {
        node.normal[1]                  = 0.6;
        node.normal[dim - 1]            = -0.8;
        node.tangents[0][0]             = 1;
        node.tangents[dim - 2][1]       = 0.8;
        node.tangents[dim - 2][dim - 1] = 0.6;
      }
    return node;
  }

  /** The coupled friction response at (u_old, w, lambda). */
  template <int dim>
  FrictionResponse<dim>
  coupled_response(const ContactNode<dim> &node,
                   const FrictionLaw      &law,
                   const Tensor<1, dim>   &u_old,
                   const Tensor<1, dim>   &w,
                   const Tensor<1, dim>   &lambda,
                   const double limit = std::numeric_limits<double>::infinity())
  {
    const double s = node.tangential(w).norm();
    return friction_response(node,
                             normal_response(foundation(), node, u_old, w, k),
                             w,
                             lambda,
                             law.value(s),
                             c,
                             1.,
                             law.derivative(s),
                             limit);
  }



  template <int dim>
  void
  test_jacobian()
  {
    const std::string      d    = std::to_string(dim) + "D: ";
    const ContactNode<dim> node = make_node<dim>();
    ExponentialFriction    law(0.8, 0.5, 2.);
    // u_nu = 1, w_nu = 0.22 (p = 2, q = 0.11): N = m 2.11.
    const Tensor<1, dim> u_old = 0.978 * node.normal + 0.3 * node.tangents[0];
    Tensor<1, dim>       t     = node.tangents[0];
    if (dim == 3)
      t = std::cos(0.7) * node.tangents[0] +
          std::sin(0.7) * node.tangents[dim - 2];
    const Tensor<1, dim> w = 0.22 * node.normal + 0.6 * t;
    // On the slip manifold: lambda = g t, g = mu(0.6) m 2.11.
    const double         g      = law.value(0.6) * m * 2.11;
    const Tensor<1, dim> lambda = g * t;
    const auto           r      = coupled_response(node, law, u_old, w, lambda);
    check(r.state == FrictionState::slip &&
            (r.value - lambda).norm() <= 1e-14 * g && !r.limited,
          d + "slip on the manifold, value g t with g = mu(|w_tau|) N");
    // The exact slip force near w: mu(|v_tau|) N(v) v_tau/|v_tau|.
    const auto exact = [&](const Tensor<1, dim> &v) {
      const Tensor<1, dim> v_tau = node.tangential(v);
      const double         s     = v_tau.norm();
      return (law.value(s) * m *
              normal_response(foundation(), node, u_old, v, k).pressure / s) *
             v_tau;
    };
    const Tensor<2, dim> fd = test_tools::finite_difference<dim>(exact, w);
    out() << d << "|jacobian - finite differences| = "
          << digits((r.jacobian - fd).norm() < 1e-9 ? 0. :
                                                      (r.jacobian - fd).norm(),
                    2)
          << ", slip-rate term t . J t = " << digits(t * (r.jacobian * t), 6)
          << std::endl;
    check((r.jacobian - fd).norm() <= 1e-8 * r.jacobian.norm(),
          d + "coupled jacobian = finite differences of mu(|w_tau|) N t");
    // The slip-rate term is mu'(s) N: t . J t = mu'(0.6) m 2.11 (+ the
    // frozen part, zero along t: dg/dw is normal then).
    check(std::abs(t * (r.jacobian * t) - law.derivative(0.6) * m * 2.11) <=
            1e-12,
          d + "t . J t = mu'(s) m (p + q)");

    // The weakening limit: the slip-rate term is cut to minus the limit.
    const double limit   = 0.1;
    const auto   limited = coupled_response(node, law, u_old, w, lambda, limit);
    check(limited.limited &&
            std::abs(t * (limited.jacobian * t) + limit) <= 1e-12,
          d + "weakening limit 0.1: t . J t = -0.1, flagged");

    // The onset of slip: w_tau = 0, lambda beyond the static threshold
    // mu(0) N: slip along t, the slip-rate term along t (mu'(0) N).
    const Tensor<1, dim> w0    = 0.22 * node.normal;
    const double         above = 1.2 * law.value(0) * m * 2.11;
    const auto onset = coupled_response(node, law, u_old, w0, above * t);
    check(onset.state == FrictionState::slip &&
            (onset.direction - t).norm() <= 1e-14 &&
            std::abs(t * (onset.jacobian * t) - law.derivative(0) * m * 2.11) <=
              1e-12,
          d + "onset of slip (w_tau = 0): slip along t, the slip-rate term "
              "along t");
    // Stick: no Jacobian (lambda is a multiplier).
    const auto stick =
      coupled_response(node, law, u_old, w0, (0.5 * law.value(0) * m) * t);
    check(stick.state == FrictionState::stick && stick.jacobian.norm() == 0,
          d + "stick below mu(0) N: no jacobian");
  }


  void
  test_eigenvalue()
  {
    // A = Q diag(4, 1, 0.5, 0) Q^T with Q the (orthogonal, symmetric)
    // discrete sine transform: largest eigenvalue 4.
    const unsigned int n = 4;
    FullMatrix<double> Q(n, n), A(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        Q(i, j) = std::sqrt(2. / (n + 1)) *
                  std::sin(M_PI * (i + 1) * (j + 1) / (n + 1));
    const double lambda[] = {4, 1, 0.5, 0};
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int p = 0; p < n; ++p)
          A(i, j) += Q(i, p) * lambda[p] * Q(j, p);
    const auto apply = [&](const std::vector<double> &x,
                           std::vector<double>       &y) {
      for (unsigned int i = 0; i < n; ++i)
        {
          y[i] = 0;
          for (unsigned int j = 0; j < n; ++j)
            y[i] += A(i, j) * x[j];
        }
    };
    const auto   identity = [](const double v) { return v; };
    const double largest =
      largest_eigenvalue(apply, {1., 0.2, -0.3, 0.5}, identity);
    check(std::abs(largest - 4) <= 1e-12,
          "largest_eigenvalue: 4 of Q diag(4, 1, 0.5, 0) Q^T");
    check(largest_eigenvalue(apply, {0., 0., 0., 0.}, identity) == 0,
          "largest_eigenvalue: 0 from a zero start");
    // The upper bound from |A|: never below 4, at most the largest
    // absolute row sum (x = 1), and tighter with x near |A|'s Perron
    // vector.
    double row_sum = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        double sum = 0;
        for (unsigned int j = 0; j < n; ++j)
          sum += std::abs(A(i, j));
        row_sum = std::max(row_sum, sum);
      }
    const auto apply_abs = [&](const std::vector<std::vector<double>> &xs,
                               std::vector<std::vector<double>>       &ys) {
      for (std::size_t v = 0; v < xs.size(); ++v)
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            ys[v][i] += std::abs(A(i, j)) * xs[v][j];
    };
    const double ones = collatz_upper_bound(apply_abs, {{1., 1., 1., 1.}});
    std::vector<double> ritz;
    largest_eigenvalue(apply, {1., 0.2, -0.3, 0.5}, identity, 1e-10, 60, &ritz);
    std::vector<double> x(n);
    for (unsigned int i = 0; i < n; ++i)
      x[i] = std::abs(ritz[i]) + 1e-3;
    const double both = collatz_upper_bound(apply_abs, {{1., 1., 1., 1.}, x});
    check(std::abs(ones - row_sum) <= 1e-12 * row_sum && both <= ones &&
            both >= 4 * (1 - 1e-12),
          "collatz_upper_bound: 4 <= bound <= largest absolute row sum (" +
            digits(both, 4) + " <= " + digits(row_sum, 4) + ")");
  }


  /** One step of the sliding block (doc of this file, item 3). */
  struct BlockCase
  {
    std::string  name;
    double       decay_rate; // alpha of mu(s) = 0.2 exp(-alpha s) + 0.4
    double       k;          // the time step
    double       stiffness;  // c_nu of the foundation
    double       damping;    // d_nu of the foundation
    unsigned int solutions;  // of the rigid block's step
  };


  StepRecord<2>
  block_step(const BlockCase &c, const std::string &linearization)
  {
    const auto series =
      test_tools::run<2>(
        test_tools::scene("sliding_block.prm"),
        {"Output/Directory=output-" + c.name + "-" + linearization,
         "Time/End time=" + std::to_string(c.k),
         "Time/Time step=" + std::to_string(c.k),
         "Boundary conditions/Traction function/Function constants=P=1e6, "
         "T=4e5",
         "Initial conditions/Velocity/Function expression=2; 0",
         "Foundation/Normal compliance/Capped ramp/Stiffness=" +
           std::to_string(c.stiffness),
         "Foundation/Normal damping/Capped ramp/Coefficient=" +
           std::to_string(c.damping),
         "Friction/Law=exponential",
         "Friction/Exponential/Static coefficient=0.6",
         "Friction/Exponential/Dynamic coefficient=0.4",
         "Friction/Exponential/Decay rate=" + std::to_string(c.decay_rate),
         "Friction/Linearization=" + linearization,
         "Friction/Count solutions=true",
         "Time/Cut back where not unique=true"})
        ->time_series();
    return series.back();
  }


  /** The block's mass, initial velocity, shear force and largest mu. */
  const double block_mass = 1000 * 0.2 * 1, v0 = 2, T = 4e5, mu_max = 0.6;

  /** The rigid block's step: its number of solutions and its fast slip. */
  struct RigidBlock
  {
    unsigned int solutions;
    double       fast;
  };

  /**
   * The rigid block's solutions: stick if the friction it needs stays below
   * mu(0) N; slip rates where h(s) = (M/k)(s - v0) - T + mu(s) N changes
   * sign.
   */
  RigidBlock
  rigid_block(const BlockCase &c, const double N)
  {
    const double M     = block_mass;
    const double alpha = c.decay_rate;
    const auto   mu    = [&](const double s) {
      return 0.2 * std::exp(-alpha * s) + 0.4;
    };
    const bool   can_stick = T + M * v0 / c.k <= mu(0) * N;
    unsigned int roots     = 0;
    double       previous  = M / c.k * (0 - v0) - T + mu(0) * N;
    double       fast      = 0;
    for (double s = 1e-6; s < 20; s *= 1.001)
      {
        const double h = M / c.k * (s - v0) - T + mu(s) * N;
        if ((h > 0) != (previous > 0))
          {
            ++roots;
            fast = s;
          }
        previous = h;
      }
    return {roots + (can_stick ? 1 : 0), fast};
  }


  /**
   * One linearization of one case of the block; @p first_velocity: the
   * mean velocity of the case's first (frozen) run, or -1.
   */
  void
  check_block_step(const BlockCase   &c,
                   const std::string &linearization,
                   double            &first_velocity)
  {
    const double M               = block_mass;
    const auto   r               = block_step(c, linearization);
    const auto  &st              = r.statistics;
    const double N               = r.normal_force;
    const double alpha           = c.decay_rate;
    const auto [solutions, fast] = rigid_block(c, N);
    // The rigid translation's Rayleigh quotient of the bound:
    // (k/M) sum_i Lambda_i, Lambda_i = L N_i + mu_max^2 m_i kappa/4
    // (theta = 1, sum_i m_i = 1, kappa = k c_nu + d_nu).
    const double rigid =
      (alpha * 0.2 * N +
       mu_max * mu_max * (c.k * c.stiffness + c.damping) / 4) *
      c.k / M;
    // The block's mean tangential velocity from its momentum:
    // (M/k)(v - v0) = T - F_t, F_t the friction force.
    const double slip_rate = v0 + c.k * (T - std::abs(r.tangential_force)) / M;
    const std::string prefix = c.name + ", " + linearization + ": ";
    out() << prefix << "the rigid block has " << solutions
          << " solution(s); mean tangential velocity " << digits(slip_rate, 3)
          << " m/s, bound " << digits(st.uniqueness_bound, 3) << " (rigid body "
          << digits(rigid, 3) << "), certificate "
          << (st.uniqueness_certificate < 0 ?
                std::string("none") :
                digits(st.uniqueness_certificate, 3))
          << ", slip nodes " << st.n_slip << ", stick nodes " << st.n_stick
          << std::endl;
    check(solutions == c.solutions,
          prefix + std::to_string(c.solutions) + " solution(s)");
    // The block's deformation only adds compliance.
    check(st.uniqueness_bound >= (1 - 1e-9) * rigid &&
            st.uniqueness_bound <= 1.25 * rigid,
          prefix + "bound between its rigid translation's value "
                   "and 1.25 times it");
    // A sufficient condition: a certificate below 1 implies one
    // solution; above 1, nothing. The certificate bounds the
    // Lanczos value from above, and is made only below 1.
    if (st.uniqueness_certificate >= 0 && st.uniqueness_certificate < 1)
      check(solutions == 1 && st.uniqueness_certificate >= st.uniqueness_bound,
            prefix + "proven unique: one solution, certificate >= "
                     "the Lanczos value");
    else
      check(st.uniqueness_bound >= 1 && st.uniqueness_certificate == -1,
            prefix + "bound >= 1: nothing proven, no certificate");
    // The starts' count (Friction/Count solutions): two distinct
    // solutions found prove several; where there is one, every
    // start that converged reached it.
    check(c.solutions > 1 ? st.solutions >= 2 : st.solutions == 1,
          prefix + "the starts found " + std::to_string(st.solutions) +
            " distinct solution(s) (" + std::to_string(st.failed_starts) +
            " reached none)");
    check(st.contraction_factor < 1 && r.cutbacks == 0,
          prefix + "contraction factor < 1 at the solution found, "
                   "no cut-back");
    if (c.solutions == 3 && linearization == "coupled")
      // The same step, another of its solutions: the coupled
      // Newton iteration, from the same start, ends at stick.
      check(st.n_slip == 0 && st.n_stick > 0 && slip_rate < 0.05 * fast &&
              r.relative_energy_defect() < 1e-8,
            prefix + "another solution of the same step found: the "
                     "block sticks (its mean velocity below 5 % of "
                     "the fast slip)");
    else
      check(st.n_stick == 0 && std::abs(slip_rate - fast) <= 0.02 * fast,
            prefix + "the (fast) slip root found to 2 %, s = " +
              digits(fast, 3) + " m/s");
    if (c.solutions == 1 && first_velocity >= 0)
      check(std::abs(slip_rate - first_velocity) <= 1e-6 * first_velocity,
            prefix + "the same solution as the frozen loop (1e-6)");
    first_velocity = slip_rate;
  }


  void
  test_block()
  {
    // A: three solutions; B: one, but a bound far above 1 (it can stick
    // only for k >= M v0/((a - b) N) = 2e-3 s); C: one, and proven (a soft
    // foundation: the coupling through the normal forces is small).
    const std::vector<BlockCase> cases = {
      {"steep-k1e-2", 2000., 0.01, 1e10, 1e8, 3},
      {"steep-k1e-3", 2000., 0.001, 1e10, 1e8, 1},
      {"mild-soft", 0.01, 0.001, 1e8, 1e5, 1}};
    for (const BlockCase &c : cases)
      {
        double first_velocity = -1;
        for (const std::string linearization : {"frozen", "coupled"})
          check_block_step(c, linearization, first_velocity);
      }
  }


  void
  test_paper_scene()
  {
    std::vector<std::vector<StepRecord<2>>> frozen, coupled;
    for (const std::string solver : {"condensed", "assembled"})
      for (const std::string linearization : {"frozen", "coupled"})
        (linearization == "frozen" ? frozen : coupled)
          .push_back(
            test_tools::run<2>(
              test_tools::scene("barboteu_danan_2016_small.prm"),
              {"Solver/Contact solver=" + solver,
               "Friction/Linearization=" + linearization,
               "Output/Directory=output-paper-" + solver + "-" + linearization})
              ->time_series());
    // Friction/Count solutions solves each step again from other starts:
    // the run's own answers stay those of its loop, to the bit, and on this
    // scene the starts find steps with several solutions.
    const auto counted =
      test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                         {"Solver/Contact solver=condensed",
                          "Friction/Count solutions=true",
                          "Output/Directory=output-paper-count"})
        ->time_series();
    bool         same    = counted.size() == frozen[0].size();
    unsigned int several = 0, failed = 0;
    for (unsigned int n = 1; same && n < counted.size(); ++n)
      {
        const auto &a = counted[n], &b = frozen[0][n];
        same =
          a.normal_force == b.normal_force &&
          a.tangential_force == b.tangential_force &&
          a.terms.energy.total() == b.terms.energy.total() &&
          a.statistics.newton_iterations == b.statistics.newton_iterations &&
          a.statistics.convexification_iterations ==
            b.statistics.convexification_iterations;
        several += a.statistics.solutions > 1;
        failed += a.statistics.failed_starts;
      }
    check(same,
          "paper small, Count solutions: the run's answers and iteration "
          "counts those of the frozen loop alone, to the bit");
    check(several > 0 && failed < counted.size(),
          "paper small, Count solutions: steps with two or more distinct "
          "solutions found");
    for (unsigned int s = 0; s < 2; ++s)
      {
        const std::string name =
          std::string("paper small, ") + (s == 0 ? "condensed" : "assembled");
        const auto  &series = coupled[s];
        unsigned int passes = 0, passes_frozen = 0, two = 0, fallbacks = 0;
        bool         rule = true, balance = true;
        for (unsigned int n = 1; n < series.size(); ++n)
          {
            const auto &st = series[n].statistics;
            passes += st.convexification_iterations;
            two += st.convexification_iterations <= 2;
            fallbacks += st.coupled_fallbacks;
            rule = rule && st.convexification_converged &&
                   st.coefficient_residual <= 1e-6;
            balance = balance && series[n].relative_energy_defect() < 1e-8 &&
                      series[n].relative_min_dissipation() >= -1e-12;
          }
        for (unsigned int n = 1; n < frozen[s].size(); ++n)
          passes_frozen += frozen[s][n].statistics.convexification_iterations;
        const unsigned int steps = series.size() - 1;
        check(steps == 128 && rule,
              name + ": 128 steps, each with the loop's stopping rule met");
        check(two >= steps * 9 / 10 && fallbacks <= steps / 20,
              name + ": two passes in at least 90 % of the steps, fallbacks "
                     "in at most 5 %");
        check(passes < 0.75 * passes_frozen,
              name + ": under 3/4 of the frozen loop's passes");
        check(balance, name + ": energy balance closed, dissipation >= 0");
      }
  }
} // namespace


int
main(int argc, char *argv[])
{
  return test_tools::run_tests(argc,
                               argv,
                               {test_jacobian<2>,
                                test_jacobian<3>,
                                test_eigenvalue,
                                test_block,
                                test_paper_scene});
}
