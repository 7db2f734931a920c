#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/assembled_solver.h>
#include <dynamic_contact/contact/condensed_solver.h>
#include <dynamic_contact/time/step_solver.h>

#include <cmath>
#include <limits>

namespace DynamicContact
{
  namespace
  {
    /** mu = 0 means no friction: no multiplier, no sets, no loop. */
    bool
    law_has_friction(const FrictionLaw *law)
    {
      if (law == nullptr)
        return false;
      if (law->is_constant() && law->value(0) == 0)
        return false;
      return true;
    }
  } // namespace


  template <int dim>
  StepSolver<dim>::StepSolver(const Discretization<dim>  &discretization,
                              const BulkOperator<dim>    &bulk,
                              const ContactBoundary<dim> &contact_boundary,
                              ContactState<dim>          &contact_state,
                              const Foundation           &foundation,
                              const FrictionLaw          *friction_law,
                              const Parameters::Solver   &solver_parameters,
                              const Parameters::Friction &friction_parameters,
                              TimerOutput                &timer,
                              const ConditionalOStream   &details)
    : discretization(discretization)
    , bulk(bulk)
    , contact_boundary(contact_boundary)
    , contact_state(contact_state)
    , foundation(foundation)
    , friction_law(friction_law)
    , parameters(solver_parameters)
    , friction_parameters(friction_parameters)
    , timer(timer)
    , details(details)
    , friction(law_has_friction(friction_law))
    , lipschitz_constant(friction && !friction_law->is_constant() ?
                           friction_law->one_sided_lipschitz_constant(
                             friction_parameters.maximum_slip_rate) :
                           0.)
  {}


  template <int dim>
  StepSolver<dim>::~StepSolver() = default;


  template <int dim>
  void
  StepSolver<dim>::reinit(const double        complementarity_constant,
                          const unsigned int  steps_per_matrix,
                          const MemoryBudget &memory)
  {
    c_t  = complementarity_constant;
    plan = plan_solver(parameters,
                       dim,
                       discretization.dof_handler.n_dofs(),
                       contact_boundary.n_global_nodes(),
                       steps_per_matrix,
                       discretization.comm,
                       memory);
    planned_parameters = plan.solver_parameters(parameters);
    details << "  solver plan: " << plan.description() << std::endl;
    solvers.clear();

    contact_state.reinit(contact_boundary,
                         friction ? friction_law->value(0) : 0.);
  }


  template <int dim>
  ContactSolver<dim> &
  StepSolver<dim>::solver_for(const TimeScheme &scheme)
  {
    auto &solver = solvers[scheme.theta()];
    if (!solver)
      {
        ContactProblem<dim> problem{discretization,
                                    bulk,
                                    contact_boundary,
                                    foundation,
                                    planned_parameters,
                                    timer,
                                    details,
                                    friction,
                                    c_t};
        if (lipschitz_constant > 0)
          problem.slip_rate_accuracy =
            friction_parameters.coefficient_tolerance / lipschitz_constant;
        solver = planned_parameters.contact_solver_plugin(plan.contact_solver)
                   .create(problem);
        solver->reinit();
      }
    return *solver;
  }


  template <int dim>
  void
  StepSolver<dim>::update_states(const TimeScheme                  &scheme,
                                 const std::vector<Tensor<1, dim>> &u_old_nodes,
                                 const std::vector<Tensor<1, dim>> &w_old_nodes,
                                 const Vector_t                    &w,
                                 Statistics                        &statistics)
  {
    const auto       &nodes     = contact_boundary.nodes();
    const auto       &mu        = contact_state.mu;
    const auto       &lambda    = contact_state.lambda;
    auto             &states    = contact_state.nodes;
    const double k         = scheme.time_step();
    unsigned int n_contact = 0, n_stick = 0, n_slip = 0;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const unsigned int   g   = i;
        const Tensor<1, dim> wi  = nodes[i].value(w);
        const Tensor<1, dim> w_e = scheme.weighted(wi, w_old_nodes[g]);
        auto                &s   = states[i];
        s.normal                 = normal_response(
          foundation, nodes[i], u_old_nodes[g], w_old_nodes[g], wi, scheme);
        s.friction_force = lambda[g];
        s.mu             = mu[g];
        s.slip_velocity  = nodes[i].tangential(w_e);
        s.slip_rate      = s.slip_velocity.norm();
        s.state          = FrictionState::free;
        if (friction)
          s.state = friction_response(nodes[i],
                                      s.normal,
                                      w_e,
                                      lambda[g],
                                      mu[g],
                                      c_t * k,
                                      scheme.effective_derivative())
                      .state;
        if (s.normal.pressure > 0)
          ++n_contact;
        n_stick += (s.state == FrictionState::stick);
        n_slip += (s.state == FrictionState::slip);
      }
    const MPI_Comm comm  = discretization.comm;
    statistics.n_contact = Utilities::MPI::sum(n_contact, comm);
    statistics.n_stick   = Utilities::MPI::sum(n_stick, comm);
    statistics.n_slip    = Utilities::MPI::sum(n_slip, comm);
  }


  template <int dim>
  void
  StepSolver<dim>::start_coefficient_states(const Vector_t &w0)
  {
    if (!friction)
      return;
    const auto  values = contact_boundary.values(w0);
    const auto &nodes  = contact_boundary.nodes();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      contact_state.coefficient_state[i] =
        friction_law->value(nodes[i].tangential(values[i]).norm());
  }


  template <int dim>
  void
  StepSolver<dim>::advance_coefficient_states(const TimeScheme &scheme)
  {
    auto &state = contact_state.coefficient_state;
    for (unsigned int i = 0; i < state.size(); ++i)
      state[i] = friction_parameters.slip_length.end_state(
        *friction_law, state[i], contact_state.nodes[i].slip_rate, scheme);
  }


  template <int dim>
  void
  StepSolver<dim>::measure_uniqueness(const TimeScheme   &scheme,
                                      ContactSolver<dim> &solver,
                                      Statistics         &statistics)
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
    TimerSection        t(timer, "Friction: uniqueness measures");
    const auto         &nodes = contact_boundary.nodes();
    const unsigned int  n     = nodes.size();
    const double        theta = scheme.effective_derivative();
    const double        kappa =
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
            contraction[i]  = std::sqrt(weakening) * outer_product(d, d);
            any_contraction = true;
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


  template class StepSolver<2>;
  template class StepSolver<3>;
} // namespace DynamicContact
