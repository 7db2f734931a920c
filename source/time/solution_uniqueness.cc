#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/time/solution_uniqueness.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  template <int dim>
  void
  SolutionUniqueness<dim>::measure(const TimeScheme   &scheme,
                                   ContactSolver<dim> &solver,
                                   StepStatistics     &statistics)
  {
    // doc/theory.md section 5.2: with L the law's one-sided Lipschitz
    // constant, mu_max its largest value, N_i the normal forces, kappa_i
    // the largest slope of the pressure in the unknown normal velocity and
    // theta = d w_e/d w_n,
    //   bound:       rho(S C S), S_i = sqrt(theta L N_i + mu_max^2 m_i
    //                kappa_i / 4) P_tau,i (every node with friction: a
    //                node out of contact here may touch in another
    //                solution); not evaluated where kappa is unknown;
    //   contraction: rho(S C S), S_i = sqrt(theta |mu'(s_i)| N_i) n_i n_i^T
    //                (slip nodes, n_i the slip direction).
    TimerSection       t(timer, "Friction: uniqueness measures");
    const auto        &nodes = contact_boundary.nodes();
    const unsigned int n     = nodes.size();
    const double       theta = scheme.effective_derivative();
    const double       kappa =
      foundation.pressure_lipschitz_constant(scheme.displacement_derivative(),
                                             theta);
    const double mu_max =
      friction_law->largest_value(friction_parameters.maximum_slip_rate);
    // With a slip length, the law of the step is mu_e (SlipLength).
    const SlipLength &slip_length = friction_parameters.slip_length;
    const double      lipschitz =
      slip_length.step_lipschitz_constant(lipschitz_constant, mu_max, scheme);
    const bool with_bound = lipschitz > 0 && std::isfinite(kappa);
    std::vector<Tensor<2, dim>> bound(n), contraction(n);
    bool                        any_bound = false, any_contraction = false;
    for (unsigned int i = 0; i < n; ++i)
      {
        const auto  &node  = nodes[i];
        const auto  &state = contact_state.nodes[i];
        const double N     = state.normal_force(node.weight);
        if (!node.unconstrained)
          continue;
        if (with_bound)
          {
            Tensor<2, dim> P = unit_symmetric_tensor<dim>();
            P -= outer_product(node.normal, node.normal);
            const double weight = theta * lipschitz * std::max(N, 0.) +
                                  mu_max * mu_max * node.weight * kappa / 4;
            bound[i]  = std::sqrt(weight) * P;
            any_bound = any_bound || weight > 0;
          }
        if (!(N > 0))
          continue;
        const double weakening =
          state.state == FrictionState::slip && state.slip_rate > 0 ?
            -slip_length
                .step_coefficient(*friction_law,
                                  contact_state.coefficient_state[i],
                                  state.slip_rate,
                                  scheme)
                .second *
              N * theta :
            0.;
        if (weakening > 0)
          {
            const Tensor<1, dim> d = state.slip_velocity / state.slip_rate;
            contraction[i]         = std::sqrt(weakening) * outer_product(d, d);
            any_contraction        = true;
          }
      }
    const MPI_Comm comm = discretization.comm;
    if (with_bound)
      {
        const SpectralEstimate b =
          Utilities::MPI::max(any_bound ? 1 : 0, comm) == 1 ?
            solver.compliance_radius(bound, true) :
            SpectralEstimate{0., 0.};
        statistics.uniqueness_bound       = b.lanczos;
        statistics.uniqueness_certificate = b.upper;
      }
    statistics.contraction_factor =
      Utilities::MPI::max(any_contraction ? 1 : 0, comm) == 1 ?
        solver.compliance_radius(contraction, false).lanczos :
        0.;
  }


  // count_solutions(): solution_count.cc.
  template class SolutionUniqueness<2>;
  template class SolutionUniqueness<3>;
} // namespace DynamicContact
