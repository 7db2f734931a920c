#include <deal.II/base/mpi.h>

#include <dynamic_contact/time/energy_balance.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace DynamicContact
{
  double
  EnergyBalanceTerms::min_dissipation_term() const
  {
    return std::min({inertia,
                     elastic,
                     viscous,
                     compliance_sign_definite ?
                       compliance :
                       std::numeric_limits<double>::infinity(),
                     damping,
                     friction + friction_slack});
  }


  double
  EnergyBalanceTerms::scale(const double previous_energy) const
  {
    return std::max({std::abs(energy.total()),
                     std::abs(previous_energy),
                     std::abs(load_work),
                     std::abs(dissipation()),
                     1e-300});
  }


  EnergyBalanceTerms
  bathe_terms(const EnergyBalanceTerms &first,
              const Energy             &extrapolated,
              const EnergyBalanceTerms &second,
              const double              extrapolation_work,
              const double              previous_energy)
  {
    EnergyBalanceTerms t;
    t.energy    = second.energy;
    t.load_work = first.load_work + second.load_work + extrapolation_work;
    const Energy &half = first.energy;
    t.inertia =
      first.inertia + first.elastic + second.inertia + second.elastic -
      ((extrapolated.kinetic - half.kinetic) +
       (extrapolated.elastic - half.elastic) +
       (extrapolated.foundation - half.foundation) - extrapolation_work);
    t.elastic    = 0;
    t.viscous    = first.viscous + second.viscous;
    t.compliance = first.compliance + second.compliance;
    t.damping    = first.damping + second.damping;
    t.friction       = first.friction + second.friction;
    t.friction_slack = first.friction_slack + second.friction_slack;
    t.close(previous_energy);
    return t;
  }


  EnergyBalanceTerms
  sdirk_terms(const EnergyBalanceTerms &first,
              const EnergyBalanceTerms &second,
              const double              previous_energy,
              const double              old_foundation,
              const Energy             &hat_energy,
              const Energy             &end_energy,
              const double              numerical,
              const double              weight)
  {
    EnergyBalanceTerms t;
    t.energy    = end_energy;
    t.load_work = weight * (first.load_work + second.load_work);
    t.inertia   = numerical;
    t.elastic   = 0;
    t.viscous   = weight * (first.viscous + second.viscous);
    t.damping   = weight * (first.damping + second.damping);
    t.friction  = weight * (first.friction + second.friction);
    t.friction_slack =
      std::abs(weight) * (first.friction_slack + second.friction_slack);
    // A stage's compliance power p(U_i) (U_i - start_i) is its term plus
    // the change of Pi over the stage.
    const double power =
      first.compliance + (first.energy.foundation - old_foundation) +
      second.compliance + (second.energy.foundation - hat_energy.foundation);
    t.compliance = weight * power - (end_energy.foundation - old_foundation);
    t.compliance_sign_definite = false;
    t.close(previous_energy);
    return t;
  }



  template <int dim>
  Energy
  EnergyBalance<dim>::energy(const Vector_t &u, const Vector_t &w) const
  {
    Energy e;
    e.kinetic    = 0.5 * density * bulk.mass_product(w, w);
    e.elastic    = 0.5 * bulk.elastic_product(u, u);
    e.foundation = foundation_energy(u);
    return e;
  }


  template <int dim>
  double
  EnergyBalance<dim>::foundation_energy(const Vector_t &u) const
  {
    double sum = 0;
    for (const auto &node : contact_boundary.nodes())
      sum += node.weight * foundation.compliance().primitive(
                             node.value(u) * node.normal - node.gap);
    return Utilities::MPI::sum(sum, comm);
  }


  template <int dim>
  EnergyBalanceTerms
  EnergyBalance<dim>::step_terms(
    const Vector_t                           &u_old,
    const Vector_t                           &w_old,
    const Vector_t                           &u,
    const Vector_t                           &w,
    const Vector_t                           &load,
    const TimeScheme                         &scheme,
    const std::vector<ContactNodeState<dim>> &states,
    const double                              previous_energy) const
  {
    const double       k = scheme.time_step();
    EnergyBalanceTerms t;
    t.energy = energy(u, w);

    // The scratch vector takes the layout of the current mesh (it changes
    // with adaptive refinement and repartitioning).
    difference.reinit(u, true);
    difference = u;
    difference -= u_old;
    t.load_work = load * difference;
    t.elastic   = scheme.numerical_dissipation_factor() *
                bulk.elastic_product(difference, difference);
    difference = w;
    difference -= w_old;
    t.inertia = scheme.numerical_dissipation_factor() * density *
                bulk.mass_product(difference, difference);
    if (bulk.has_viscosity())
      {
        difference = w;
        scheme.weigh(difference, w_old); // w_e
        t.viscous = k * bulk.viscous_product(difference, difference);
      }

    // Nodal terms, with the states of the converged solve.
    const auto &nodes      = contact_boundary.nodes();
    const auto &p          = foundation.compliance();
    double compliance = 0, damping = 0, friction = 0, friction_slack = 0;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const double m    = nodes[i].weight;
        const double u_nu = states[i].normal.u_nu;
        const double u_nu_old =
          nodes[i].value(u_old) * nodes[i].normal - nodes[i].gap;
        const double w_nu = states[i].normal.w_nu; // w_e . nu
        const double P =
          scheme.is_backward_euler() ?
            p.value(u_nu) :
            scheme.compliance_force(p.value(u_nu),
                                    p.discrete_gradient(u_nu_old, u_nu));
        const double q = states[i].normal.pressure - P;
        // The compliance force's work minus the change of Pi: >= 0 for
        // p(u_n) (evaluated without cancellation), 0 for the discrete
        // gradient, (2 theta - 1) times the first in between.
        compliance += scheme.is_backward_euler() ?
                        m * p.dissipation(u_nu_old, u_nu) :
                        m * (P * (u_nu - u_nu_old) -
                             (p.primitive(u_nu) - p.primitive(u_nu_old)));
        damping += k * m * q * w_nu;
        const Tensor<1, dim> w_e =
          scheme.weighted(nodes[i].value(w), nodes[i].value(w_old));
        friction += k * (states[i].friction_force * nodes[i].tangential(w_e));
        if (states[i].state == FrictionState::stick)
          friction_slack += k * states[i].friction_force.norm() *
                            nodes[i].tangential(w_e).norm();
      }
    t.compliance = Utilities::MPI::sum(compliance, comm);
    t.damping    = Utilities::MPI::sum(damping, comm);
    t.friction       = Utilities::MPI::sum(friction, comm);
    t.friction_slack = Utilities::MPI::sum(friction_slack, comm);

    t.close(previous_energy);
    return t;
  }


  template class EnergyBalance<2>;
  template class EnergyBalance<3>;
} // namespace DynamicContact
