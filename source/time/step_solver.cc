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
    , friction_parameters(friction_parameters)
    , timer(timer)
    , details(details)
    , friction(law_has_friction(friction_law))
    , lipschitz_constant(friction && !friction_law->is_constant() ?
                           friction_law->one_sided_lipschitz_constant(
                             friction_parameters.maximum_slip_rate) :
                           0.)
    , solvers(discretization,
              bulk,
              contact_boundary,
              foundation,
              solver_parameters,
              timer,
              details,
              friction,
              lipschitz_constant > 0 ?
                friction_parameters.coefficient_tolerance / lipschitz_constant :
                std::numeric_limits<double>::infinity())
    , uniqueness(discretization,
                 contact_boundary,
                 contact_state,
                 foundation,
                 friction_law,
                 this->friction_parameters, // the copy kept here
                 lipschitz_constant,
                 timer,
                 details)
  {}


  template <int dim>
  StepSolver<dim>::~StepSolver() = default;


  template <int dim>
  void
  StepSolver<dim>::reinit(const double        complementarity_constant,
                          const unsigned int  steps_per_matrix,
                          const MemoryBudget &memory)
  {
    solvers.reinit(complementarity_constant, steps_per_matrix, memory);

    contact_state.reinit(contact_boundary,
                         friction ? friction_law->value(0) : 0.);
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
                                      solvers.complementarity_constant() * k,
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


  template class StepSolver<2>;
  template class StepSolver<3>;
} // namespace DynamicContact
