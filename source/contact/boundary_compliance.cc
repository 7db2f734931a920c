#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/boundary_compliance.h>

namespace DynamicContact
{
  template <int dim>
  void
  BoundaryCompliance<dim>::reinit()
  {
    const auto &all = gathered.all_nodes();
    table.reinit();
    owned_index.assign(all.size(), -1);
    const auto &global = gathered.global_indices();
    for (unsigned int i = 0; i < global.size(); ++i)
      owned_index[global[i]] = i;
    prepared_scheme = TimeScheme();
    measures.reinit();
    regularized.reinit(problem.bulk.sparsity_pattern());
    stiff_springs.reinit();
  }


  template <int dim>
  bool
  BoundaryCompliance<dim>::holds_tables() const
  {
    return table.holds_tables();
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::on_leader(Result                      &result,
                                     const std::function<void()> &work)
  {
    Assert(leading == nullptr, ExcInternalError());
    LeadingProcess lead(problem.boundary.get_mpi_communicator(),
                        [&](const std::vector<unsigned int> &nodes) {
                          table.make(nodes, bulk_solver, result);
                        });
    // compute_columns() asks through lead while the work runs (rank 0).
    struct Reset
    {
      LeadingProcess *&pointer;
      ~Reset()
      {
        pointer = nullptr;
      }
    } reset{leading};
    leading = &lead;
    lead.run(work);
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::compute_columns(
    const std::vector<unsigned int> &nodes,
    Result                          &result)
  {
    if (leading != nullptr && leading->shared())
      {
        // Rank 0 inside on_leader(): every process computes them with it.
        if (!has_columns(nodes))
          leading->request(nodes);
        return;
      }
    table.make(nodes, bulk_solver, result);
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::memory_consumption(MemoryItems &items) const
  {
    if (regularized.m() > 0)
      items.push_back({"K0' = K0 + springs (values)",
                       stored_values_bytes(regularized),
                       false});
    bulk_solver.memory_consumption("factorization of K0'", items);
    table.memory_consumption(items);
  }


  template <int dim>
  bool
  BoundaryCompliance<dim>::prepare(Result &result)
  {
    if (problem.bulk.scheme() == prepared_scheme)
      return false;
    stiff_springs.add_springs(regularized, owned_index);
    {
      // The DoFs of Gamma_3 last (taken by the Cholesky factorization, on
      // one process, where it pays): the compliance of every node is then
      // the inverse of their Schur complement (compute_columns()).
      std::vector<types::global_dof_index> trailing;
      for (const auto &node : gathered.all_nodes())
        trailing.insert(trailing.end(), node.dofs.begin(), node.dofs.end());
      TimerSection t(problem.timer, "Bulk: factorization of K0");
      bulk_solver.initialize(regularized, problem.discretization, trailing);
    }
    ++result.factorizations;
    prepared_scheme = problem.bulk.scheme();
    // C depends on K0: forget it.
    table.forget();
    return true;
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::solve(const Vector_t &b,
                                   Vector_t       &x,
                                   Result         &result)
  {
    TimerSection t(problem.timer, "Bulk: solves with K0");
    bulk_solver.solve(b, x);
    problem.discretization.constraints.set_zero(x);
    ++result.bulk_solves;
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::solve(const std::vector<const Vector_t *> &b,
                                   const std::vector<Vector_t *>       &x,
                                   Result                              &result)
  {
    TimerSection t(problem.timer, "Bulk: solves with K0");
    bulk_solver.solve(b, x);
    for (Vector_t *xc : x)
      problem.discretization.constraints.set_zero(*xc);
    result.bulk_solves += b.size();
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::response(
    const std::vector<Tensor<1, dim>> &w_free,
    const std::vector<Tensor<1, dim>> &forces,
    const std::vector<unsigned int>   &with_force,
    std::vector<Tensor<1, dim>>       &w) const
  {
    w = w_free;
    subtract(forces, with_force, w);
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::subtract(
    const std::vector<Tensor<1, dim>> &forces,
    const std::vector<unsigned int>   &nodes,
    std::vector<Tensor<1, dim>>       &w) const
  {
    table.subtract(forces, nodes, w);
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::apply_k0(
    const std::vector<unsigned int>   &nodes,
    const std::vector<Tensor<1, dim>> &f,
    std::vector<Tensor<1, dim>>       &v,
    Result                            &result)
  {
    // The columns of the nodes and of the springs, then K0^{-1} from them.
    compute_columns(stiff_springs.needed_nodes(nodes, prepared_scheme), result);
    stiff_springs.apply_k0(table, nodes, f, v, prepared_scheme);
  }


  template <int dim>
  const std::vector<double> &
  BoundaryCompliance<dim>::weakening_limits(Result &result)
  {
    return measures.weakening_limits(result);
  }


  template <int dim>
  SpectralEstimate
  BoundaryCompliance<dim>::radius(const std::vector<Tensor<2, dim>> &roots,
                                  const bool                         certify)
  {
    return measures.radius(roots, certify);
  }

  template class BoundaryCompliance<2>;
  template class BoundaryCompliance<3>;
} // namespace DynamicContact
