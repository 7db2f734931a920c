#include <deal.II/lac/full_matrix.h>

#include <dynamic_contact/bulk/bulk_newton_matrix.h>
#include <dynamic_contact/bulk/stored_forms.h>

#include <functional>
#include <unordered_map>

#include "bulk_assembly.h"

namespace DynamicContact
{
  template <int dim>
  void
  BulkNewtonMatrix<dim>::reinit(const bool store)
  {
    stored_matrix = store;
    if (stored_matrix)
      {
        make_pattern(discretization,
                     component_couplings<dim>(/*each_with_itself=*/false),
                     pattern);
        bulk_matrix.reinit(pattern);
      }
    else
      {
        pattern.clear();
        bulk_matrix.clear();
      }
  }


  template <int dim>
  void
  BulkNewtonMatrix<dim>::set_time_step(const TimeScheme       &scheme,
                                       const StoredForms<dim> *stored_forms)
  {
    using Form = typename StoredForms<dim>::Form;
    kernel     = BulkKernel<dim>(scheme, material);
    if (stored_forms)
      {
        // K0 = (rho/k) M + theta A + theta^2 k B.
        bulk_matrix.copy_from(stored_forms->matrix(Form::elasticity));
        bulk_matrix *= scheme.elasticity_coefficient();
        bulk_matrix.add(scheme.mass_coefficient(material.density()),
                        stored_forms->matrix(Form::mass));
        if (material.has_viscosity())
          bulk_matrix.add(scheme.viscosity_coefficient(),
                          stored_forms->matrix(Form::viscosity));
      }
    else if (stored_matrix)
      assemble(scheme);
  }


  template <int dim>
  template <typename Take, typename CellDone>
  void
  BulkNewtonMatrix<dim>::for_each_cell_matrix(const BulkKernel<dim> &K,
                                              const Take            &take,
                                              const CellDone &cell_done) const
  {
    // K0 = (rho/k) M + theta A + theta^2 k B, cell by cell.
    const unsigned int n = discretization.fe.n_dofs_per_cell();
    FullMatrix<double> local(n, n);
    std::vector<SymmetricTensor<2, dim>> stress(n);
    std::vector<Tensor<1, dim>>          inertia(n);
    for_each_point(
      discretization,
      [&](const std::vector<Tensor<1, dim>>          &value,
          const std::vector<SymmetricTensor<2, dim>> &eps,
          const double                                JxW) {
        for (unsigned int i = 0; i < n; ++i)
          {
            stress[i]  = (K.stiffness * eps[i]) * JxW;
            inertia[i] = value[i] * (K.mass * JxW);
          }
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            local(i, j) += inertia[i] * value[j] + stress[i] * eps[j];
      },
      [&](const std::vector<types::global_dof_index> &dofs) {
        cell_done(local, dofs);
        local = 0;
      },
      take);
  }


  template <int dim>
  void
  BulkNewtonMatrix<dim>::assemble(const TimeScheme &scheme)
  {
    bulk_matrix = 0;
    for_each_cell_matrix(
      BulkKernel<dim>(scheme, material),
      std::function<bool(
        const typename DoFHandler<dim>::active_cell_iterator &)>(),
      [&](const FullMatrix<double>                   &local,
          const std::vector<types::global_dof_index> &dofs) {
        discretization.constraints.distribute_local_to_global(local,
                                                              dofs,
                                                              bulk_matrix);
      });
    bulk_matrix.compress(VectorOperation::add);
  }


  template <int dim>
  void
  BulkNewtonMatrix<dim>::vmult(Vector_t &dst, const Vector_t &src) const
  {
    if (stored_matrix)
      bulk_matrix.vmult(dst, src);
    else
      forms.vmult(kernel, dst, src);
  }


  namespace
  {
    /**
     * Every process's @p nodes, in the order of the processes; @p first is
     * set to where this process's own nodes begin.
     */
    template <int dim>
    std::vector<std::array<types::global_dof_index, dim>>
    all_processes_nodes(
      const MPI_Comm                                               comm,
      const std::vector<std::array<types::global_dof_index, dim>> &nodes,
      unsigned int                                                &first)
    {
      const auto per_process = Utilities::MPI::all_gather(comm, nodes);
      std::vector<std::array<types::global_dof_index, dim>> all;
      first = 0;
      for (unsigned int r = 0; r < per_process.size(); ++r)
        {
          if (r == Utilities::MPI::this_mpi_process(comm))
            first = all.size();
          all.insert(all.end(), per_process[r].begin(), per_process[r].end());
        }
      return all;
    }


    /** Which node and component each DoF of the @p nodes is. */
    template <int dim>
    std::unordered_map<types::global_dof_index,
                       std::pair<unsigned int, unsigned int>>
    node_and_component_of(
      const std::vector<std::array<types::global_dof_index, dim>> &nodes)
    {
      std::unordered_map<types::global_dof_index,
                         std::pair<unsigned int, unsigned int>>
        node_of;
      for (unsigned int p = 0; p < nodes.size(); ++p)
        for (unsigned int a = 0; a < dim; ++a)
          node_of[nodes[p][a]] = {p, a};
      return node_of;
    }


    /**
     * A local DoF resolved into the nodes' DoFs: (node, component,
     * coefficient), as condensation resolves it.
     */
    struct NodePart
    {
      unsigned int node, component;
      double       coefficient;
    };


    /**
     * Resolve each of a cell's @p dofs into the nodes' DoFs (@p node_of),
     * through @p constraints, into @p parts. Returns whether any of them
     * touches a node.
     */
    bool
    resolve_into_nodes(
      const std::vector<types::global_dof_index> &dofs,
      const AffineConstraints<double>            &constraints,
      const std::unordered_map<types::global_dof_index,
                               std::pair<unsigned int, unsigned int>> &node_of,
      std::vector<std::vector<NodePart>>                              &parts)
    {
      const unsigned int n   = parts.size();
      bool               any = false;
      for (unsigned int i = 0; i < n; ++i)
        {
          parts[i].clear();
          const auto add = [&](const types::global_dof_index g,
                               const double                  c) {
            const auto found = node_of.find(g);
            if (found != node_of.end())
              parts[i].push_back(
                {found->second.first, found->second.second, c});
          };
          if (!constraints.is_constrained(dofs[i]))
            add(dofs[i], 1.);
          else if (const auto *entries =
                     constraints.get_constraint_entries(dofs[i]))
            for (const auto &[master, c] : *entries)
              add(master, c);
          any = any || !parts[i].empty();
        }
      return any;
    }


    /**
     * A constrained DoF's row and column are the stored K0's stand-in:
     * only its diagonal, here the mean of the node's other diagonal entries.
     */
    template <int dim>
    void
    stand_in_for_constrained_dofs(
      const std::vector<std::array<types::global_dof_index, dim>> &nodes,
      const AffineConstraints<double>                             &constraints,
      std::vector<Tensor<2, dim>>                                 &blocks)
    {
      for (unsigned int p = 0; p < nodes.size(); ++p)
        {
          double       sum  = 0;
          unsigned int free = 0;
          for (unsigned int a = 0; a < dim; ++a)
            if (!constraints.is_constrained(nodes[p][a]))
              {
                sum += blocks[p][a][a];
                ++free;
              }
          for (unsigned int a = 0; a < dim; ++a)
            if (constraints.is_constrained(nodes[p][a]))
              {
                for (unsigned int b = 0; b < dim; ++b)
                  blocks[p][a][b] = blocks[p][b][a] = 0;
                blocks[p][a][a] = free > 0 ? sum / free : 1.;
              }
        }
    }
  } // namespace


  template <int dim>
  std::vector<Tensor<2, dim>>
  BulkNewtonMatrix<dim>::node_blocks(
    const std::vector<std::array<types::global_dof_index, dim>> &nodes) const
  {
    std::vector<Tensor<2, dim>> blocks(nodes.size());
    if (stored_matrix)
      {
        for (unsigned int p = 0; p < nodes.size(); ++p)
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int b = 0; b < dim; ++b)
              blocks[p][a][b] = bulk_matrix.el(nodes[p][a], nodes[p][b]);
        return blocks;
      }

    // Every process's nodes: each process sums what its own cells give to
    // any of them (a cell whose hanging node hangs on a node need not be
    // a ghost of the node's owner), then the sums are added up.
    const MPI_Comm     comm    = discretization.comm;
    unsigned int       first   = 0;
    const auto         all     = all_processes_nodes<dim>(comm, nodes, first);
    const auto         node_of = node_and_component_of<dim>(all);
    const auto        &constraints = discretization.constraints;
    const unsigned int n           = discretization.fe.n_dofs_per_cell();
    std::vector<std::vector<NodePart>>   parts(n);
    std::vector<types::global_dof_index> cell_dofs(n);
    std::vector<double>                  sums(all.size() * dim * dim, 0.);
    for_each_cell_matrix(
      kernel,
      std::function<bool(
        const typename DoFHandler<dim>::active_cell_iterator &)>(
        [&](const typename DoFHandler<dim>::active_cell_iterator &cell) {
          if (!cell->is_locally_owned())
            return false;
          cell->get_dof_indices(cell_dofs);
          return resolve_into_nodes(cell_dofs, constraints, node_of, parts);
        }),
      [&](const FullMatrix<double> &local,
          const std::vector<types::global_dof_index> &) {
        for (unsigned int i = 0; i < n; ++i)
          for (const NodePart &r : parts[i])
            for (unsigned int j = 0; j < n; ++j)
              for (const NodePart &c : parts[j])
                if (c.node == r.node)
                  sums[(r.node * dim + r.component) * dim + c.component] +=
                    r.coefficient * local(i, j) * c.coefficient;
      });
    Utilities::MPI::sum(sums, comm, sums);
    for (unsigned int p = 0; p < nodes.size(); ++p)
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          blocks[p][a][b] = sums[((first + p) * dim + a) * dim + b];
    stand_in_for_constrained_dofs<dim>(nodes, constraints, blocks);
    return blocks;
  }


  template class BulkNewtonMatrix<2>;
  template class BulkNewtonMatrix<3>;
} // namespace DynamicContact
