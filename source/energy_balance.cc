#include <deal.II/base/mpi.h>

#include <dynamic_contact/energy_balance.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  double
  EnergyBalanceTerms::min_dissipation_term() const
  {
    return std::min({inertia, elastic, viscous, compliance, damping, friction});
  }


  bool
  EnergyBalanceTerms::dissipation_nonnegative(const double previous_energy) const
  {
    return min_dissipation_term() >= -roundoff * scale(previous_energy);
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


  template <int dim>
  EnergyBalance<dim>::EnergyBalance(const BulkOperator<dim> &    bulk,
                                    const ContactBoundary<dim> &boundary,
                                    const Foundation &          foundation,
                                    const double                density,
                                    const MPI_Comm              comm)
    : bulk(bulk)
    , contact_boundary(boundary)
    , foundation(foundation)
    , density(density)
    , comm(comm)
  {}


  template <int dim>
  Energy
  EnergyBalance<dim>::energy(const Vector_t &u, const Vector_t &w) const
  {
    Energy e;
    e.kinetic = 0.5 * density * bulk.mass_product(w, w);
    e.elastic = 0.5 * bulk.elastic_product(u, u);
    double foundation_energy = 0;
    for (const auto &node : contact_boundary.nodes())
      foundation_energy +=
        node.weight * foundation.compliance().primitive(
                        node.value(u) * node.normal - node.gap);
    e.foundation = Utilities::MPI::sum(foundation_energy, comm);
    return e;
  }


  template <int dim>
  EnergyBalanceTerms
  EnergyBalance<dim>::step_terms(
    const Vector_t &                          u_old,
    const Vector_t &                          w_old,
    const Vector_t &                          u,
    const Vector_t &                          w,
    const Vector_t &                          load,
    const double                              k,
    const std::vector<ContactNodeState<dim>> &states,
    const double                              previous_energy) const
  {
    EnergyBalanceTerms t;
    t.energy = energy(u, w);

    // The scratch vector takes the layout of the current mesh (it changes
    // with adaptive refinement and repartitioning).
    difference.reinit(u, true);
    difference = u;
    difference -= u_old;
    t.load_work = load * difference;
    t.elastic   = 0.5 * bulk.elastic_product(difference, difference);
    difference  = w;
    difference -= w_old;
    t.inertia = 0.5 * density * bulk.mass_product(difference, difference);
    t.viscous = k * bulk.viscous_product(w, w);

    // Nodal terms, with the states of the converged solve.
    const auto &nodes      = contact_boundary.nodes();
    const auto &p          = foundation.compliance();
    double      compliance = 0, damping = 0, friction = 0;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const double m          = nodes[i].weight;
        const double u_nu       = states[i].normal.u_nu;
        const double u_nu_old   = nodes[i].value(u_old) * nodes[i].normal -
                                nodes[i].gap;
        const double w_nu       = states[i].normal.w_nu;
        const double q          = states[i].normal.pressure - p.value(u_nu);
        compliance += m * p.dissipation(u_nu_old, u_nu);
        damping += k * m * q * w_nu;
        friction += k * (states[i].friction_force *
                         nodes[i].tangential(nodes[i].value(w)));
      }
    t.compliance = Utilities::MPI::sum(compliance, comm);
    t.damping    = Utilities::MPI::sum(damping, comm);
    t.friction   = Utilities::MPI::sum(friction, comm);

    t.defect =
      t.energy.total() - previous_energy + t.dissipation() - t.load_work;
    return t;
  }


  template class EnergyBalance<2>;
  template class EnergyBalance<3>;
} // namespace DynamicContact
