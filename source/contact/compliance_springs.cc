#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/contact/compliance_springs.h>

#include <algorithm>

namespace DynamicContact
{
  template <int dim>
  void
  ComplianceSprings<dim>::reinit()
  {
    correction_scheme = TimeScheme();
    choose_spring_nodes();
  }


  template <int dim>
  void
  ComplianceSprings<dim>::choose_spring_nodes()
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
  ComplianceSprings<dim>::add_springs(Matrix_t               &regularized,
                                      const std::vector<int> &owned_index)
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
  std::vector<unsigned int>
  ComplianceSprings<dim>::needed_nodes(const std::vector<unsigned int> &nodes,
                                       const TimeScheme &prepared_scheme)
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
    return needed;
  }


  template <int dim>
  void
  ComplianceSprings<dim>::apply_k0(const ComplianceTable<dim>        &table,
                                   const std::vector<unsigned int>   &nodes,
                                   const std::vector<Tensor<1, dim>> &f,
                                   std::vector<Tensor<1, dim>>       &v,
                                   const TimeScheme &prepared_scheme)
  {
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
                W(a, b)           = -table.column(l)[j][c][d];
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
        v[a] += table.column(nodes[b])[nodes[a]] * f[b];
    if (m == 0)
      return;
    Vector<double> at_springs(m), r(m);
    for (unsigned int e = 0; e < m; ++e)
      {
        const auto [j, c] = spring_dofs[e];
        for (unsigned int b = 0; b < nodes.size(); ++b)
          at_springs(e) += (table.column(nodes[b])[j] * f[b])[c];
      }
    spring_correction.vmult(r, at_springs);
    for (unsigned int e = 0; e < m; ++e)
      {
        const auto [j, c] = spring_dofs[e];
        for (unsigned int a = 0; a < nodes.size(); ++a)
          for (unsigned int q = 0; q < dim; ++q)
            v[a][q] += table.column(j)[nodes[a]][q][c] * r(e);
      }
  }


  template <int dim>
  void
  ComplianceSprings<dim>::apply_absolute(
    const ComplianceTable<dim>             &table,
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
              H[a](e, q) = table.column(nodes[a])[j][c][q];
              for (unsigned int f = 0; f < m; ++f)
                GW[a](q, f) +=
                  table.column(j)[nodes[a]][q][c] * spring_correction(e, f);
            }
        }
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        {
          Tensor<2, dim> K = table.column(nodes[b])[nodes[a]];
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

  template class ComplianceSprings<2>;
  template class ComplianceSprings<3>;
} // namespace DynamicContact
