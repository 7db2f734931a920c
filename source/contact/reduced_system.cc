#include <dynamic_contact/contact/reduced_system.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  namespace
  {
    /**
     * B = sum_r u_r v_r^T of the smallest number of terms, by elimination
     * with complete pivoting: each term removes the largest remaining entry
     * (a cross of B), until what remains is round-off (below 1e-13 of the
     * largest entry of B). A normal law's block, or a 2D slip law's, has
     * rank 1; zero has none.
     */
    template <int dim>
    void
    low_rank_factors(const Tensor<2, dim>        &B,
                     std::vector<Tensor<1, dim>> &u,
                     std::vector<Tensor<1, dim>> &v)
    {
      u.clear();
      v.clear();
      Tensor<2, dim> rest    = B;
      double         largest = 0;
      for (unsigned int p = 0; p < dim; ++p)
        for (unsigned int q = 0; q < dim; ++q)
          largest = std::max(largest, std::abs(B[p][q]));
      for (unsigned int term = 0; term < dim; ++term)
        {
          unsigned int pp = 0, qq = 0;
          for (unsigned int p = 0; p < dim; ++p)
            for (unsigned int q = 0; q < dim; ++q)
              if (std::abs(rest[p][q]) > std::abs(rest[pp][qq]))
                {
                  pp = p;
                  qq = q;
                }
          const double pivot = rest[pp][qq];
          if (!(std::abs(pivot) > 1e-13 * largest))
            break;
          Tensor<1, dim> column, row;
          for (unsigned int p = 0; p < dim; ++p)
            {
              column[p] = rest[p][qq];
              row[p]    = rest[pp][p] / pivot;
            }
          rest -= outer_product(column, row);
          u.push_back(column);
          v.push_back(row);
        }
    }
  } // namespace


  template <int dim>
  void
  ReducedSystem<dim>::reset()
  {
    matrix = LAPACKFullMatrix<double>();
    lu.reset();
    layout.clear();
  }


  template <int dim>
  void
  ReducedSystem<dim>::set_up_unknowns(const BoundaryIterate<dim> &it,
                                      const TimeScheme           &scheme)
  {
    const auto        &nodes    = gathered.all_nodes();
    const unsigned int n_active = active.size();
    offset.assign(n_active + 1, 0);
    n_low_rank.assign(n_active, 0);
    row_vectors.assign(n_active, {});
    column_vectors.assign(n_active, {});
    stick_target.assign(n_active, {});
    for (unsigned int a = 0; a < n_active; ++a)
      {
        const unsigned int i = active[a];
        const auto        &l = it.lin[i];
        low_rank_factors(l.block, column_vectors[a], row_vectors[a]);
        n_low_rank[a] = row_vectors[a].size();
        if (l.friction.state == FrictionState::stick)
          {
            const Tensor<1, dim> w_e = scheme.weighted(it.w[i], it.w_old[i]);
            for (const auto &t : nodes[i].tangents)
              {
                // The unknown is c_s l_s, a velocity like y (c_s = t_s . C_ii
                // t_s, the node's own tangential compliance): every entry of
                // the reduced matrix is then a pure number, and its pivots
                // are the same in any consistent system of units.
                const double c = t * (compliance.column(i)[i] * t);
                Assert(c > 0, ExcInternalError());
                row_vectors[a].push_back(t);
                column_vectors[a].push_back(t / c);
                // t_s . w_e = 0 at the new iterate: t_s . dw = -(t_s .
                // w_e)/theta.
                stick_target[a].push_back(-(t * w_e) /
                                          scheme.effective_derivative());
              }
          }
        offset[a + 1] = offset[a] + row_vectors[a].size();
      }
  }


  template <int dim>
  void
  ReducedSystem<dim>::assemble_and_factorize()
  {
    const unsigned int n_active = active.size();
    const unsigned int size     = offset[n_active];
    matrix.reinit(size, size);
    if (size > 0)
      {
        // Column by column (C_:j is contiguous in its column).
        for (unsigned int b = 0; b < n_active; ++b)
          {
            const auto &column = compliance.column(active[b]);
            for (unsigned int c = 0; c < column_vectors[b].size(); ++c)
              for (unsigned int a = 0; a < n_active; ++a)
                {
                  const Tensor<1, dim> Cu =
                    column[active[a]] * column_vectors[b][c];
                  const auto &rows = row_vectors[a];
                  for (unsigned int q = 0; q < rows.size(); ++q)
                    matrix(offset[a] + q, offset[b] + c) = rows[q] * Cu;
                }
          }
        for (unsigned int a = 0; a < n_active; ++a)
          for (unsigned int q = 0; q < n_low_rank[a]; ++q)
            matrix(offset[a] + q, offset[a] + q) += 1.;
      }
    std::vector<unsigned int> new_layout(active);
    new_layout.insert(new_layout.end(), offset.begin(), offset.end());
    // The factorization of the last reduced matrix serves while the
    // unknowns are the same (same active nodes, same kinds) and its
    // refinement converges (MixedPrecisionLU::reuse_for()).
    if (lu && new_layout == layout && size >= large_system)
      lu->reuse_for(matrix);
    else
      {
        lu     = std::make_unique<MixedPrecisionLU>(matrix, large_system);
        layout = std::move(new_layout);
      }
  }


  template <int dim>
  void
  ReducedSystem<dim>::solve(const std::vector<Tensor<1, dim>>      &rr,
                            const std::vector<std::vector<double>> &tg,
                            Vector<double>                         &xx,
                            std::vector<Tensor<1, dim>>            &dd)
  {
    // dd_i = rr_i - sum_j C_ij (U_j y_j + T_j l_j) cancels digits where the
    // foundation is stiff (C B >> 1: the sum is nearly rr_i); its
    // components along the rows of node i are known exactly and are set
    // (project_onto_rows()).
    const unsigned int n_active = active.size();
    xx.reinit(offset[n_active]);
    for (unsigned int a = 0; a < n_active; ++a)
      {
        for (unsigned int q = 0; q < row_vectors[a].size(); ++q)
          xx(offset[a] + q) = row_vectors[a][q] * rr[a];
        for (unsigned int s = 0; s < tg[a].size(); ++s)
          xx(offset[a] + n_low_rank[a] + s) -= tg[a][s];
      }
    lu->solve(xx);
    force_change.resize(n_active);
    for (unsigned int b = 0; b < n_active; ++b)
      {
        force_change[b] = Tensor<1, dim>();
        for (unsigned int c = 0; c < column_vectors[b].size(); ++c)
          force_change[b] += xx(offset[b] + c) * column_vectors[b][c];
      }
    dd = rr;
    for (unsigned int b = 0; b < n_active; ++b)
      {
        const auto &column = compliance.column(active[b]);
        for (unsigned int a = 0; a < n_active; ++a)
          dd[a] -= column[active[a]] * force_change[b];
      }
    for (unsigned int a = 0; a < n_active; ++a)
      project_onto_rows(a, xx, tg, dd[a]);
  }


  template <int dim>
  void
  ReducedSystem<dim>::project_onto_rows(
    const unsigned int                      a,
    const Vector<double>                   &xx,
    const std::vector<std::vector<double>> &tg,
    Tensor<1, dim>                         &dd)
  {
    // The rows made orthonormal, dependent ones dropped (a spring node
    // that sticks has dim + 1 of them).
    basis.clear();
    basis_value.clear();
    for (unsigned int q = 0; q < row_vectors[a].size(); ++q)
      {
        Tensor<1, dim> row   = row_vectors[a][q];
        double         value = q < n_low_rank[a] ? xx(offset[a] + q) :
                                                   tg[a][q - n_low_rank[a]];
        for (unsigned int e = 0; e < basis.size(); ++e)
          {
            const double c = row * basis[e];
            row -= c * basis[e];
            value -= c * basis_value[e];
          }
        const double norm = row.norm();
        if (norm > 1e-10 * row_vectors[a][q].norm())
          {
            basis.push_back(row / norm);
            basis_value.push_back(value / norm);
          }
      }
    for (unsigned int e = 0; e < basis.size(); ++e)
      dd += (basis_value[e] - basis[e] * dd) * basis[e];
  }


  template <int dim>
  Tensor<1, dim>
  ReducedSystem<dim>::stick_force(const Vector<double> &xx,
                                  const unsigned int    a) const
  {
    Tensor<1, dim> l;
    for (unsigned int c = n_low_rank[a]; c < column_vectors[a].size(); ++c)
      l += xx(offset[a] + c) * column_vectors[a][c];
    return l;
  }


  template <int dim>
  void
  ReducedSystem<dim>::refine(const BoundaryIterate<dim>        &it,
                             const std::vector<Tensor<1, dim>> &r,
                             Vector<double>                    &x,
                             std::vector<Tensor<1, dim>>       &dw)
  {
    // The residual of the unreduced system, e_i = r_i - dw_i - sum_j C_ij
    // (B_j dw_j + T_j l_j), is the round-off the reconstruction left (the
    // stick constraints hold).
    const unsigned int          n_active = active.size();
    std::vector<Tensor<1, dim>> full_change(n_active), e(n_active), de;
    for (unsigned int b = 0; b < n_active; ++b)
      full_change[b] = it.lin[active[b]].block * dw[b] + stick_force(x, b);
    for (unsigned int a = 0; a < n_active; ++a)
      e[a] = r[a] - dw[a];
    for (unsigned int b = 0; b < n_active; ++b)
      {
        const auto &column = compliance.column(active[b]);
        for (unsigned int a = 0; a < n_active; ++a)
          e[a] -= column[active[a]] * full_change[b];
      }
    Vector<double> dx;
    auto           no_target = stick_target;
    for (auto &t : no_target)
      std::fill(t.begin(), t.end(), 0.);
    solve(e, no_target, dx, de);
    x += dx;
    for (unsigned int a = 0; a < n_active; ++a)
      dw[a] += de[a];
  }


  template <int dim>
  void
  ReducedSystem<dim>::step(const BoundaryIterate<dim>        &it,
                           const TimeScheme                  &scheme,
                           const std::vector<Tensor<1, dim>> &r,
                           std::vector<Tensor<1, dim>>       &dw,
                           std::vector<Tensor<1, dim>>       &lambda,
                           std::vector<Tensor<1, dim>>       &new_forces,
                           const bool far_from_solution)
  {
    active                     = it.active;
    const unsigned int n_active = active.size();
    set_up_unknowns(it, scheme);
    dw.assign(n_active, Tensor<1, dim>());
    new_forces.assign(gathered.all_nodes().size(), Tensor<1, dim>());
    for (auto &l : lambda)
      l = Tensor<1, dim>();
    assemble_and_factorize();

    Vector<double> x;
    solve(r, stick_target, x, dw);
    if (!far_from_solution || offset[n_active] < large_system)
      refine(it, r, x, dw);

    for (unsigned int a = 0; a < n_active; ++a)
      {
        const unsigned int j = active[a];
        const auto        &l = it.lin[j];
        if (l.friction.state == FrictionState::slip)
          lambda[j] = l.friction.value + l.friction.jacobian * dw[a];
        else if (l.friction.state == FrictionState::stick)
          lambda[j] = stick_force(x, a);
        // base_j + block_j dw + T_j l_j, with the springs' part (g form).
        new_forces[j] = it.base[j] + l.block * dw[a];
        if (l.friction.state == FrictionState::stick)
          new_forces[j] += lambda[j];
      }
  }


  template class ReducedSystem<2>;
  template class ReducedSystem<3>;
} // namespace DynamicContact
