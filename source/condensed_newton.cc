#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/condensed_newton.h>

#include <algorithm>
#include <cmath>
#include <optional>

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
    const auto &all = problem.boundary.all_nodes();
    columns.assign(all.size(), {});
    owned_index.assign(all.size(), -1);
    const auto &global = problem.boundary.global_indices();
    for (unsigned int i = 0; i < global.size(); ++i)
      owned_index[global[i]] = i;
    prepared_k          = 0;
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
    const auto &all = problem.boundary.all_nodes();
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
    const double k = problem.bulk.time_step();
    if (k == prepared_k)
      return;
    // K0' = K0 + S.
    const Matrix_t &K0 = problem.bulk.newton_matrix();
    regularized.copy_from(K0);
    {
      const auto &        all = problem.boundary.all_nodes();
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
      TimerOutput::Scope t(problem.timer, "Bulk: factorization of K0");
      std::vector<std::vector<bool>> constant_modes;
      if (problem.parameters.linear_solver ==
          Parameters::Solver::LinearSolver::iterative)
        DoFTools::extract_constant_modes(problem.discretization.dof_handler,
                                         ComponentMask(),
                                         constant_modes);
      bulk_solver.initialize(regularized,
                             constant_modes,
                             problem.discretization.fe.degree > 1);
    }
    ++result.factorizations;
    prepared_k          = k;
    free_response_valid = false;
    // C depends on K0: forget it.
    for (auto &c : columns)
      c.clear();
  }


  template <int dim>
  void
  CondensedNewton<dim>::solve_bulk(const Vector_t &b,
                                   Vector_t &      x,
                                   Result &        result)
  {
    TimerOutput::Scope t(problem.timer, "Bulk: solves with K0");
    bulk_solver.solve(b, x);
    problem.discretization.constraints.set_zero(x);
    ++result.bulk_solves;
  }


  template <int dim>
  void
  CondensedNewton<dim>::compute_columns(const std::vector<unsigned int> &nodes,
                                        Result &                         result)
  {
    std::vector<unsigned int> missing;
    for (const unsigned int j : nodes)
      if (columns[j].empty())
        missing.push_back(j);
    if (missing.empty())
      return;
    TimerOutput::Scope t(problem.timer, "Bulk: compliance columns");

    // One right-hand side per missing node and direction: a unit force in
    // direction c at node j, through the node's constraints (P_j^T e_c).
    const auto &                           all = problem.boundary.all_nodes();
    std::vector<BulkSolver::SparseColumn> rhs;
    for (const unsigned int j : missing)
      for (unsigned int c = 0; c < dim; ++c)
        {
          BulkSolver::SparseColumn column;
          for (unsigned int r = 0; r < dim; ++r)
            if (all[j].constraint_map[c][r] != 0)
              column.emplace_back(all[j].dofs[r], all[j].constraint_map[c][r]);
          rhs.push_back(column);
        }
    // The responses at the owned nodes, then at every node.
    const auto &                         owned  = problem.boundary.nodes();
    const auto &                         global = problem.boundary.global_indices();
    std::vector<types::global_dof_index> rows;
    for (const auto &node : owned)
      for (unsigned int r = 0; r < dim; ++r)
        rows.push_back(node.dofs[r]);
    std::vector<std::vector<double>> values;
    bulk_solver.solve_columns(rhs, rows, values);
    result.bulk_solves += rhs.size();

    std::vector<double> packed;
    for (unsigned int m = 0; m < missing.size(); ++m)
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
    for (const unsigned int j : missing)
      columns[j].assign(all.size(), Tensor<2, dim>());
    for (const auto &part :
         Utilities::MPI::all_gather(problem.discretization.comm, packed))
      for (std::size_t p = 0; p < part.size(); p += 3 + dim)
        {
          const unsigned int j = missing[static_cast<unsigned int>(part[p])];
          const unsigned int c = static_cast<unsigned int>(part[p + 1]);
          const unsigned int i = static_cast<unsigned int>(part[p + 2]);
          for (unsigned int r = 0; r < dim; ++r)
            columns[j][i][r][c] = part[p + 3 + r];
        }
  }


  template <int dim>
  void
  CondensedNewton<dim>::compliance_response(
    const std::vector<Tensor<1, dim>> &w_free,
    const std::vector<Tensor<1, dim>> &forces,
    const std::vector<unsigned int> &  with_force,
    std::vector<Tensor<1, dim>> &      w) const
  {
    w = w_free;
    for (const unsigned int j : with_force)
      for (unsigned int i = 0; i < w.size(); ++i)
        w[i] -= columns[j][i] * forces[j];
  }


  template <int dim>
  void
  CondensedNewton<dim>::linearize(const std::vector<Tensor<1, dim>> &u_old,
                                  const std::vector<Tensor<1, dim>> &w_old,
                                  const std::vector<double> &         mu,
                                  const std::vector<Tensor<1, dim>> &lambda,
                                  const std::vector<Tensor<1, dim>> &w_nodes,
                                  Iterate &                           it) const
  {
    const auto &       nodes = problem.boundary.all_nodes();
    const unsigned int n     = nodes.size();
    const double       k     = problem.bulk.time_step();
    const double       theta = problem.theta;
    it.w_old = w_old;
    it.lin.resize(n);
    it.forces.resize(n);
    it.base_true.resize(n);
    it.g.resize(n);
    it.base.resize(n);
    it.signature.resize(n);
    it.active.clear();
    it.f_scale      = 1e-300;
    it.law_residual = 0;
    it.law_squares  = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const auto &l = it.lin[i] = linearize_node(problem.foundation,
                                                   nodes[i],
                                                   u_old[i],
                                                   w_old[i],
                                                   w_nodes[i],
                                                   k,
                                                   theta,
                                                   problem.friction,
                                                   lambda[i],
                                                   problem.friction ? mu[i] :
                                                                      0.,
                                                   problem.c_t * k);
        const Tensor<1, dim> normal_force =
          l.normal.pressure * nodes[i].weight * nodes[i].normal;
        // The force at the iterate (normal law at w, the friction force as it
        // stands) and the part of the linearized force that does not depend
        // on the unknowns of the Newton step.
        it.forces[i]    = normal_force + lambda[i];
        it.base_true[i] = normal_force;
        if (l.friction.state == ContactState::slip)
          it.base_true[i] += l.friction.value;
        // Condensation with K0' = K0 + S sees the forces minus the springs'.
        // S_i = s_i P_i, and P_i w_i = w_i (P_i diagonal, 0 or 1).
        const double s = spring_stiffness[i];
        it.g[i]         = it.forces[i] - s * w_nodes[i];
        it.base[i]      = it.base_true[i] - s * w_nodes[i];
        if (s > 0)
          it.lin[i].block -= s * nodes[i].constraint_map;
        it.signature[i] = l.normal.set_signature() +
                          16 * static_cast<unsigned int>(l.friction.state);
        it.f_scale = std::max(it.f_scale, it.forces[i].norm());
        if (problem.friction)
          {
            const double law =
              (lambda[i] -
               projected_friction_force(nodes[i],
                                        l.friction.threshold,
                                        theta * w_nodes[i] +
                                          (1 - theta) * w_old[i],
                                        lambda[i],
                                        problem.c_t * k))
                .norm();
            it.law_residual = std::max(it.law_residual, law);
            it.law_squares += law * law;
          }
        if (l.active() || it.forces[i].norm_square() > 0 || s > 0)
          it.active.push_back(i);
      }
  }


  template <int dim>
  void
  CondensedNewton<dim>::dense_step(const Iterate &                     it,
                                   const std::vector<Tensor<1, dim>> &r,
                                   std::vector<Tensor<1, dim>> &       dw,
                                   std::vector<Tensor<1, dim>> &       lambda,
                                   std::vector<Tensor<1, dim>> &new_forces) const
  {
    // The Newton system on the active nodes: unknowns dw_i (dim each) and, at
    // stick nodes, the tangential force (dim-1 each, scaled by the node's
    // compliance), for
    //   dw_i + sum_j C_ij (block_j dw_j + T_j l_j) = r_i,
    //   t_s . (w_i + dw_i) = 0 at stick nodes.
    const auto &              nodes    = problem.boundary.all_nodes();
    const auto &              active   = it.active;
    const unsigned int        n_active = active.size();
    std::vector<unsigned int> stick_offset(n_active, 0);
    std::vector<double>       stick_scale(n_active, 0);
    unsigned int              size = dim * n_active;
    for (unsigned int a = 0; a < n_active; ++a)
      if (it.lin[active[a]].friction.state == ContactState::stick)
        {
          const unsigned int j = active[a];
          stick_offset[a]      = size;
          size += dim - 1;
          double c = 0;
          for (const auto &t : nodes[j].tangents)
            c += t * (columns[j][j] * t);
          stick_scale[a] = c > 0 ? (dim - 1) / c : 1.;
        }

    dw.assign(n_active, Tensor<1, dim>());
    new_forces.assign(nodes.size(), Tensor<1, dim>());
    for (auto &l : lambda)
      l = Tensor<1, dim>();
    if (size == 0)
      return;

    LAPACKFullMatrix<double> matrix(size, size);
    Vector<double>           vector(size);
    for (unsigned int a = 0; a < n_active; ++a)
      {
        const unsigned int i = active[a];
        for (unsigned int b = 0; b < n_active; ++b)
          {
            const unsigned int    j  = active[b];
            const Tensor<2, dim> &C  = columns[j][i];
            const Tensor<2, dim>  CB = C * it.lin[j].block;
            for (unsigned int p = 0; p < dim; ++p)
              for (unsigned int q = 0; q < dim; ++q)
                matrix(dim * a + p, dim * b + q) = CB[p][q];
            if (stick_offset[b] > 0)
              for (unsigned int s = 0; s < dim - 1; ++s)
                {
                  const Tensor<1, dim> Ct = C * nodes[j].tangents[s];
                  for (unsigned int p = 0; p < dim; ++p)
                    matrix(dim * a + p, stick_offset[b] + s) =
                      Ct[p] / stick_scale[b];
                }
          }
        for (unsigned int p = 0; p < dim; ++p)
          {
            matrix(dim * a + p, dim * a + p) += 1.;
            vector(dim * a + p) = r[a][p];
          }
        if (stick_offset[a] > 0)
          for (unsigned int s = 0; s < dim - 1; ++s)
            {
              for (unsigned int p = 0; p < dim; ++p)
                matrix(stick_offset[a] + s, dim * a + p) =
                  nodes[i].tangents[s][p];
              // t_s . w_e = 0 at the new iterate: t_s . dw = -(t_s . w_e)/theta.
              vector(stick_offset[a] + s) =
                -(nodes[i].tangents[s] *
                  (problem.theta * it.w[i] + (1 - problem.theta) * it.w_old[i])) /
                problem.theta;
            }
      }
    matrix.compute_lu_factorization();
    matrix.solve(vector);

    for (unsigned int a = 0; a < n_active; ++a)
      {
        const unsigned int j = active[a];
        for (unsigned int p = 0; p < dim; ++p)
          dw[a][p] = vector(dim * a + p);
        const auto &l = it.lin[j];
        if (l.friction.state == ContactState::slip)
          lambda[j] = l.friction.value + l.friction.jacobian * dw[a];
        else if (l.friction.state == ContactState::stick)
          for (unsigned int s = 0; s < dim - 1; ++s)
            lambda[j] += (vector(stick_offset[a] + s) / stick_scale[a]) *
                         nodes[j].tangents[s];
        // base_j + block_j dw + T_j l_j, with the springs' part (g form).
        new_forces[j] = it.base[j] + l.block * dw[a];
        if (l.friction.state == ContactState::stick)
          new_forces[j] += lambda[j];
      }
  }


  template <int dim>
  void
  CondensedNewton<dim>::add_nodal_forces(const std::vector<Tensor<1, dim>> &f,
                                         const double      factor,
                                         Vector_t &        v) const
  {
    const auto &global = problem.boundary.global_indices();
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return f[global[i]]; }, factor, v);
  }


  template <int dim>
  typename CondensedNewton<dim>::Result
  CondensedNewton<dim>::solve(const Vector_t &                    rhs,
                              const std::vector<Tensor<1, dim>> &u_old,
                              const std::vector<Tensor<1, dim>> &w_old,
                              const std::vector<double> &         mu,
                              std::vector<Tensor<1, dim>> &       lambda,
                              Vector_t &                          w)
  {
    Result result;
    prepare(result);
    const unsigned int n   = problem.boundary.all_nodes().size();
    const double       tol = problem.parameters.newton_tolerance;

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
        w_free_nodes        = problem.boundary.gather_values(free_response);
        free_response_valid = true;
      }
    if (n == 0)
      {
        w = free_response;
        return result;
      }
    const std::vector<Tensor<1, dim>> &w_free = w_free_nodes;

    // Phase 1, on Gamma_3 only: w_i = w_free,i - sum_j C_ij f_j, from the
    // initial guess given (w_{n-1}, or the last convexification pass). No
    // solve with K0 but for new columns of C. It finds the active sets; where
    // K0 is nearly singular (a body held only by the foundation) the
    // cancellation in w_free - C f limits its accuracy, and phase 2 polishes.
    Iterate it, trial;
    it.w = problem.boundary.gather_values(w);
    double w_scale = 1e-300;
    for (unsigned int i = 0; i < n; ++i)
      w_scale = std::max({w_scale, w_free[i].norm(), it.w[i].norm()});
    std::vector<Tensor<1, dim>> dw, new_forces, response, r, w_full,
      lambda_full;

    // The residual of an iterate: its largest entries (relative, for the
    // stopping test) and the merit function (1/2 the sum of squares, with
    // the scales of the current iterate) that the line search decreases.
    struct Measure
    {
      double residual = 0, equilibrium = 0, equilibrium_squares = 0;
    };
    auto evaluate = [&](const std::vector<Tensor<1, dim>> &w_nodes,
                        const std::vector<Tensor<1, dim>> &lam,
                        Iterate &                          state) {
      linearize(u_old, w_old, mu, lam, w_nodes, state);
      state.w = w_nodes;
      compute_columns(state.active, result);
      compliance_response(w_free, state.g, state.active, response);
      Measure m;
      for (unsigned int i = 0; i < n; ++i)
        {
          const double e = (w_nodes[i] - response[i]).norm();
          m.equilibrium  = std::max(m.equilibrium, e);
          m.equilibrium_squares += e * e;
        }
      m.residual =
        std::max(m.equilibrium / w_scale, state.law_residual / state.f_scale);
      return m;
    };
    auto merit = [&](const Measure &m, const Iterate &state, const double f) {
      return 0.5 * (m.equilibrium_squares / (w_scale * w_scale) +
                    state.law_squares / (f * f));
    };

    {
      TimerOutput::Scope t(problem.timer, "Contact: boundary Newton");
      Measure                                current = evaluate(it.w, lambda, it);
      std::vector<std::vector<unsigned int>> history; // active sets seen
      std::vector<double>                    merits;
      bool                                   monotone = false;
      for (unsigned int iteration = 0;; ++iteration)
        {
          problem.details << "    Newton " << result.iterations
                          << " (on Gamma_3): residual " << current.residual
                          << " (equilibrium " << current.equilibrium / w_scale
                          << ", law " << it.law_residual / it.f_scale
                          << "), active nodes " << it.active.size()
                          << std::endl;
          // Stagnation near round-off (the cancellation in w_free - C f of
          // an ill-conditioned K0): phase 2 polishes.
          const bool stagnated = iteration > 0 && !history.empty() &&
                                 it.signature == history.back() &&
                                 current.residual > 0.1 * result.residual &&
                                 current.residual < std::sqrt(tol);
          if (current.residual <= tol || stagnated)
            break;
          result.residual = current.residual;
          check_newton_cap(result.iterations, result.residual, problem.parameters);

          // Active-set cycling: a return to sets seen before, with other
          // sets in between (keeping the last sets, as a damped step does,
          // is no cycle). The line search then damps the step (the remedy).
          const bool cycling =
            history.size() >= 2 && it.signature != history.back() &&
            std::find(history.begin(), history.end() - 1, it.signature) !=
              history.end() - 1;
          result.cycles += cycling;
          monotone = monotone || cycling;
          history.push_back(it.signature);
          const double f_scale     = it.f_scale;
          const double merit_now   = merit(current, it, f_scale);
          merits.push_back(merit_now);

          // The full semismooth Newton step.
          compliance_response(w_free, it.base, it.active, response);
          r.resize(it.active.size());
          for (unsigned int a = 0; a < it.active.size(); ++a)
            r[a] = response[it.active[a]] - it.w[it.active[a]];
          lambda_full = lambda;
          dense_step(it, r, dw, lambda_full, new_forces);
          compliance_response(w_free, new_forces, it.active, w_full);

          // Accept it unless the sets cycle, or, after the first iterations
          // (where set changes may raise the merit while Newton converges),
          // the merit rises above that of the last five iterates
          // (non-monotone), or, once a cycle was seen, above the current one
          // (monotone from then on); otherwise backtrack along it (Armijo). Measured on
          // the stress scenes: it costs a few iterations where plain Newton
          // converges and completes the scenes where the sets cycle.
          Measure      trial_measure = evaluate(w_full, lambda_full, trial);
          const double reference     = *std::max_element(
            merits.end() - std::min<std::size_t>(merits.size(), 5),
            merits.end());
          const double merit_full = merit(trial_measure, trial, f_scale);
          if (problem.parameters.line_search &&
              (cycling || (monotone && merit_full > merit_now) ||
               (iteration >= 4 && merit_full > reference)))
            {
              std::vector<Tensor<1, dim>> w_trial(n), lambda_trial(n);
              for (double alpha = 0.5;; alpha *= 0.5)
                {
                  for (unsigned int i = 0; i < n; ++i)
                    {
                      w_trial[i] = it.w[i] + alpha * (w_full[i] - it.w[i]);
                      lambda_trial[i] =
                        lambda[i] + alpha * (lambda_full[i] - lambda[i]);
                    }
                  trial_measure = evaluate(w_trial, lambda_trial, trial);
                  ++result.line_search_steps;
                  if (merit(trial_measure, trial, f_scale) <=
                        (1 - 1e-4 * alpha) * merit_now ||
                      alpha < 1. / 64)
                    break;
                }
              lambda_full = lambda_trial;
            }
          std::swap(it, trial);
          lambda  = lambda_full;
          current = trial_measure;
          ++result.iterations;
        }
    }

    // The forces into the bulk: w = K0'^{-1} (b - sum_i P_i^T g_i), i.e.
    // K0 w = b - sum_i P_i^T f_i where w_i is the iterate of phase 1.
    right_hand_side = rhs;
    add_nodal_forces(it.g, -1., right_hand_side);
    solve_bulk(right_hand_side, w, result);

    // Phase 2: Newton on the residual of the whole system,
    //   R = K0 w - b + sum_i P_i^T f_i(w),
    // each step solved by the same condensation (two solves with K0). Where
    // phase 1 converged this only checks the residual.
    auto full_residual = [&](const Vector_t &                   v,
                             const std::vector<Tensor<1, dim>> &lam,
                             Iterate &                          state) {
      state.w = problem.boundary.gather_values(v);
      linearize(u_old, w_old, mu, lam, state.w, state);
      problem.bulk.newton_matrix().vmult(residual, v);
      const double scale =
        std::max({rhs.l2_norm(), residual.l2_norm(), 1e-300});
      residual -= rhs;
      add_nodal_forces(state.forces, 1., residual);
      return std::max(residual.l2_norm() / scale,
                      state.law_residual / state.f_scale);
    };
    double                    previous_residual = 0;
    std::vector<unsigned int> previous_signature;
    Vector_t                  w_start;
    // The residual of (w, lambda) when the line search already evaluated it
    // (into trial, swapped into it, and into the vector residual).
    std::optional<double> evaluated;
    for (unsigned int refinement = 0;; ++refinement)
      {
        TimerOutput::Scope t(problem.timer, "Contact: refinement");
        result.residual =
          evaluated ? *evaluated : full_residual(w, lambda, it);
        evaluated.reset();
        problem.details << "    Newton " << result.iterations
                        << " (whole system): residual " << result.residual
                        << ", active nodes " << it.active.size() << std::endl;
        // Stagnation at the attainable accuracy: with a very stiff
        // foundation (c_nu m_i >> the bulk stiffness) round-off in u_nu,
        // amplified by c_nu, bounds the relative residual above tol. Accepted
        // when the sets no longer change, a full step gained less than a
        // factor 2, and the residual is below sqrt(tol).
        const bool stagnated = refinement > 0 &&
                               it.signature == previous_signature &&
                               result.residual > 0.5 * previous_residual &&
                               result.residual < std::sqrt(tol);
        if (result.residual <= tol || stagnated)
          break;
        check_newton_cap(result.iterations, result.residual, problem.parameters);
        previous_residual  = result.residual;
        previous_signature = it.signature;

        // z = -K0'^{-1} (K0 w - b + sum_i P_i^T base_i); the step is
        // dw = z - K0'^{-1} sum_i P_i^T (g_i^new - base_i) (g form).
        add_nodal_forces(it.forces, -1., residual);
        add_nodal_forces(it.base_true, 1., residual);
        residual *= -1.;
        solve_bulk(residual, solution, result);
        const auto z = problem.boundary.gather_values(solution);
        compute_columns(it.active, result);
        r.resize(it.active.size());
        for (unsigned int a = 0; a < it.active.size(); ++a)
          r[a] = z[it.active[a]];
        lambda_full = lambda;
        dense_step(it, r, dw, lambda_full, new_forces);
        for (const unsigned int j : it.active)
          new_forces[j] -= it.base[j];
        right_hand_side = 0;
        add_nodal_forces(new_forces, 1., right_hand_side);
        solve_bulk(right_hand_side, increment, result);
        solution -= increment; // the full step

        // Backtrack (Armijo on the residual) if the full step does not
        // reduce it: a stiff foundation makes the linearization at a node
        // out of contact blind to the force it meets once the step pushes
        // it in, and full steps then overshoot back and forth.
        w_start = w;
        w += solution;
        if (problem.parameters.line_search)
          {
            const std::vector<Tensor<1, dim>> lambda_start = lambda;
            for (double alpha = 1;; alpha *= 0.5)
              {
                for (unsigned int i = 0; i < n; ++i)
                  lambda[i] =
                    lambda_start[i] + alpha * (lambda_full[i] - lambda_start[i]);
                const double trial_residual = full_residual(w, lambda, trial);
                if (trial_residual <= (1 - 1e-4 * alpha) * result.residual ||
                    alpha < 1. / 64)
                  {
                    std::swap(it, trial);
                    evaluated = trial_residual;
                    break;
                  }
                ++result.line_search_steps;
                w = w_start;
                w.add(alpha * 0.5, solution);
              }
          }
        else
          lambda = lambda_full;
        ++result.iterations;
      }
    return result;
  }


  template class CondensedNewton<2>;
  template class CondensedNewton<3>;
} // namespace DynamicContact
