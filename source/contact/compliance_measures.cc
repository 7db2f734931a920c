#include <deal.II/base/mpi.h>

#include <dynamic_contact/contact/boundary_compliance.h>
#include <dynamic_contact/contact/compliance_measures.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>
#include <dynamic_contact/contact/weakening_limit.h>

#include <algorithm>

namespace DynamicContact
{
  template <int dim>
  ComplianceMeasures<dim>::ComplianceMeasures(
    BoundaryCompliance<dim> &compliance)
    : compliance(compliance)
  {}


  template <int dim>
  void
  ComplianceMeasures<dim>::reinit()
  {
    limits_scheme = TimeScheme();
    limits.clear();
  }


  template <int dim>
  const std::vector<double> &
  ComplianceMeasures<dim>::weakening_limits(Result &result)
  {
    if (limits_scheme == compliance.prepared_scheme && !limits.empty())
      return limits;
    const auto               &all = compliance.gathered.all_nodes();
    std::vector<double>       local(all.size(), 0.), stiffness(all.size());
    std::vector<unsigned int> mine;
    std::vector<std::array<types::global_dof_index, dim>> dofs;
    for (unsigned int i = 0; i < all.size(); ++i)
      if (compliance.owned_index[i] >= 0 && all[i].unconstrained)
        {
          mine.push_back(i);
          dofs.push_back(all[i].dofs);
        }
    const auto blocks = compliance.problem.bulk.newton_blocks(dofs);
    for (unsigned int k = 0; k < mine.size(); ++k)
      local[mine[k]] =
        WeakeningLimit::tangential_stiffness(all[mine[k]], blocks[k]);
    Utilities::MPI::max(local,
                        compliance.problem.discretization.comm,
                        stiffness);
    // The sample's compliance under K0, as the assembled solver sees it,
    // from C: on rank 0, which holds it; the limits then to every process.
    const auto compliance_at = [&](const int j) {
      const std::vector<unsigned int> node = {static_cast<unsigned int>(j)};
      Tensor<2, dim>                  C;
      std::vector<Tensor<1, dim>>     v;
      for (unsigned int c = 0; c < dim; ++c)
        {
          std::vector<Tensor<1, dim>> e(1);
          e[0][c] = 1;
          compliance.apply_k0(node, e, v, result);
          for (unsigned int q = 0; q < dim; ++q)
            C[q][c] = v[0][q];
        }
      return WeakeningLimit::tangential_compliance(all[j], C);
    };
    compliance.on_leader(result, [&]() {
      limits =
        WeakeningLimit::limits(all, stiffness, compliance_at, MPI_COMM_SELF);
    });
    compliance.share(limits);
    limits_scheme = compliance.prepared_scheme;
    return limits;
  }


  template <int dim>
  SpectralEstimate
  ComplianceMeasures<dim>::radius(const std::vector<Tensor<2, dim>> &roots,
                                  const bool                         certify)
  {
    // The roots of every node: each process fills its own, a sum gathers.
    const auto         &all = compliance.gathered.all_nodes();
    std::vector<double> local(all.size() * dim * dim, 0.),
      every(all.size() * dim * dim);
    for (unsigned int i = 0; i < all.size(); ++i)
      if (compliance.owned_index[i] >= 0)
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            local[(i * dim + a) * dim + b] =
              roots[compliance.owned_index[i]][a][b];
    Utilities::MPI::sum(local, compliance.problem.discretization.comm, every);
    std::vector<unsigned int>   nodes;
    std::vector<Tensor<2, dim>> S;
    for (unsigned int i = 0; i < all.size(); ++i)
      {
        Tensor<2, dim> r;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            r[a][b] = every[(i * dim + a) * dim + b];
        if (r.norm_square() > 0)
          {
            nodes.push_back(i);
            S.push_back(r);
          }
      }
    if (nodes.empty())
      return SpectralEstimate{0., 0.};
    Result                      result;
    const unsigned int          n = nodes.size();
    std::vector<Tensor<1, dim>> z(n), v;
    const auto                  apply = [&](const std::vector<double> &x,
                           std::vector<double>       &y) {
      for (unsigned int b = 0; b < n; ++b)
        z[b] = S[b] * nodal_entries<dim>(x, b);
      compliance.apply_k0(nodes, z, v, result);
      for (unsigned int a = 0; a < n; ++a)
        set_nodal_entries<dim>(S[a] * v[a], a, y);
    };
    std::vector<double> start(dim * n);
    for (unsigned int a = 0; a < n; ++a)
      set_nodal_entries<dim>(S[a] * lanczos_start(all[nodes[a]]), a, start);
    // On rank 0, which holds C; the values then to every process.
    SpectralEstimate estimate;
    compliance.on_leader(result, [&]() {
      std::vector<double> ritz;
      estimate.lanczos = largest_eigenvalue(
        apply, start, [](const double v) { return v; }, 1e-10, 60, &ritz);
      if (!certify || !(estimate.lanczos < 1))
        return;
      // The columns and the springs' correction over these nodes (what
      // the Lanczos steps made, made once more where it took none).
      std::vector<Tensor<1, dim>> zero(n), unused;
      compliance.apply_k0(nodes, zero, unused, result);
      // x = 1 (the largest row sum) and x = |Ritz vector|, lifted to
      // positive entries.
      double top = 0;
      for (const double r : ritz)
        top = std::max(top, std::abs(r));
      std::vector<std::vector<double>> x(2, std::vector<double>(dim * n, 1.));
      for (unsigned int i = 0; i < dim * n; ++i)
        x[1][i] = std::abs(ritz[i]) + 1e-3 * top + 1e-300;
      estimate.upper = collatz_upper_bound(
        [&](const std::vector<std::vector<double>> &xs,
            std::vector<std::vector<double>>       &ys) {
          compliance.stiff_springs.apply_absolute(
            compliance.table, nodes, S, xs, ys);
        },
        x);
    });
    compliance.share(estimate.lanczos);
    compliance.share(estimate.upper);
    return estimate;
  }

  template class ComplianceMeasures<2>;
  template class ComplianceMeasures<3>;
} // namespace DynamicContact
