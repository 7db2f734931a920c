#ifndef dynamic_contact_contact_boundary_h
#define dynamic_contact_contact_boundary_h

#include <deal.II/base/function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/contact_node.h>

#include <array>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The data of Gamma_3 in one object, computed once per mesh: the nodes
   * whose DoFs this process owns. Nothing here is replicated: every law is
   * node-wise (doc/theory.md section 3), so a process needs only its own
   * nodes, whose DoFs it owns.
   */
  template <int dim>
  class ContactBoundary
  {
  public:
    /**
     * Collect the nodes of the boundary ids @p contact_ids. The gap function
     * is evaluated at each node.
     */
    void
    reinit(const Discretization<dim>             &discretization,
           const std::vector<types::boundary_id> &contact_ids,
           const Function<dim>                   &initial_gap);

    /** The nodes whose DoFs this process owns, sorted by position. */
    const std::vector<ContactNode<dim>> &
    nodes() const
    {
      return owned_nodes;
    }

    /** The nodal vectors of a (master form) vector at the owned nodes. */
    template <typename VectorType>
    std::vector<Tensor<1, dim>>
    values(const VectorType &v) const
    {
      std::vector<Tensor<1, dim>> result(owned_nodes.size());
      for (unsigned int i = 0; i < owned_nodes.size(); ++i)
        result[i] = owned_nodes[i].value(v);
      return result;
    }

    /**
     * v += factor sum_i P_i^T f_i over the owned nodes i (the nodal forces
     * into the body's equations, through each node's constraint map);
     * @p force_of(i) is the force of owned node i. Collective (compress).
     */
    template <typename ForceOf>
    void
    add_nodal_forces(const ForceOf &force_of,
                     const double   factor,
                     Vector_t      &v) const
    {
      std::vector<types::global_dof_index> indices;
      std::vector<double>                  values;
      for (unsigned int i = 0; i < owned_nodes.size(); ++i)
        {
          const Tensor<1, dim> condensed =
            transpose(owned_nodes[i].constraint_map) * force_of(i);
          for (unsigned int c = 0; c < dim; ++c)
            {
              indices.push_back(owned_nodes[i].dofs[c]);
              values.push_back(factor * condensed[c]);
            }
        }
      v.add(indices, values);
      v.compress(VectorOperation::add);
    }

    /** The number of nodes on all processes. */
    types::global_dof_index
    n_global_nodes() const
    {
      return n_global;
    }

    MPI_Comm
    get_mpi_communicator() const
    {
      return comm;
    }

  private:
    MPI_Comm                      comm = MPI_COMM_SELF;
    std::vector<ContactNode<dim>> owned_nodes;
    types::global_dof_index       n_global = 0;
  };


  /**
   * Every node of Gamma_3 on every process, in one order (by position)
   * whatever the number of processes, and the gathers that fill per-node
   * vectors on it. Only the condensed solver, whose dense tables couple
   * every pair of nodes, builds one: its memory and the communication of
   * its gathers grow with the whole contact boundary on every process.
   */
  template <int dim>
  class GatheredBoundary
  {
  public:
    /** Collective. */
    void
    reinit(const ContactBoundary<dim> &boundary);

    const std::vector<ContactNode<dim>> &
    all_nodes() const
    {
      return every_node;
    }

    /** For each owned node of the ContactBoundary, its index here. */
    const std::vector<unsigned int> &
    global_indices() const
    {
      return owned_to_global;
    }

    /** Per-node values of the owned nodes, at every node (collective). */
    std::vector<Tensor<1, dim>>
    gather(const std::vector<Tensor<1, dim>> &owned_values) const;
    std::vector<double>
    gather(const std::vector<double> &owned_values) const;

    /** The owned nodes' entries of an every-node vector. */
    template <typename T>
    std::vector<T>
    owned_part(const std::vector<T> &every) const
    {
      std::vector<T> result(owned_to_global.size());
      for (unsigned int i = 0; i < owned_to_global.size(); ++i)
        result[i] = every[owned_to_global[i]];
      return result;
    }

  private:
    MPI_Comm                      comm = MPI_COMM_SELF;
    std::vector<ContactNode<dim>> every_node;
    std::vector<unsigned int>     owned_to_global;
  };
} // namespace DynamicContact

#endif
