#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/boundary_compliance.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>
#include <dynamic_contact/contact/weakening_limit.h>

#include <algorithm>

namespace DynamicContact
{
  template <int dim>
  BoundaryCompliance<dim>::BoundaryCompliance(
    const ContactProblem<dim>   &problem,
    const GatheredBoundary<dim> &gathered)
    : problem(problem)
    , gathered(gathered)
    , bulk_solver(problem.parameters)
  {}


  template <int dim>
  void
  BoundaryCompliance<dim>::reinit()
  {
    const auto &all = gathered.all_nodes();
    columns.assign(all.size(), {});
    made.assign(all.size(), false);
    full_columns.assign(dim * all.size(), {});
    full_column_stored.assign(all.size(), false);
    stored_full_columns = 0;
    max_owned_dofs =
      Utilities::MPI::max(problem.discretization.locally_owned.n_elements(),
                          problem.discretization.comm);
    owned_index.assign(all.size(), -1);
    const auto &global = gathered.global_indices();
    for (unsigned int i = 0; i < global.size(); ++i)
      owned_index[global[i]] = i;
    prepared_scheme   = TimeScheme();
    limits_scheme     = TimeScheme();
    correction_scheme = TimeScheme();
    limits.clear();
    regularized.reinit(problem.bulk.sparsity_pattern());
    choose_spring_nodes();
  }


  template <int dim>
  bool
  BoundaryCompliance<dim>::holds_tables() const
  {
    return Utilities::MPI::this_mpi_process(
             problem.boundary.get_mpi_communicator()) == 0;
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::on_leader(Result                      &result,
                                     const std::function<void()> &work)
  {
    Assert(leading == nullptr, ExcInternalError());
    LeadingProcess lead(problem.boundary.get_mpi_communicator(),
                        [&](const std::vector<unsigned int> &nodes) {
                          make_columns(nodes, result);
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
  BoundaryCompliance<dim>::choose_spring_nodes()
  {
    // Extreme nodes: the first and last by position and, in 3D, the one
    // farthest from the line through them; among the unconstrained nodes,
    // or, if there are fewer than two, among the nodes with a free component
    // and axis-parallel constraints (the springs act on the free components).
    const auto &all = gathered.all_nodes();
    spring_nodes.clear();
    springs.assign(all.size(), 0.);
    std::vector<unsigned int> free_nodes;
    for (unsigned int i = 0; i < all.size(); ++i)
      if (all[i].unconstrained)
        free_nodes.push_back(i);
    if (free_nodes.size() < 2)
      {
        free_nodes.clear();
        for (unsigned int i = 0; i < all.size(); ++i)
          {
            const auto &P        = all[i].constraint_map;
            bool        diagonal = true, some_free = false;
            for (unsigned int r = 0; r < dim; ++r)
              for (unsigned int c = 0; c < dim; ++c)
                if (r != c && P[r][c] != 0)
                  diagonal = false;
            for (unsigned int c = 0; c < dim; ++c)
              some_free = some_free || P[c][c] == 1;
            if (diagonal && some_free)
              free_nodes.push_back(i);
          }
      }
    if (free_nodes.empty())
      return;
    spring_nodes.push_back(free_nodes.front());
    if (free_nodes.size() > 1)
      spring_nodes.push_back(free_nodes.back());
    if (dim == 3 && free_nodes.size() > 2)
      {
        const Point<dim> a = all[spring_nodes[0]].position;
        Tensor<1, dim>   d = all[spring_nodes[1]].position - a;
        if (d.norm() > 0)
          d /= d.norm();
        unsigned int far      = free_nodes[1];
        double       distance = -1;
        for (const unsigned int i : free_nodes)
          {
            const Tensor<1, dim> r = all[i].position - a;
            const double         e = (r - (r * d) * d).norm();
            if (e > distance)
              {
                distance = e;
                far      = i;
              }
          }
        if (distance > 0)
          spring_nodes.push_back(far);
      }
  }

  template <int dim>
  void
  BoundaryCompliance<dim>::add_springs()
  {
    const Matrix_t &K0 = problem.bulk.newton_matrix();
    regularized.copy_from(K0);
    const auto         &all = gathered.all_nodes();
    std::vector<double> local(all.size(), 0.);
    for (const unsigned int j : spring_nodes)
      if (owned_index[j] >= 0)
        for (const auto dof : all[j].dofs)
          local[j] = std::max(local[j], K0.diag_element(dof));
    Utilities::MPI::max(local, problem.discretization.comm, springs);
    // Springs on the free components: S_j = s_j P_j (P_j diagonal).
    for (const unsigned int j : spring_nodes)
      if (owned_index[j] >= 0)
        for (unsigned int c = 0; c < dim; ++c)
          if (all[j].constraint_map[c][c] == 1)
            regularized.add(all[j].dofs[c], all[j].dofs[c], springs[j]);
    regularized.compress(VectorOperation::add);
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
    double c = 0, full = 0;
    for (const auto &column : columns)
      c += column.size() * sizeof(Tensor<2, dim>);
    for (const auto &column : full_columns)
      full += column.size() * sizeof(double);
    // The same items on every process (a process may own none of them).
    items.push_back({"compliance C of Gamma_3", c, false});
    items.push_back({"whole responses to Gamma_3", full, false});
  }


  template <int dim>
  bool
  BoundaryCompliance<dim>::prepare(Result &result)
  {
    if (problem.bulk.scheme() == prepared_scheme)
      return false;
    add_springs();
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
    for (auto &c : columns)
      c.clear();
    made.assign(made.size(), false);
    for (auto &c : full_columns)
      std::vector<double>().swap(c);
    full_column_stored.assign(full_column_stored.size(), false);
    stored_full_columns = 0;
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
  bool
  BoundaryCompliance<dim>::apply_full_columns(
    const std::vector<Tensor<1, dim>> &f,
    const std::vector<unsigned int>   &nodes,
    Vector_t                          &x) const
  {
    for (const unsigned int j : nodes)
      if (!full_column_stored[j])
        return false;
    TimerSection t(problem.timer, "Bulk: sums of compliance columns");
    x            = 0;
    double    *y = x.trilinos_vector()[0];
    const auto n = problem.discretization.locally_owned.n_elements();
    for (const unsigned int j : nodes)
      for (unsigned int c = 0; c < dim; ++c)
        if (f[j][c] != 0)
          {
            const double  a      = f[j][c];
            const double *column = full_columns[dim * j + c].data();
            for (std::size_t i = 0; i < n; ++i)
              y[i] += a * column[i];
          }
    problem.discretization.constraints.set_zero(x);
    return true;
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
    for (const unsigned int j : nodes)
      for (unsigned int i = 0; i < w.size(); ++i)
        w[i] -= columns[j][i] * forces[j];
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::apply_k0(
    const std::vector<unsigned int>   &nodes,
    const std::vector<Tensor<1, dim>> &f,
    std::vector<Tensor<1, dim>>       &v,
    Result                            &result)
  {
    const auto &all = gathered.all_nodes();
    if (correction_scheme != prepared_scheme || spring_dofs.empty())
      {
        spring_dofs.clear();
        for (const unsigned int j : spring_nodes)
          if (springs[j] > 0)
            for (unsigned int c = 0; c < dim; ++c)
              if (all[j].constraint_map[c][c] == 1)
                spring_dofs.emplace_back(j, c);
      }
    std::vector<unsigned int> needed(nodes);
    for (const auto &[j, c] : spring_dofs)
      needed.push_back(j);
    compute_columns(needed, result);
    const unsigned int m = spring_dofs.size();
    if (correction_scheme != prepared_scheme)
      {
        // W = S^{-1} - P C' P^T, inverted (m <= 3 dim).
        FullMatrix<double> W(m, m);
        for (unsigned int a = 0; a < m; ++a)
          {
            const auto [j, c] = spring_dofs[a];
            for (unsigned int b = 0; b < m; ++b)
              {
                const auto [l, d] = spring_dofs[b];
                W(a, b)           = -columns[l][j][c][d];
              }
            W(a, a) += 1. / springs[j];
          }
        spring_correction.reinit(m, m);
        if (m > 0)
          spring_correction.invert(W);
        correction_scheme = prepared_scheme;
      }
    // v = C' f, then + C' P^T W^{-1} P C' f.
    v.assign(nodes.size(), Tensor<1, dim>());
    for (unsigned int a = 0; a < nodes.size(); ++a)
      for (unsigned int b = 0; b < nodes.size(); ++b)
        v[a] += columns[nodes[b]][nodes[a]] * f[b];
    if (m == 0)
      return;
    Vector<double> at_springs(m), r(m);
    for (unsigned int e = 0; e < m; ++e)
      {
        const auto [j, c] = spring_dofs[e];
        for (unsigned int b = 0; b < nodes.size(); ++b)
          at_springs(e) += (columns[nodes[b]][j] * f[b])[c];
      }
    spring_correction.vmult(r, at_springs);
    for (unsigned int e = 0; e < m; ++e)
      {
        const auto [j, c] = spring_dofs[e];
        for (unsigned int a = 0; a < nodes.size(); ++a)
          for (unsigned int q = 0; q < dim; ++q)
            v[a][q] += columns[j][nodes[a]][q][c] * r(e);
      }
  }


  template <int dim>
  const std::vector<double> &
  BoundaryCompliance<dim>::weakening_limits(Result &result)
  {
    if (limits_scheme == prepared_scheme && !limits.empty())
      return limits;
    const auto         &all = gathered.all_nodes();
    std::vector<double> local(all.size(), 0.), stiffness(all.size());
    std::vector<unsigned int>                                  mine;
    std::vector<std::array<types::global_dof_index, dim>>      dofs;
    for (unsigned int i = 0; i < all.size(); ++i)
      if (owned_index[i] >= 0 && all[i].unconstrained)
        {
          mine.push_back(i);
          dofs.push_back(all[i].dofs);
        }
    const auto blocks = problem.bulk.newton_blocks(dofs);
    for (unsigned int k = 0; k < mine.size(); ++k)
      local[mine[k]] =
        WeakeningLimit::tangential_stiffness(all[mine[k]], blocks[k]);
    Utilities::MPI::max(local, problem.discretization.comm, stiffness);
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
          apply_k0(node, e, v, result);
          for (unsigned int q = 0; q < dim; ++q)
            C[q][c] = v[0][q];
        }
      return WeakeningLimit::tangential_compliance(all[j], C);
    };
    on_leader(result, [&]() {
      limits =
        WeakeningLimit::limits(all, stiffness, compliance_at, MPI_COMM_SELF);
    });
    share(limits);
    limits_scheme = prepared_scheme;
    return limits;
  }


  template <int dim>
  void
  BoundaryCompliance<dim>::apply_absolute(
    const std::vector<unsigned int>        &nodes,
    const std::vector<Tensor<2, dim>>      &R,
    const std::vector<std::vector<double>> &x,
    std::vector<std::vector<double>>       &y) const
  {
    // [K0^{-1}]_ab = C'_ab + G_a W^{-1} H_b (apply_k0()): G_a[q][e] the
    // response at a to spring DoF e, H_b[e][r] that of DoF e to a force
    // at b.
    const unsigned int              n = nodes.size(), m = spring_dofs.size();
    std::vector<FullMatrix<double>> GW(n, FullMatrix<double>(dim, m)),
      H(n, FullMatrix<double>(m, dim));
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int e = 0; e < m; ++e)
        {
          const auto [j, c] = spring_dofs[e];
          for (unsigned int q = 0; q < dim; ++q)
            {
              H[a](e, q) = columns[nodes[a]][j][c][q];
              for (unsigned int f = 0; f < m; ++f)
                GW[a](q, f) +=
                  columns[j][nodes[a]][q][c] * spring_correction(e, f);
            }
        }
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        {
          Tensor<2, dim> K = columns[nodes[b]][nodes[a]];
          for (unsigned int q = 0; q < dim; ++q)
            for (unsigned int r = 0; r < dim; ++r)
              for (unsigned int e = 0; e < m; ++e)
                K[q][r] += GW[a](q, e) * H[b](e, r);
          const Tensor<2, dim> A = R[a] * K * R[b];
          for (std::size_t v = 0; v < x.size(); ++v)
            for (unsigned int q = 0; q < dim; ++q)
              for (unsigned int r = 0; r < dim; ++r)
                y[v][dim * a + q] += std::abs(A[q][r]) * x[v][dim * b + r];
        }
  }


  template <int dim>
  SpectralEstimate
  BoundaryCompliance<dim>::radius(const std::vector<Tensor<2, dim>> &roots,
                                  const bool                         certify)
  {
    // The roots of every node: each process fills its own, a sum gathers.
    const auto                 &all = gathered.all_nodes();
    std::vector<double>         local(all.size() * dim * dim, 0.),
      every(all.size() * dim * dim);
    for (unsigned int i = 0; i < all.size(); ++i)
      if (owned_index[i] >= 0)
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            local[(i * dim + a) * dim + b] = roots[owned_index[i]][a][b];
    Utilities::MPI::sum(local, problem.discretization.comm, every);
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
    const auto apply = [&](const std::vector<double> &x,
                           std::vector<double>       &y) {
      for (unsigned int b = 0; b < n; ++b)
        z[b] = S[b] * nodal_entries<dim>(x, b);
      apply_k0(nodes, z, v, result);
      for (unsigned int a = 0; a < n; ++a)
        set_nodal_entries<dim>(S[a] * v[a], a, y);
    };
    std::vector<double> start(dim * n);
    for (unsigned int a = 0; a < n; ++a)
      set_nodal_entries<dim>(S[a] * lanczos_start(all[nodes[a]]), a, start);
    // On rank 0, which holds C; the values then to every process.
    SpectralEstimate estimate;
    on_leader(result, [&]() {
      std::vector<double> ritz;
      estimate.lanczos = largest_eigenvalue(
        apply, start, [](const double v) { return v; }, 1e-10, 60, &ritz);
      if (!certify || !(estimate.lanczos < 1))
        return;
      // The columns and the springs' correction over these nodes (what
      // the Lanczos steps made, made once more where it took none).
      std::vector<Tensor<1, dim>> zero(n), unused;
      apply_k0(nodes, zero, unused, result);
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
          apply_absolute(nodes, S, xs, ys);
        },
        x);
    });
    share(estimate.lanczos);
    share(estimate.upper);
    return estimate;
  }

  template class BoundaryCompliance<2>;
  template class BoundaryCompliance<3>;
} // namespace DynamicContact
