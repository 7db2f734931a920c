#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/base/mpi_gather.h>

#include <algorithm>
#include <map>
#include <set>

namespace DynamicContact
{
  namespace
  {
    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &normal)
    {
      std::array<Tensor<1, dim>, dim - 1> t;
      if constexpr (dim == 2)
        {
          t[0][0] = -normal[1];
          t[0][1] = normal[0];
        }
      else
        {
          Tensor<1, dim> axis;
          axis[std::abs(normal[0]) < 0.9 ? 0 : 1] = 1;
          t[0] = axis - (axis * normal) * normal;
          t[0] /= t[0].norm();
          t[1] = cross_product_3d(t[0], normal);
        }
      return t;
    }

    template <int dim>
    bool
    by_position(const ContactNode<dim> &a, const ContactNode<dim> &b)
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (a.position[d] != b.position[d])
          return a.position[d] < b.position[d];
      return false;
    }

    template <int dim>
    void
    pack(const ContactNode<dim> &node, std::vector<double> &out)
    {
      for (const auto dof : node.dofs)
        out.push_back(static_cast<double>(dof));
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          out.push_back(node.constraint_map[i][j]);
      out.push_back(node.unconstrained ? 1 : 0);
      for (unsigned int d = 0; d < dim; ++d)
        out.push_back(node.position[d]);
      for (unsigned int d = 0; d < dim; ++d)
        out.push_back(node.normal[d]);
      for (const auto &t : node.tangents)
        for (unsigned int d = 0; d < dim; ++d)
          out.push_back(t[d]);
      out.push_back(node.weight);
      out.push_back(node.gap);
      out.push_back(static_cast<double>(node.scalar_dof));
    }

    template <int dim>
    ContactNode<dim>
    unpack(const std::vector<double> &in, std::size_t &pos)
    {
      ContactNode<dim> node;
      for (auto &dof : node.dofs)
        dof = static_cast<types::global_dof_index>(in[pos++]);
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          node.constraint_map[i][j] = in[pos++];
      node.unconstrained = in[pos++] != 0;
      for (unsigned int d = 0; d < dim; ++d)
        node.position[d] = in[pos++];
      for (unsigned int d = 0; d < dim; ++d)
        node.normal[d] = in[pos++];
      for (auto &t : node.tangents)
        for (unsigned int d = 0; d < dim; ++d)
          t[d] = in[pos++];
      node.weight     = in[pos++];
      node.gap        = in[pos++];
      node.scalar_dof = static_cast<types::global_dof_index>(in[pos++]);
      return node;
    }
  } // namespace


  namespace
  {
    /**
     * Gather per-node values of width @p width (the owned nodes' entries,
     * packed after their index in the every-node list) to every process.
     */
    template <typename Pack, typename Unpack>
    void
    gather_nodal(const MPI_Comm                   comm,
                 const std::vector<unsigned int> &owned_to_global,
                 const unsigned int               width,
                 const Pack                      &pack,
                 const Unpack                    &unpack)
    {
      std::vector<double> local;
      local.reserve(owned_to_global.size() * (width + 1));
      for (unsigned int i = 0; i < owned_to_global.size(); ++i)
        {
          local.push_back(owned_to_global[i]);
          pack(i, local);
        }
      for (const auto &part : all_gather_values(comm, local))
        for (std::size_t pos = 0; pos < part.size(); pos += width + 1)
          unpack(static_cast<unsigned int>(part[pos]), &part[pos + 1]);
    }
  } // namespace


  template <int dim>
  std::vector<Tensor<1, dim>>
  GatheredBoundary<dim>::gather(
    const std::vector<Tensor<1, dim>> &owned_values) const
  {
    std::vector<Tensor<1, dim>> values(every_node.size());
    gather_nodal(
      comm,
      owned_to_global,
      dim,
      [&](const unsigned int i, std::vector<double> &out) {
        for (unsigned int d = 0; d < dim; ++d)
          out.push_back(owned_values[i][d]);
      },
      [&](const unsigned int g, const double *in) {
        for (unsigned int d = 0; d < dim; ++d)
          values[g][d] = in[d];
      });
    return values;
  }


  template <int dim>
  std::vector<double>
  GatheredBoundary<dim>::gather(const std::vector<double> &owned_values) const
  {
    std::vector<double> values(every_node.size());
    gather_nodal(
      comm,
      owned_to_global,
      1,
      [&](const unsigned int i, std::vector<double> &out) {
        out.push_back(owned_values[i]);
      },
      [&](const unsigned int g, const double *in) { values[g] = in[0]; });
    return values;
  }


  template <int dim>
  void
  GatheredBoundary<dim>::reinit(const ContactBoundary<dim> &boundary)
  {
    comm = boundary.get_mpi_communicator();
    std::vector<double> packed;
    for (const auto &node : boundary.nodes())
      pack(node, packed);
    every_node.clear();
    for (const auto &part : all_gather_values(comm, packed))
      for (std::size_t pos = 0; pos < part.size();)
        every_node.push_back(unpack<dim>(part, pos));
    std::sort(every_node.begin(), every_node.end(), by_position<dim>);
    owned_to_global.clear();
    for (const auto &node : boundary.nodes())
      {
        const auto it = std::lower_bound(every_node.begin(),
                                         every_node.end(),
                                         node,
                                         by_position<dim>);
        Assert(it != every_node.end() && it->dofs == node.dofs,
               ExcInternalError());
        owned_to_global.push_back(it - every_node.begin());
      }
  }


  namespace
  {
    /**
     * The lumped weights int phi_i and normal moments int phi_i n over the
     * faces of @p ids, with the Gauss-Lobatto rule whose nodes are the
     * support points, assembled into global vectors through the
     * hanging-node constraints (a hanging node's share goes to its
     * masters).
     */
    template <int dim>
    void
    lumped_moments(const Discretization<dim>          &discretization,
                   const std::set<types::boundary_id> &ids,
                   TrilinosWrappers::MPI::Vector      &weights,
                   TrilinosWrappers::MPI::Vector      &normal_moments)
    {
      const auto &fe          = discretization.fe;
      const auto &dof_handler = discretization.dof_handler;
      discretization.reinit_owned(weights);
      discretization.reinit_owned(normal_moments);
      const QGaussLobatto<dim - 1>         quadrature(fe.degree + 1);
      FEFaceValues<dim>                    fe_face(discretization.mapping,
                                fe,
                                quadrature,
                                update_values | update_normal_vectors |
                                  update_JxW_values);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      Vector<double>                       local_w(fe.n_dofs_per_cell()),
        local_n(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                ids.count(cell->face(f)->boundary_id()))
              {
                fe_face.reinit(cell, f);
                local_w = 0;
                local_n = 0;
                for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
                  {
                    const unsigned int c =
                      fe.system_to_component_index(i).first;
                    for (unsigned int q = 0; q < quadrature.size(); ++q)
                      {
                        const double phi =
                          fe_face.shape_value_component(i, q, c);
                        local_w(i) += phi * fe_face.JxW(q);
                        local_n(i) +=
                          phi * fe_face.normal_vector(q)[c] * fe_face.JxW(q);
                      }
                  }
                cell->get_dof_indices(dofs);
                discretization.hanging_node_constraints
                  .distribute_local_to_global(local_w, dofs, weights);
                discretization.hanging_node_constraints
                  .distribute_local_to_global(local_n, dofs, normal_moments);
              }
      weights.compress(VectorOperation::add);
      normal_moments.compress(VectorOperation::add);
    }


    /**
     * The clamped/roller constraints restricted to @p node (its
     * constraint_map, and whether it is unconstrained); false if every
     * component of the node is fixed to zero (a clamped node feels no
     * foundation).
     */
    template <int dim>
    bool
    restrict_constraints(ContactNode<dim>                &node,
                         const AffineConstraints<double> &constraints)
    {
      node.constraint_map = 0;
      node.unconstrained  = true;
      bool all_zero       = true;
      for (unsigned int c = 0; c < dim; ++c)
        if (!constraints.is_constrained(node.dofs[c]))
          {
            node.constraint_map[c][c] = 1;
            all_zero                  = false;
          }
        else
          {
            node.unconstrained = false;
            for (const auto &[dof, coefficient] :
                 *constraints.get_constraint_entries(node.dofs[c]))
              {
                const auto it =
                  std::find(node.dofs.begin(), node.dofs.end(), dof);
                AssertThrow(it != node.dofs.end(),
                            ExcMessage(
                              "A node of Gamma_3 is constrained to "
                              "another node; contact boundaries must not "
                              "share nodes with constraints of that "
                              "kind."));
                node.constraint_map[c][it - node.dofs.begin()] = coefficient;
                all_zero                                       = false;
              }
          }
      return !all_zero;
    }

    /**
     * The contact node of the support point @p base_index of a face of
     * Gamma_3 (its DoFs @p face_dofs) at @p position: its DoFs per
     * component, its lumped weight, and the unit normal and tangents from
     * the normal moments at its DoFs, its scalar DoF (of
     * @p scalar_face_dofs) and its gap. Its constraints are the caller's.
     */
    template <int dim>
    ContactNode<dim>
    make_node(const FiniteElement<dim>                   &fe,
              const std::vector<types::global_dof_index> &face_dofs,
              const std::vector<types::global_dof_index> &scalar_face_dofs,
              const unsigned int                          base_index,
              const Point<dim>                           &position,
              const TrilinosWrappers::MPI::Vector        &weights,
              const TrilinosWrappers::MPI::Vector        &normal_moments,
              const Function<dim>                        &initial_gap)
    {
      ContactNode<dim> node;
      for (unsigned int k = 0; k < fe.n_dofs_per_face(); ++k)
        if (fe.face_system_to_component_index(k).second == base_index)
          node.dofs[fe.face_system_to_component_index(k).first] = face_dofs[k];
      node.position = position;
      node.weight   = weights[node.dofs[0]];
      for (unsigned int c = 0; c < dim; ++c)
        node.normal[c] = normal_moments[node.dofs[c]];
      Assert(node.weight > 0 && node.normal.norm() > 0, ExcInternalError());
      node.normal /= node.normal.norm();
      node.tangents   = tangent_basis<dim>(node.normal);
      node.scalar_dof = scalar_face_dofs[base_index];
      node.gap        = initial_gap.value(node.position);
      AssertThrow(node.gap >= 0,
                  ExcMessage("Foundation/Initial gap must be >= 0, but it "
                             "is negative at a node of Gamma_3."));
      return node;
    }
  } // namespace


  template <int dim>
  void
  ContactBoundary<dim>::reinit(
    const Discretization<dim>             &discretization,
    const std::vector<types::boundary_id> &contact_ids,
    const Function<dim>                   &initial_gap)
  {
    owned_nodes.clear();
    const std::set<types::boundary_id> ids(contact_ids.begin(),
                                           contact_ids.end());
    const auto                        &fe          = discretization.fe;
    const auto                        &dof_handler = discretization.dof_handler;

    // Lumped weights and normal moments at every DoF of Gamma_3.
    TrilinosWrappers::MPI::Vector weights, normal_moments;
    lumped_moments(discretization, ids, weights, normal_moments);

    // The nodes: support points on Gamma_3 faces of owned and ghost cells
    // (together they touch every owned DoF), whose DoFs this process owns
    // and which are not hanging.
    const Quadrature<dim - 1> support_points(fe.get_unit_face_support_points());
    FEFaceValues<dim>         fe_face(discretization.mapping,
                              fe,
                              support_points,
                              update_quadrature_points);
    std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
    std::vector<types::global_dof_index> scalar_face_dofs(
      discretization.scalar_fe.n_dofs_per_face());
    std::set<types::global_dof_index> seen;

    auto scalar_cell = discretization.scalar_dof_handler.begin_active();
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_artificial())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                ids.count(cell->face(f)->boundary_id()))
              {
                cell->face(f)->get_dof_indices(face_dofs);
                scalar_cell->face(f)->get_dof_indices(scalar_face_dofs);
                fe_face.reinit(cell, f);
                // Group the face DoFs by support point: component 0 first.
                for (unsigned int j = 0; j < fe.n_dofs_per_face(); ++j)
                  {
                    const auto [component, base_index] =
                      fe.face_system_to_component_index(j);
                    if (component != 0)
                      continue;
                    const auto dof0 = face_dofs[j];
                    if (!discretization.locally_owned.is_element(dof0) ||
                        discretization.hanging_node_constraints.is_constrained(
                          dof0) ||
                        seen.count(dof0))
                      continue;
                    seen.insert(dof0);

                    ContactNode<dim> node =
                      make_node(fe,
                                face_dofs,
                                scalar_face_dofs,
                                base_index,
                                fe_face.quadrature_point(j),
                                weights,
                                normal_moments,
                                initial_gap);

                    if (restrict_constraints(node, discretization.constraints))
                      owned_nodes.push_back(node);
                  }
              }
        ++scalar_cell;
      }

    // A reproducible order: by position.
    std::sort(owned_nodes.begin(), owned_nodes.end(), by_position<dim>);

    comm = discretization.comm;
    n_global =
      Utilities::MPI::sum<types::global_dof_index>(owned_nodes.size(), comm);
  }


  template class ContactBoundary<2>;
  template class ContactBoundary<3>;
  template class GatheredBoundary<2>;
  template class GatheredBoundary<3>;
} // namespace DynamicContact
