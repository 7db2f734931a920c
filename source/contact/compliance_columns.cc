#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/mpi_gather.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/compliance_table.h>

#include <algorithm>
#include <functional>

namespace DynamicContact
{
  // ComplianceTable<dim>::make and its two ways, in a file of their own
  // (the rest of the table is in compliance_table.cc).
  template <int dim>
  void
  ComplianceTable<dim>::make(const std::vector<unsigned int> &nodes,
                             BulkSolver                      &bulk_solver,
                             Result                          &result)
  {
    std::vector<unsigned int> missing;
    // Whole blocks of nodes_per_block consecutive nodes, each solved as one
    // block of right-hand sides: a block solve's round-off depends on the
    // block's composition (BLAS 3 in CHOLMOD), which is so fixed, and a run
    // resumed from a checkpoint gets the columns of the uninterrupted one.
    const auto        &all             = gathered.all_nodes();
    const unsigned int nodes_per_block = 64 / dim;
    std::vector<bool>  wanted(all.size(), false);
    for (const unsigned int j : nodes)
      if (!made[j])
        wanted[j / nodes_per_block * nodes_per_block] = true;
    for (unsigned int first = 0; first < all.size(); first += nodes_per_block)
      if (wanted[first])
        for (unsigned int j = first;
             j < std::min<unsigned int>(first + nodes_per_block, all.size());
             ++j)
          if (!made[j])
            missing.push_back(j);
    if (missing.empty())
      return;
    TimerSection t(problem.timer, "Bulk: compliance columns");
    if (!columns_from_inverse_block(bulk_solver))
      columns_by_solves(missing, dim * nodes_per_block, bulk_solver, result);
  }


  template <int dim>
  bool
  ComplianceTable<dim>::columns_from_inverse_block(BulkSolver &bulk_solver)
  {
    // With the Cholesky factor (the whole one), which has the DoFs of
    // Gamma_3 last (BoundaryCompliance::prepare()): the compliance of every
    // node at once, from the inverse of their Schur complement
    // (BulkSolver::inverse_block()), dense work of order (dim n)^3 instead of
    // dim solves per node. The whole columns are not kept: with a Cholesky
    // factor a solve reads fewer numbers than their sum. Only rank 0 holds C
    // (and gets the block where it can).
    std::vector<double> X;
    const bool          holds = holds_tables();
    if (!bulk_solver.inverse_block(X, false))
      return false;
    const auto       &all = gathered.all_nodes();
    const std::size_t m   = dim * all.size();
    made.assign(all.size(), true);
    if (!holds)
      return true;
    for (unsigned int j = 0; j < all.size(); ++j)
      {
        columns[j].assign(all.size(), Tensor<2, dim>());
        for (unsigned int i = 0; i < all.size(); ++i)
          {
            Tensor<2, dim> X_ij;
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int b = 0; b < dim; ++b)
                X_ij[a][b] = X[(dim * i + a) + (dim * j + b) * m];
            columns[j][i] =
              all[i].constraint_map * X_ij * transpose(all[j].constraint_map);
          }
      }
    problem.details << "    compliance of Gamma_3: the inverse of its "
                       "Schur complement ("
                    << m << " DoFs)" << std::endl;
    return true;
  }


  namespace
  {
    /**
     * One right-hand side per node of @p missing and direction: a unit
     * force in direction c at node j, through the node's constraints
     * (P_j^T e_c).
     */
    template <int dim>
    std::vector<BulkSolver::SparseColumn>
    unit_forces(const std::vector<ContactNode<dim>> &all,
                const std::vector<unsigned int>     &missing)
    {
      std::vector<BulkSolver::SparseColumn> rhs;
      for (const unsigned int j : missing)
        for (unsigned int c = 0; c < dim; ++c)
          {
            BulkSolver::SparseColumn column;
            for (unsigned int r = 0; r < dim; ++r)
              if (all[j].constraint_map[c][r] != 0)
                column.emplace_back(all[j].dofs[r],
                                    all[j].constraint_map[c][r]);
            rhs.push_back(column);
          }
      return rhs;
    }


    /**
     * The responses @p values at the @p owned nodes (rows: their DoFs) to
     * the unit forces of @p n_missing nodes, through each owned node's
     * constraints, packed for rank 0 as (missing node m, direction c,
     * global index of the owned node, dim entries).
     */
    template <int dim>
    std::vector<double>
    packed_responses(const std::vector<ContactNode<dim>>    &owned,
                     const std::vector<unsigned int>        &global,
                     const std::vector<std::vector<double>> &values,
                     const unsigned int                      n_missing)
    {
      std::vector<double> packed;
      for (unsigned int m = 0; m < n_missing; ++m)
        for (unsigned int c = 0; c < dim; ++c)
          for (unsigned int i = 0; i < owned.size(); ++i)
            {
              Tensor<1, dim> raw;
              for (unsigned int r = 0; r < dim; ++r)
                raw[r] = values[dim * m + c][dim * i + r];
              const Tensor<1, dim> response = owned[i].constraint_map * raw;
              packed.push_back(m);
              packed.push_back(c);
              packed.push_back(global[i]);
              for (unsigned int r = 0; r < dim; ++r)
                packed.push_back(response[r]);
            }
      return packed;
    }
  } // namespace


  template <int dim>
  void
  ComplianceTable<dim>::columns_by_solves(
    const std::vector<unsigned int> &missing,
    const unsigned int               block_size,
    BulkSolver                      &bulk_solver,
    Result                          &result)
  {
    const auto                                 &all = gathered.all_nodes();
    const std::vector<BulkSolver::SparseColumn> rhs = unit_forces(all, missing);
    // The responses at the owned nodes, then at every node.
    const auto                          &owned  = problem.boundary.nodes();
    const auto                          &global = gathered.global_indices();
    std::vector<types::global_dof_index> rows;
    for (const auto &node : owned)
      for (unsigned int r = 0; r < dim; ++r)
        rows.push_back(node.dofs[r]);
    std::vector<std::vector<double>> values;
    // Keep the whole columns while they fit, and only if a sum of all of
    // them reads fewer numbers than a solve (the same decision everywhere).
    const bool store =
      (stored_full_columns + rhs.size()) * max_owned_dofs * sizeof(double) <=
        full_column_budget &&
      double(dim) * all.size() * max_owned_dofs <= bulk_solver.solve_cost();
    const std::size_t n_owned =
      problem.discretization.locally_owned.n_elements();
    std::function<void(unsigned int, const double *)> keep;
    if (store)
      keep = [&](const unsigned int column, const double *entries) {
        full_columns[dim * missing[column / dim] + column % dim].assign(
          entries, entries + n_owned);
      };
    problem.details << "    compliance of Gamma_3: " << missing.size()
                    << " nodes by " << rhs.size() << " solves" << std::endl;
    bulk_solver.solve_columns(rhs, rows, values, keep, block_size);
    if (store)
      {
        stored_full_columns += rhs.size();
        for (const unsigned int j : missing)
          full_column_stored[j] = true;
      }
    result.bulk_solves += rhs.size();

    const std::vector<double> packed =
      packed_responses(owned, global, values, missing.size());
    // To rank 0, which holds C.
    const bool holds = holds_tables();
    for (const unsigned int j : missing)
      {
        made[j] = true;
        if (holds)
          columns[j].assign(all.size(), Tensor<2, dim>());
      }
    for (const auto &part :
         gather_values(problem.discretization.comm, packed, 0))
      for (std::size_t p = 0; p < part.size(); p += 3 + dim)
        {
          const unsigned int j = missing[static_cast<unsigned int>(part[p])];
          const unsigned int c = static_cast<unsigned int>(part[p + 1]);
          const unsigned int i = static_cast<unsigned int>(part[p + 2]);
          for (unsigned int r = 0; r < dim; ++r)
            columns[j][i][r][c] = part[p + 3 + r];
        }
  }


  template void
  ComplianceTable<2>::make(const std::vector<unsigned int> &,
                           BulkSolver &,
                           Result &);
  template void
  ComplianceTable<3>::make(const std::vector<unsigned int> &,
                           BulkSolver &,
                           Result &);
} // namespace DynamicContact
