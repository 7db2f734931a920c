#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/contact/condensed_newton.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>
#include <dynamic_contact/contact/mixed_precision_lu.h>
#include <dynamic_contact/contact/newton_driver.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/weakening_limit.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

namespace DynamicContact
{
  template <int dim>
  CondensedNewton<dim>::CondensedNewton(const ContactProblem<dim> &problem)
    : problem(problem)
    , bulk_solver(problem.parameters)
  {}


  template <int dim>
  void
  CondensedNewton<dim>::reinit()
  {
    gathered.reinit(problem.boundary);
    const auto &all = gathered.all_nodes();
    columns.assign(all.size(), {});
    full_columns.assign(dim * all.size(), {});
    full_column_stored.assign(all.size(), false);
    stored_full_columns = 0;
    pending.reset();
    max_owned_dofs =
      Utilities::MPI::max(problem.discretization.locally_owned.n_elements(),
                          problem.discretization.comm);
    owned_index.assign(all.size(), -1);
    const auto &global = gathered.global_indices();
    for (unsigned int i = 0; i < global.size(); ++i)
      owned_index[global[i]] = i;
    prepared_scheme     = TimeScheme();
    limits_scheme       = TimeScheme();
    correction_scheme   = TimeScheme();
    weakening_limits.clear();
    free_response_valid = false;
    regularized.reinit(problem.bulk.sparsity_pattern());
    choose_spring_nodes();
    problem.discretization.reinit_owned(solution);
    problem.discretization.reinit_owned(right_hand_side);
    problem.discretization.reinit_owned(residual);
    problem.discretization.reinit_owned(increment);
    problem.discretization.reinit_owned(scratch);
    problem.discretization.reinit_owned(free_response);
    problem.discretization.reinit_owned(cached_rhs);
  }


  template <int dim>
  void
  CondensedNewton<dim>::choose_spring_nodes()
  {
    // Extreme nodes: the first and last by position and, in 3D, the one
    // farthest from the line through them; among the unconstrained nodes,
    // or, if there are fewer than two, among the nodes with a free component
    // and axis-parallel constraints (the springs act on the free components).
    const auto &all = gathered.all_nodes();
    spring_nodes.clear();
    spring_stiffness.assign(all.size(), 0.);
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
  CondensedNewton<dim>::prepare(Result &result)
  {
    if (problem.bulk.scheme() == prepared_scheme)
      return;
    // K0' = K0 + S.
    const Matrix_t &K0 = problem.bulk.newton_matrix();
    regularized.copy_from(K0);
    {
      const auto         &all = gathered.all_nodes();
      std::vector<double> local(all.size(), 0.);
      for (const unsigned int j : spring_nodes)
        if (owned_index[j] >= 0)
          for (const auto dof : all[j].dofs)
            local[j] = std::max(local[j], K0.diag_element(dof));
      Utilities::MPI::max(local, problem.discretization.comm, spring_stiffness);
      // Springs on the free components: S_j = s_j P_j (P_j diagonal).
      for (const unsigned int j : spring_nodes)
        if (owned_index[j] >= 0)
          for (unsigned int c = 0; c < dim; ++c)
            if (all[j].constraint_map[c][c] == 1)
              regularized.add(all[j].dofs[c],
                              all[j].dofs[c],
                              spring_stiffness[j]);
      regularized.compress(VectorOperation::add);
    }
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
    prepared_scheme     = problem.bulk.scheme();
    free_response_valid = false;
    // C depends on K0: forget it, and the reduced matrices made from it.
    for (auto &c : columns)
      c.clear();
    reduced = Reduced();
    for (auto &c : full_columns)
      std::vector<double>().swap(c);
    full_column_stored.assign(full_column_stored.size(), false);
    stored_full_columns = 0;
  }


  template <int dim>
  void
  CondensedNewton<dim>::solve_bulk(const Vector_t &b,
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
  CondensedNewton<dim>::solve_bulk(const std::vector<const Vector_t *> &b,
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
  CondensedNewton<dim>::apply_full_columns(
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
  CondensedNewton<dim>::compliance_response(
    const std::vector<Tensor<1, dim>> &w_free,
    const std::vector<Tensor<1, dim>> &forces,
    const std::vector<unsigned int>   &with_force,
    std::vector<Tensor<1, dim>>       &w) const
  {
    w = w_free;
    subtract_compliance(forces, with_force, w);
  }


  template <int dim>
  void
  CondensedNewton<dim>::subtract_compliance(
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
  CondensedNewton<dim>::linearize(Iterate &it) const
  {
    const auto        &u_old   = u_old_all;
    const auto        &w_old   = w_old_all;
    const auto        &mu      = mu_all;
    const auto        &lambda  = it.lambda;
    const auto        &w_nodes = it.w;
    const auto        &nodes   = gathered.all_nodes();
    const unsigned int n       = nodes.size();
    it.w_old                   = w_old;
    it.lin.resize(n);
    it.forces.resize(n);
    it.base_true.resize(n);
    it.g.resize(n);
    it.base.resize(n);
    it.signature = 0;
    it.active.clear();
    it.f_scale      = 1e-300;
    it.law_residual = 0;
    it.law_squares  = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const NodeEvaluation<dim> e = evaluate_node(problem,
                                                    nodes[i],
                                                    u_old[i],
                                                    w_old[i],
                                                    w_nodes[i],
                                                    lambda[i],
                                                    mu,
                                                    i);
        const auto               &l = it.lin[i] = e.lin;
        it.forces[i]                            = e.force;
        it.base_true[i]                         = e.base;
        // Condensation with K0' = K0 + S sees the forces minus the springs'.
        // S_i = s_i P_i, and P_i w_i = w_i (P_i diagonal, 0 or 1).
        const double s = spring_stiffness[i];
        it.g[i]        = it.forces[i] - s * w_nodes[i];
        it.base[i]     = it.base_true[i] - s * w_nodes[i];
        if (s > 0)
          it.lin[i].block -= s * nodes[i].constraint_map;
        it.signature += e.signature;
        it.f_scale      = std::max(it.f_scale, e.force.norm());
        it.law_residual = std::max(it.law_residual, e.law_residual);
        it.law_squares += e.law_residual * e.law_residual;
        if (l.active() || it.forces[i].norm_square() > 0 || s > 0)
          it.active.push_back(i);
      }
  }


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
  CondensedNewton<dim>::dense_step(const Iterate                     &it,
                                   const std::vector<Tensor<1, dim>> &r,
                                   std::vector<Tensor<1, dim>>       &dw,
                                   std::vector<Tensor<1, dim>>       &lambda,
                                   std::vector<Tensor<1, dim>> &new_forces,
                                   const bool far_from_solution) const
  {
    // The Newton system on the active nodes,
    //   dw_i + sum_j C_ij (B_j dw_j + T_j l_j) = r_i,
    //   t_s . (w_i + dw_i) = 0 at stick nodes (l_j their tangential force),
    // reduced to the forces: with B_j = U_j V_j^T of rank k_j (a normal law,
    // a 2D slip law: rank 1) and y_j = V_j^T dw_j, dw_i = r_i - sum_j C_ij
    // (U_j y_j + T_j l_j), and the unknowns y and l solve
    //   y_i + V_i^T sum_j C_ij (U_j y_j + T_j l_j) = V_i^T r_i,
    //   t_s^T sum_j C_ij (U_j y_j + T_j l_j) = t_s^T r_i - target_s,
    // sum_j k_j + (dim - 1) n_stick unknowns instead of dim n + (dim - 1)
    // n_stick (the same Newton step; in 2D about half as many unknowns, an
    // LU several times cheaper). Stick rows are scaled by 1/(t_s^T C_ii t_s).
    const auto        &nodes    = gathered.all_nodes();
    const auto        &active   = it.active;
    const unsigned int n_active = active.size();
    const TimeScheme  &scheme   = problem.bulk.scheme();

    // Per active node: the row vectors (V_i, then the scaled tangents) and
    // the column vectors (U_i, then the tangents) of its unknowns.
    std::vector<unsigned int>                offset(n_active + 1, 0);
    std::vector<unsigned int>                n_low_rank(n_active, 0);
    std::vector<std::vector<Tensor<1, dim>>> row_vectors(n_active),
      column_vectors(n_active);
    std::vector<std::vector<double>> stick_target(n_active);
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
                const double c     = t * (columns[i][i] * t);
                const double scale = c > 0 ? 1. / c : 1.;
                row_vectors[a].push_back(scale * t);
                column_vectors[a].push_back(t);
                // t_s . w_e = 0 at the new iterate: t_s . dw = -(t_s .
                // w_e)/theta (scaled like the row).
                stick_target[a].push_back(-scale * (t * w_e) /
                                          scheme.effective_derivative());
              }
          }
        offset[a + 1] = offset[a] + row_vectors[a].size();
      }
    const unsigned int size = offset[n_active];

    dw.assign(n_active, Tensor<1, dim>());
    new_forces.assign(nodes.size(), Tensor<1, dim>());
    for (auto &l : lambda)
      l = Tensor<1, dim>();
    LAPACKFullMatrix<double> &matrix = reduced.matrix;
    matrix.reinit(size, size);
    if (size > 0)
      {
        // Column by column (C_:j is contiguous in columns[j]).
        for (unsigned int b = 0; b < n_active; ++b)
          {
            const auto &column = columns[active[b]];
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
    std::vector<unsigned int> layout(active);
    layout.insert(layout.end(), offset.begin(), offset.end());
    // The factorization of the last reduced matrix serves while the
    // unknowns are the same (same active nodes, same kinds) and its
    // refinement converges (MixedPrecisionLU::reuse_for()).
    if (reduced.lu && layout == reduced.layout && size >= large_system)
      reduced.lu->reuse_for(matrix);
    else
      {
        reduced.lu = std::make_unique<MixedPrecisionLU>(matrix, large_system);
        reduced.layout = std::move(layout);
      }
    MixedPrecisionLU &lu = *reduced.lu;

    // The reduced system for the right-hand side @p rr and stick targets
    // @p tg: its unknowns @p xx and the velocities @p dd. dd_i = rr_i -
    // sum_j C_ij (U_j y_j + T_j l_j) cancels digits where the foundation is
    // stiff (C B >> 1: the sum is nearly rr_i); its components along the
    // rows of node i are known exactly (V_i^T dd_i = y_i, t_s . dd_i =
    // target_s) and are set: dd_i is projected onto these affine
    // constraints (their rows made orthonormal, dependent ones dropped: a
    // spring node that sticks has dim + 1 of them).
    std::vector<Tensor<1, dim>> force_change(n_active), basis;
    std::vector<double>         basis_value;
    const auto solve_reduced = [&](const std::vector<Tensor<1, dim>>      &rr,
                                   const std::vector<std::vector<double>> &tg,
                                   Vector<double>                         &xx,
                                   std::vector<Tensor<1, dim>>            &dd) {
      xx.reinit(size);
      for (unsigned int a = 0; a < n_active; ++a)
        {
          for (unsigned int q = 0; q < row_vectors[a].size(); ++q)
            xx(offset[a] + q) = row_vectors[a][q] * rr[a];
          for (unsigned int s = 0; s < tg[a].size(); ++s)
            xx(offset[a] + n_low_rank[a] + s) -= tg[a][s];
        }
      lu.solve(xx);
      for (unsigned int b = 0; b < n_active; ++b)
        {
          force_change[b] = Tensor<1, dim>();
          for (unsigned int c = 0; c < column_vectors[b].size(); ++c)
            force_change[b] += xx(offset[b] + c) * column_vectors[b][c];
        }
      dd = rr;
      for (unsigned int b = 0; b < n_active; ++b)
        {
          const auto &column = columns[active[b]];
          for (unsigned int a = 0; a < n_active; ++a)
            dd[a] -= column[active[a]] * force_change[b];
        }
      for (unsigned int a = 0; a < n_active; ++a)
        {
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
            dd[a] += (basis_value[e] - basis[e] * dd[a]) * basis[e];
        }
    };
    // The tangential force at a stick node from the unknowns.
    const auto stick_force = [&](const Vector<double> &xx,
                                 const unsigned int    a) {
      Tensor<1, dim> l;
      for (unsigned int c = n_low_rank[a]; c < column_vectors[a].size(); ++c)
        l += xx(offset[a] + c) * column_vectors[a][c];
      return l;
    };

    Vector<double> x;
    solve_reduced(r, stick_target, x, dw);
    // One step of iterative refinement on the unreduced system, whose
    // residual e_i = r_i - dw_i - sum_j C_ij (B_j dw_j + T_j l_j) is the
    // round-off the reconstruction left (the stick constraints hold).
    if (!far_from_solution || size < large_system)
      {
        std::vector<Tensor<1, dim>> full_change(n_active), e(n_active), de;
        for (unsigned int b = 0; b < n_active; ++b)
          full_change[b] = it.lin[active[b]].block * dw[b] + stick_force(x, b);
        for (unsigned int a = 0; a < n_active; ++a)
          e[a] = r[a] - dw[a];
        for (unsigned int b = 0; b < n_active; ++b)
          {
            const auto &column = columns[active[b]];
            for (unsigned int a = 0; a < n_active; ++a)
              e[a] -= column[active[a]] * full_change[b];
          }
        Vector<double> dx;
        auto           no_target = stick_target;
        for (auto &t : no_target)
          std::fill(t.begin(), t.end(), 0.);
        solve_reduced(e, no_target, dx, de);
        x += dx;
        for (unsigned int a = 0; a < n_active; ++a)
          dw[a] += de[a];
      }

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


  template <int dim>
  void
  CondensedNewton<dim>::add_nodal_forces(const std::vector<Tensor<1, dim>> &f,
                                         const double factor,
                                         Vector_t    &v) const
  {
    const auto &global = gathered.global_indices();
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return f[global[i]]; }, factor, v);
  }


  /**
   * Phase 1 of CondensedNewton::solve() as globalized_newton() sees it: the
   * iterates are the velocities and friction forces at every node of
   * Gamma_3, the equilibrium is w_i = w_free,i - sum_j C_ij g_j, the merit
   * half the sum of the squared equilibrium and law residuals (each relative
   * to its scale).
   */
  template <int dim>
  class CondensedNewton<dim>::BoundaryProblem
  {
  public:
    using Iterate = typename CondensedNewton<dim>::Iterate;

    BoundaryProblem(CondensedNewton<dim> &solver,
                    const double          w_scale,
                    Result               &result)
      : solver(solver)
      , w_scale(w_scale)
      , result(result)
    {}

    NewtonMeasure
    evaluate(Iterate &x)
    {
      solver.linearize(x);
      solver.compute_columns(x.active, result);
      solver.compliance_response(solver.w_free_nodes,
                                 x.g,
                                 x.active,
                                 x.response);
      const auto &response  = x.response;
      x.equilibrium         = 0;
      x.equilibrium_squares = 0;
      for (unsigned int i = 0; i < x.w.size(); ++i)
        {
          const double e = (x.w[i] - response[i]).norm();
          x.equilibrium  = std::max(x.equilibrium, e);
          x.equilibrium_squares += e * e;
        }
      NewtonMeasure m;
      m.residual  = residual(x);
      m.merit     = merit(x, x);
      m.signature = x.signature;
      return m;
    }

    /** The relative residual of an evaluated iterate. */
    double
    residual(const Iterate &x) const
    {
      return std::max(x.equilibrium / w_scale, x.law_residual / x.f_scale);
    }

    /** With the force scale of the current iterate. */
    double
    merit(const Iterate &trial, const Iterate &current) const
    {
      const double f = current.f_scale;
      return 0.5 * (trial.equilibrium_squares / (w_scale * w_scale) +
                    law_merit(trial.law_squares, f));
    }

    void
    newton_step(Iterate &x, Iterate &full)
    {
      // w_free - C base from evaluate()'s w_free - C g: base and g differ at
      // the stick nodes only (the friction force, an unknown of the step).
      response = x.response;
      difference.clear();
      differing.clear();
      difference.resize(x.g.size());
      for (const unsigned int j : x.active)
        if ((x.base[j] - x.g[j]).norm_square() > 0)
          {
            difference[j] = x.base[j] - x.g[j];
            differing.push_back(j);
          }
      solver.subtract_compliance(difference, differing, response);
      r.resize(x.active.size());
      for (unsigned int a = 0; a < x.active.size(); ++a)
        r[a] = response[x.active[a]] - x.w[x.active[a]];
      full.lambda = x.lambda;
      // Far from the solution (residual above 1e-3) the step's round-off
      // does not matter: the next residual is of the order of the square
      // of this one.
      solver.dense_step(
        x, r, dw, full.lambda, new_forces, residual(x) >= far_above);
      solver.compliance_response(solver.w_free_nodes,
                                 new_forces,
                                 x.active,
                                 full.w);
    }

    /** Drop the coupled linearization's weakening limits (newton_driver.h). */
    /** The weakening limit acted at a node of @p x (newton_driver.h). */
    bool
    safeguarded(const Iterate &x) const
    {
      for (const auto &l : x.lin)
        if (l.friction.limited)
          return true;
      return false;
    }

    void
    combine(const Iterate &x,
            const Iterate &full,
            const double   alpha,
            Iterate       &trial) const
    {
      const unsigned int n = x.w.size();
      trial.w.resize(n);
      trial.lambda.resize(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          trial.w[i] = x.w[i] + alpha * (full.w[i] - x.w[i]);
          trial.lambda[i] =
            x.lambda[i] + alpha * (full.lambda[i] - x.lambda[i]);
        }
    }

  private:
    static constexpr double     far_above = 1e-3;
    CondensedNewton<dim>       &solver;
    const double                w_scale;
    Result                     &result;
    std::vector<Tensor<1, dim>> response, r, dw, new_forces, difference;
    std::vector<unsigned int>   differing;
  };


  template <int dim>
  typename CondensedNewton<dim>::Result
  CondensedNewton<dim>::solve(const Vector_t                    &rhs,
                              const std::vector<Tensor<1, dim>> &u_old,
                              const std::vector<Tensor<1, dim>> &w_old,
                              const FrictionCoefficients        &mu,
                              std::vector<Tensor<1, dim>>       &lambda,
                              Vector_t                          &w)
  {
    return solve(rhs, u_old, w_old, mu, lambda, w, false);
  }


  template <int dim>
  typename CondensedNewton<dim>::Result
  CondensedNewton<dim>::solve_provisional(
    const Vector_t                    &rhs,
    const std::vector<Tensor<1, dim>> &u_old,
    const std::vector<Tensor<1, dim>> &w_old,
    const FrictionCoefficients        &mu,
    std::vector<Tensor<1, dim>>       &lambda,
    Vector_t                          &w,
    const double                       velocity_accuracy)
  {
    return solve(rhs, u_old, w_old, mu, lambda, w, true, velocity_accuracy);
  }


  template <int dim>
  std::vector<Tensor<1, dim>>
  CondensedNewton<dim>::provisional_velocities() const
  {
    Assert(pending, ExcInternalError());
    return gathered.owned_part(pending->it.response);
  }


  template <int dim>
  void
  CondensedNewton<dim>::apply_k0_compliance(
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
          if (spring_stiffness[j] > 0)
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
            W(a, a) += 1. / spring_stiffness[j];
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
  CondensedNewton<dim>::coupled_limits(Result &result)
  {
    if (limits_scheme == prepared_scheme && !weakening_limits.empty())
      return weakening_limits;
    const auto         &all = gathered.all_nodes();
    std::vector<double> local(all.size(), 0.), stiffness(all.size());
    for (unsigned int i = 0; i < all.size(); ++i)
      if (owned_index[i] >= 0 && all[i].unconstrained)
        local[i] = WeakeningLimit::tangential_stiffness(
          all[i], problem.bulk.newton_matrix());
    Utilities::MPI::max(local, problem.discretization.comm, stiffness);
    // Every process holds every node: the same sample everywhere.
    // The sample's compliance under K0, as the assembled solver sees it.
    weakening_limits = WeakeningLimit::limits(
      all,
      stiffness,
      [&](const int j) {
        const std::vector<unsigned int> node = {static_cast<unsigned int>(j)};
        Tensor<2, dim>                  C;
        std::vector<Tensor<1, dim>>     v;
        for (unsigned int c = 0; c < dim; ++c)
          {
            std::vector<Tensor<1, dim>> e(1);
            e[0][c] = 1;
            apply_k0_compliance(node, e, v, result);
            for (unsigned int q = 0; q < dim; ++q)
              C[q][c] = v[0][q];
          }
        return WeakeningLimit::tangential_compliance(all[j], C);
      },
      MPI_COMM_SELF);
    limits_scheme = prepared_scheme;
    return weakening_limits;
  }


  template <int dim>
  double
  CondensedNewton<dim>::compliance_radius(
    const std::vector<Tensor<2, dim>> &roots)
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
      return 0;
    Result                      result;
    const unsigned int          n = nodes.size();
    std::vector<Tensor<1, dim>> z(n), v;
    const auto apply = [&](const std::vector<double> &x,
                           std::vector<double>       &y) {
      for (unsigned int b = 0; b < n; ++b)
        z[b] = S[b] * nodal_entries<dim>(x, b);
      apply_k0_compliance(nodes, z, v, result);
      for (unsigned int a = 0; a < n; ++a)
        set_nodal_entries<dim>(S[a] * v[a], a, y);
    };
    std::vector<double> start(dim * n);
    for (unsigned int a = 0; a < n; ++a)
      set_nodal_entries<dim>(S[a] * lanczos_start(all[nodes[a]]), a, start);
    return largest_eigenvalue(apply, start, [](const double v) { return v; });
  }


  template <int dim>
  typename CondensedNewton<dim>::Result
  CondensedNewton<dim>::finalize(Vector_t                    &w,
                                 std::vector<Tensor<1, dim>> &lambda,
                                 Vector_t                    *previous)
  {
    Assert(previous == nullptr || previous_pass, ExcInternalError());
    Result result;
    if (!pending)
      return result;
    const Pending p = std::move(*pending);
    pending.reset();
    u_old_all = gathered.gather(p.u_old);
    w_old_all = gathered.gather(p.w_old);
    mu_all    = gather_coefficients(p.mu);
    if (!p.loose)
      polish(p.it, p.u_old, p.w_old, p.mu, lambda, w, result, previous);
    else
      {
        // The pass stopped early: phase 1 on to the Newton tolerance first
        // (on Gamma_3, cheap), so that phase 2 starts where it would have.
        Iterate it = p.it;
        boundary_newton(it, p.w_scale, 0., result);
        polish(it, p.u_old, p.w_old, p.mu, lambda, w, result, previous);
      }
    return result;
  }


  template <int dim>
  typename CondensedNewton<dim>::Result
  CondensedNewton<dim>::solve(const Vector_t                    &rhs,
                              const std::vector<Tensor<1, dim>> &u_old,
                              const std::vector<Tensor<1, dim>> &w_old,
                              const FrictionCoefficients        &mu,
                              std::vector<Tensor<1, dim>>       &lambda,
                              Vector_t                          &w,
                              const bool                         provisional,
                              const double velocity_accuracy)
  {
    Result result;
    prepare(result);
    const unsigned int n = gathered.all_nodes().size();

    // The free response: the body without the foundation. The passes of a
    // convexification loop share it (same b, same K0').
    bool same_rhs = free_response_valid && cached_rhs.size() == rhs.size();
    if (same_rhs)
      {
        scratch = rhs;
        scratch -= cached_rhs;
        same_rhs = (scratch.linfty_norm() == 0);
      }
    if (!same_rhs)
      {
        solve_bulk(rhs, free_response, result);
        cached_rhs          = rhs;
        w_free_nodes        = gather_values(free_response);
        free_response_valid = true;
        // A new step: the reduced factorization starts afresh, so a step
        // is solved the same whatever came before it (a resumed run
        // repeats an uninterrupted one to the byte).
        reduced = Reduced();
      }
    // A pending provisional pass of the same step (same b) is the loop's
    // last iterate; one of another step is stale (a failed step).
    previous_pass.reset();
    std::vector<Tensor<1, dim>> previous_velocities;
    if (pending && same_rhs && provisional)
      {
        previous_velocities = std::move(pending->it.response);
        previous_pass.emplace(std::move(pending->it.g),
                              std::move(pending->it.active));
      }
    pending.reset();
    if (n == 0)
      {
        w = free_response;
        return result;
      }
    u_old_all = gathered.gather(u_old);
    w_old_all = gathered.gather(w_old);
    // The coupled linearization's limits (WeakeningLimit): at every node
    // for phase 1, at the owned ones for phase 2.
    FrictionCoefficients owned_mu = mu;
    mu_all                        = gather_coefficients(mu);
    if (mu.coupled())
      {
        mu_all.weakening_limit   = coupled_limits(result);
        owned_mu.weakening_limit = gathered.owned_part(mu_all.weakening_limit);
      }

    // Phase 1, on Gamma_3 only: w_i = w_free,i - sum_j C_ij f_j, from the
    // initial guess given (w_{n-1}, or the last convexification pass). No
    // solve with K0 but for new columns of C. It finds the active sets; where
    // K0 is nearly singular (a body held only by the foundation) the
    // cancellation in w_free - C f limits its accuracy, and phase 2 polishes.
    Iterate it;
    if (previous_pass)
      it.w = std::move(previous_velocities);
    else
      it.w = gather_values(w);
    it.lambda      = gathered.gather(lambda);
    double w_scale = 1e-300;
    for (unsigned int i = 0; i < n; ++i)
      w_scale = std::max({w_scale, w_free_nodes[i].norm(), it.w[i].norm()});
    // Phase 1's residual is relative to w_scale (a velocity).
    const double loose_tolerance =
      provisional ? velocity_accuracy / w_scale : 0.;
    boundary_newton(it, w_scale, loose_tolerance, result);

    // Provisional: the nodal velocities w_free - C g of the iterate (at the
    // nodes, what w = K0'^{-1} (b - sum_i P_i^T g_i) would be), no solve
    // and no phase 2 (the loop's next pass, or finalize(), follows).
    if (provisional)
      {
        lambda = gathered.owned_part(it.lambda);
        pending.emplace(
          Pending{u_old,
                  w_old,
                  owned_mu,
                  std::move(it),
                  w_scale,
                  loose_tolerance > problem.parameters.newton_tolerance});
        result.provisional = true;
        return result;
      }
    polish(it, u_old, w_old, owned_mu, lambda, w, result);
    return result;
  }


  template <int dim>
  void
  CondensedNewton<dim>::boundary_newton(Iterate     &it,
                                        const double w_scale,
                                        const double tolerance,
                                        Result      &result)
  {
    TimerSection    t(problem.timer, "Contact: boundary Newton");
    BoundaryProblem boundary_problem(*this, w_scale, result);
    NewtonPolicy    policy; // non-monotone, stagnation factor 0.1
    policy.name      = "on Gamma_3";
    policy.tolerance = tolerance;
    // Phase 1 stops early at stagnation (sqrt(tol)): phase 2 polishes.
    globalized_newton(boundary_problem,
                      it,
                      policy,
                      problem.parameters,
                      problem.details,
                      result);
  }


  template <int dim>
  void
  CondensedNewton<dim>::polish(const Iterate                     &it,
                               const std::vector<Tensor<1, dim>> &u_old,
                               const std::vector<Tensor<1, dim>> &w_old,
                               const FrictionCoefficients        &mu,
                               std::vector<Tensor<1, dim>>       &lambda,
                               Vector_t                          &w,
                               Result                            &result,
                               Vector_t                          *previous)
  {
    const Vector_t &rhs = cached_rhs;
    // The forces into the bulk: w = K0'^{-1} (b - sum_i P_i^T g_i), i.e.
    // K0 w = b - sum_i P_i^T f_i where w_i is the iterate of phase 1. (A
    // solve: w_free - sum_j X_j g_j from the stored columns costs as much
    // and leaves a bulk residual up to 1e2 times larger, which the first
    // Newton step of phase 2 would have to solve for.)
    right_hand_side = rhs;
    add_nodal_forces(it.g, -1., right_hand_side);
    // The earlier provisional pass's velocity alike (finalize()): a sum of
    // the stored whole columns, or in one block solve with w.
    if (previous != nullptr && apply_full_columns(previous_pass->first,
                                                  previous_pass->second,
                                                  scratch))
      {
        *previous = free_response;
        *previous -= scratch;
        previous = nullptr;
      }
    if (previous != nullptr)
      {
        scratch = rhs;
        add_nodal_forces(previous_pass->first, -1., scratch);
        solve_bulk({&right_hand_side, &scratch}, {&w, previous}, result);
      }
    else
      solve_bulk(right_hand_side, w, result);

    // Phase 2: Newton on the residual of the whole system,
    //   R = K0 w - b + sum_i P_i^T f_i(w),
    // each step solved by the same condensation (newton_step()). Where
    // phase 1 converged this only checks the residual.
    TimerSection      t(problem.timer, "Contact: refinement");
    SystemNewton<dim> system(problem, rhs, u_old, w_old, mu, *this, result);
    // The stick condition in velocity units too, relative to |w|; where the
    // body is at rest |w| is itself round-off, which is of order eps
    // |w_free| (w = w_free - C g cancels): 1e-6 |w_free| keeps the test
    // above it.
    system.velocity_scale =
      std::max({w.linfty_norm(), 1e-6 * free_response.linfty_norm(), 1e-300});
    SystemIterate<dim> x;
    x.w      = w;
    x.lambda = gathered.owned_part(it.lambda);
    NewtonPolicy policy;
    policy.monotone          = true;
    policy.stagnation_factor = 0.5;
    policy.name              = "whole system";
    globalized_newton(
      system, x, policy, problem.parameters, problem.details, result);
    w      = x.w;
    lambda = x.lambda;
  }


  template <int dim>
  void
  CondensedNewton<dim>::newton_step(const SystemNewton<dim> & /*system*/,
                                    const SystemIterate<dim> &x,
                                    SystemIterate<dim>       &full,
                                    Result                   &result)
  {
    // The linearization at every node (the dense system couples them).
    Iterate it;
    it.w      = gather_values(x.w);
    it.lambda = gathered.gather(x.lambda);
    linearize(it);

    // z = K0'^{-1} v, v = -(K0 w - b + sum_i P_i^T base_i); the step is
    // dw = z - K0'^{-1} sum_i P_i^T (g_i^new - base_i) (g form).
    residual = x.residual;
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return x.forces[i]; }, -1., residual);
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return x.base[i]; }, 1., residual);
    residual *= -1.;
    compute_columns(it.active, result);

    // The rest of the step, K0'^{-1} sum_i P_i^T (g_i^new - base_i), is a
    // sum of the stored whole columns if they are kept, else a solve. (Tried:
    // z from C times the nodal part of v alone, the rest of v, bulk
    // round-off of about 1e-11 |b|, left out: its response at the nodes is
    // some 500 times larger and left |w_tau| = 7.9e-8 at a stick node of
    // the critical-speed stress scene, 2.6 times the law's tolerance.)
    solve_bulk(residual, solution, result);
    const auto                  z = gather_values(solution);
    std::vector<Tensor<1, dim>> r(it.active.size()), dw, new_forces;
    for (unsigned int a = 0; a < it.active.size(); ++a)
      r[a] = z[it.active[a]];
    std::vector<Tensor<1, dim>> lambda_full = it.lambda;
    dense_step(it, r, dw, lambda_full, new_forces);
    for (const unsigned int j : it.active)
      new_forces[j] -= it.base[j];
    if (!apply_full_columns(new_forces, it.active, increment))
      {
        right_hand_side = 0;
        add_nodal_forces(new_forces, 1., right_hand_side);
        solve_bulk(right_hand_side, increment, result);
      }
    solution -= increment; // the full step
    full.w = x.w;
    full.w += solution;
    full.lambda = gathered.owned_part(lambda_full);
  }


  template class CondensedNewton<2>;
  template class CondensedNewton<3>;
} // namespace DynamicContact
