#include <dynamic_contact/contact/contact_state.h>

namespace DynamicContact
{
  template <int dim>
  void
  ContactState<dim>::reinit(const ContactBoundary<dim> &boundary,
                            const double                initial_mu)
  {
    const unsigned int n = boundary.nodes().size();
    mu.assign(n, initial_mu);
    lambda.assign(n, Tensor<1, dim>());
    nodes.assign(n, ContactNodeState<dim>());
    coefficient_state.assign(n, initial_mu);
  }


  template <int dim>
  std::pair<double, double>
  ContactState<dim>::force_sums(const ContactBoundary<dim> &boundary,
                                const MPI_Comm              comm) const
  {
    const auto &boundary_nodes = boundary.nodes();
    double      normal = 0, tangential = 0;
    for (unsigned int i = 0; i < boundary_nodes.size(); ++i)
      {
        normal += nodes[i].normal_force(boundary_nodes[i].weight);
        tangential += nodes[i].friction_force.norm();
      }
    return {Utilities::MPI::sum(normal, comm),
            Utilities::MPI::sum(tangential, comm)};
  }


  template <int dim>
  template <typename NodalValue>
  Vector_t
  ContactState<dim>::nodal_field(const Discretization<dim>  &discretization,
                                 const ContactBoundary<dim> &boundary,
                                 const NodalValue           &value)
  {
    Vector_t field;
    discretization.reinit_owned(field);
    const auto                          &boundary_nodes = boundary.nodes();
    std::vector<types::global_dof_index> indices;
    std::vector<double>                  values;
    for (unsigned int i = 0; i < boundary_nodes.size(); ++i)
      for (unsigned int c = 0; c < dim; ++c)
        {
          indices.push_back(boundary_nodes[i].dofs[c]);
          values.push_back(value(i, c));
        }
    field.set(indices, values);
    field.compress(VectorOperation::insert);
    return field;
  }


  template <int dim>
  Vector_t
  ContactState<dim>::friction_field(const Discretization<dim>  &discretization,
                                    const ContactBoundary<dim> &boundary,
                                    const bool per_weight) const
  {
    const auto &boundary_nodes = boundary.nodes();
    return nodal_field(discretization,
                       boundary,
                       [&](const unsigned int i, const unsigned int c) {
                         return i < lambda.size() ?
                                  lambda[i][c] / (per_weight ?
                                                    boundary_nodes[i].weight :
                                                    1.) :
                                  0.;
                       });
  }


  template <int dim>
  Vector_t
  ContactState<dim>::state_field(const Discretization<dim>  &discretization,
                                 const ContactBoundary<dim> &boundary) const
  {
    return nodal_field(discretization,
                       boundary,
                       [&](const unsigned int i, const unsigned int c) {
                         return c == 0 && i < coefficient_state.size() ?
                                  coefficient_state[i] :
                                  0.;
                       });
  }


  template <int dim>
  void
  ContactState<dim>::set_state_from_field(const ContactBoundary<dim> &boundary,
                                          const Vector_t             &field)
  {
    const auto &boundary_nodes = boundary.nodes();
    coefficient_state.resize(boundary_nodes.size());
    for (unsigned int i = 0; i < boundary_nodes.size(); ++i)
      coefficient_state[i] = field[boundary_nodes[i].dofs[0]];
  }


  template <int dim>
  void
  ContactState<dim>::set_friction_from_field(
    const ContactBoundary<dim> &boundary,
    const Vector_t             &field,
    const bool                  per_weight)
  {
    const auto &boundary_nodes = boundary.nodes();
    lambda.resize(boundary_nodes.size());
    for (unsigned int i = 0; i < boundary_nodes.size(); ++i)
      {
        Tensor<1, dim> raw;
        for (unsigned int c = 0; c < dim; ++c)
          raw[c] = field[boundary_nodes[i].dofs[c]];
        // A traction interpolated onto a new mesh: its tangential part,
        // times the new weight; a nodal force of the same mesh: as it was.
        lambda[i] = per_weight ? boundary_nodes[i].weight *
                                   boundary_nodes[i].tangential(raw) :
                                 raw;
      }
  }


  template class ContactState<2>;
  template class ContactState<3>;
} // namespace DynamicContact
