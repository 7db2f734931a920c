#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/condensed_newton.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  template <int dim>
  CondensedNewton<dim>::CondensedNewton(const ContactProblem<dim> &problem)
    : problem(problem)
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
    direct.reset();
    amg.reset();
    prepared_k = 0;
    problem.discretization.reinit_owned(solution);
    problem.discretization.reinit_owned(right_hand_side);
  }


  template <int dim>
  unsigned int
  CondensedNewton<dim>::n_columns() const
  {
    return std::count_if(columns.begin(), columns.end(), [](const auto &c) {
      return !c.empty();
    });
  }


  template <int dim>
  void
  CondensedNewton<dim>::prepare(Result &result)
  {
    const double k = problem.bulk.time_step();
    if (k == prepared_k)
      return;
    const Matrix_t &K0 = problem.bulk.newton_matrix();
    if (problem.parameters.linear_solver ==
        Parameters::Solver::LinearSolver::direct)
      {
        TimerOutput::Scope t(problem.timer, "Bulk: factorization of K0");
        direct = std::make_unique<TrilinosWrappers::SolverDirect>(
          direct_control,
          TrilinosWrappers::SolverDirect::AdditionalData(
            false, problem.parameters.direct_solver_package));
        direct->initialize(K0);
      }
    else
      {
        TimerOutput::Scope t(problem.timer, "Bulk: AMG setup for K0");
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = problem.discretization.fe.degree > 1;
        data.smoother_sweeps       = 2;
        data.aggregation_threshold = 0.02;
        DoFTools::extract_constant_modes(problem.discretization.dof_handler,
                                         ComponentMask(),
                                         data.constant_modes);
        amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        amg->initialize(K0, data);
      }
    ++result.factorizations;
    prepared_k = k;
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
    if (direct)
      direct->solve(x, b);
    else
      {
        // K0 = (rho/k) M + A + k B is symmetric positive definite.
        SolverControl control(problem.parameters.max_linear_iterations,
                              problem.parameters.linear_tolerance *
                                b.l2_norm());
        SolverCG<Vector_t> cg(control);
        x = 0;
        cg.solve(problem.bulk.newton_matrix(), x, b, *amg);
      }
    problem.discretization.constraints.set_zero(x);
    ++result.bulk_solves;
  }


  template <int dim>
  void
  CondensedNewton<dim>::compute_column(const unsigned int j, Result &result)
  {
    if (!columns[j].empty())
      return;
    const auto &all = problem.boundary.all_nodes();
    columns[j].assign(all.size(), Tensor<2, dim>());
    for (unsigned int c = 0; c < dim; ++c)
      {
        // A unit force in direction c at node j, through the node's
        // constraints into the condensed right-hand side.
        right_hand_side = 0;
        if (owned_index[j] >= 0)
          {
            const auto &   node = all[j];
            Tensor<1, dim> unit;
            unit[c]                    = 1;
            const Tensor<1, dim> force = transpose(node.constraint_map) * unit;
            for (unsigned int r = 0; r < dim; ++r)
              right_hand_side(node.dofs[r]) = force[r];
          }
        right_hand_side.compress(VectorOperation::insert);
        solve_bulk(right_hand_side, solution, result);
        const auto response = problem.boundary.gather_values(solution);
        for (unsigned int i = 0; i < all.size(); ++i)
          for (unsigned int r = 0; r < dim; ++r)
            columns[j][i][r][c] = response[i][r];
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
  typename CondensedNewton<dim>::Result
  CondensedNewton<dim>::solve(const Vector_t &                    rhs,
                              const std::vector<Tensor<1, dim>> &u_old,
                              const std::vector<double> &         mu,
                              std::vector<Tensor<1, dim>> &       lambda,
                              Vector_t &                          w)
  {
    Result result;
    prepare(result);
    const auto &       nodes = problem.boundary.all_nodes();
    const unsigned int n     = nodes.size();
    const double       k     = problem.bulk.time_step();

    // The free response: the body without the foundation.
    solve_bulk(rhs, solution, result);
    if (n == 0)
      {
        w = solution;
        return result;
      }
    const std::vector<Tensor<1, dim>> w_free =
      problem.boundary.gather_values(solution);

    // The initial iterate: the initial guess given (w_{n-1}, or the last
    // convexification pass), as the assembled Newton starts.
    std::vector<Tensor<1, dim>> w_nodes = problem.boundary.gather_values(w);

    std::vector<NodeLinearization<dim>> lin(n);
    std::vector<Tensor<1, dim>>         forces(n);
    std::vector<unsigned int>           active;
    double w_scale = 1e-300;
    for (unsigned int i = 0; i < n; ++i)
      w_scale = std::max(w_scale, w_free[i].norm());

    for (unsigned int iteration = 0;; ++iteration)
      {
        TimerOutput::Scope t(problem.timer, "Contact: boundary Newton");
        // Linearize every node; the active ones enter the dense system.
        active.clear();
        double f_scale = 1e-300, law_residual = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            lin[i] = linearize_node(problem.foundation,
                                    nodes[i],
                                    u_old[i],
                                    w_nodes[i],
                                    k,
                                    problem.friction,
                                    lambda[i],
                                    problem.friction ? mu[i] : 0.,
                                    problem.c_t * k);
            // The force at the iterate: normal law at w, friction force as
            // it stands.
            forces[i] = lin[i].normal.pressure * nodes[i].weight *
                          nodes[i].normal +
                        lambda[i];
            f_scale = std::max(f_scale, forces[i].norm());
            if (problem.friction)
              law_residual = std::max(
                law_residual,
                (lambda[i] - projected_friction_force(nodes[i],
                                                      lin[i].friction.threshold,
                                                      w_nodes[i],
                                                      lambda[i],
                                                      problem.c_t * k))
                  .norm());
            if (lin[i].active() || forces[i].norm_square() > 0)
              active.push_back(i);
          }
        for (const unsigned int j : active)
          compute_column(j, result);

        // Residual of w_i = w_free,i - sum_j C_ij f_j at every node.
        std::vector<Tensor<1, dim>> response;
        compliance_response(w_free, forces, active, response);
        double equilibrium_residual = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            w_scale = std::max(w_scale, w_nodes[i].norm());
            equilibrium_residual =
              std::max(equilibrium_residual, (w_nodes[i] - response[i]).norm());
          }
        result.residual = std::max(equilibrium_residual / w_scale,
                                   law_residual / f_scale);
        if (result.residual <= problem.parameters.newton_tolerance)
          break;
        AssertThrow(iteration < problem.parameters.max_newton_iterations,
                    ExcMessage(
                      "The semismooth Newton iteration did not converge in "
                      "Solver/Maximum Newton iterations = " +
                      std::to_string(problem.parameters.max_newton_iterations) +
                      " iterations (relative residual " +
                      std::to_string(result.residual) + ")."));

        // The dense Newton system on the active nodes: unknowns dw_i (dim
        // each) and, at stick nodes, the tangential force (dim-1 each,
        // scaled to the compliance of the node).
        const unsigned int        n_active = active.size();
        std::vector<unsigned int> stick_offset(n_active, 0);
        std::vector<double>       stick_scale(n_active, 0);
        unsigned int              size = dim * n_active;
        for (unsigned int a = 0; a < n_active; ++a)
          if (lin[active[a]].friction.state == ContactState::stick)
            {
              const unsigned int j = active[a];
              stick_offset[a]      = size;
              size += dim - 1;
              double c = 0;
              for (const auto &t : nodes[j].tangents)
                c += t * (columns[j][j] * t);
              stick_scale[a] = c > 0 ? (dim - 1) / c : 1.;
            }

        if (size == 0)
          {
            // Nothing in contact: the free response is the next iterate.
            for (auto &l : lambda)
              l = Tensor<1, dim>();
            w_nodes = w_free;
            ++result.iterations;
            continue;
          }
        LAPACKFullMatrix<double> matrix(size, size);
        Vector<double>           vector(size);
        // Linearized forces: f_j + block_j dw_j (+ T_j l_j at stick nodes).
        std::vector<Tensor<1, dim>> base_force(n_active);
        for (unsigned int b = 0; b < n_active; ++b)
          {
            const unsigned int j = active[b];
            base_force[b] =
              lin[j].normal.pressure * nodes[j].weight * nodes[j].normal;
            if (lin[j].friction.state == ContactState::slip)
              base_force[b] += lin[j].friction.value;
          }
        for (unsigned int a = 0; a < n_active; ++a)
          {
            const unsigned int i = active[a];
            // Rows of node i: dw_i + sum_j C_ij (block_j dw_j + T_j l_j)
            //                   = w_free,i - w_i - sum_j C_ij base_j
            Tensor<1, dim> r = w_free[i] - w_nodes[i];
            for (unsigned int b = 0; b < n_active; ++b)
              {
                const unsigned int    j  = active[b];
                const Tensor<2, dim> &C  = columns[j][i];
                const Tensor<2, dim>  CB = C * lin[j].block;
                r -= C * base_force[b];
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
                vector(dim * a + p) = r[p];
              }
            // Stick: t_s . (w_i + dw_i) = 0.
            if (stick_offset[a] > 0)
              for (unsigned int s = 0; s < dim - 1; ++s)
                {
                  for (unsigned int p = 0; p < dim; ++p)
                    matrix(stick_offset[a] + s, dim * a + p) =
                      nodes[i].tangents[s][p];
                  vector(stick_offset[a] + s) =
                    -(nodes[i].tangents[s] * w_nodes[i]);
                }
          }
        matrix.compute_lu_factorization();
        matrix.solve(vector);

        // New forces of the active nodes; friction forces updated.
        std::vector<Tensor<1, dim>> new_forces(n);
        for (unsigned int i = 0; i < n; ++i)
          lambda[i] = Tensor<1, dim>();
        for (unsigned int a = 0; a < n_active; ++a)
          {
            const unsigned int j = active[a];
            Tensor<1, dim>     dw;
            for (unsigned int p = 0; p < dim; ++p)
              dw[p] = vector(dim * a + p);
            const auto &l = lin[j];
            if (l.friction.state == ContactState::slip)
              lambda[j] = l.friction.value + l.friction.jacobian * dw;
            else if (l.friction.state == ContactState::stick)
              for (unsigned int s = 0; s < dim - 1; ++s)
                lambda[j] += (vector(stick_offset[a] + s) / stick_scale[a]) *
                             nodes[j].tangents[s];
            new_forces[j] = l.normal.pressure * nodes[j].weight *
                              nodes[j].normal +
                            (l.block - l.friction.jacobian) * dw + lambda[j];
          }
        compliance_response(w_free, new_forces, active, w_nodes);
        ++result.iterations;
      }

    // The converged forces into the bulk: w = K0^{-1} (b - sum_i P_i^T f_i).
    right_hand_side = rhs;
    {
      const auto &                         owned  = problem.boundary.nodes();
      const auto &                         global = problem.boundary.global_indices();
      std::vector<types::global_dof_index> indices;
      std::vector<double>                  values;
      for (unsigned int i = 0; i < owned.size(); ++i)
        {
          const Tensor<1, dim> f =
            transpose(owned[i].constraint_map) * forces[global[i]];
          for (unsigned int c = 0; c < dim; ++c)
            {
              indices.push_back(owned[i].dofs[c]);
              values.push_back(-f[c]);
            }
        }
      right_hand_side.add(indices, values);
      right_hand_side.compress(VectorOperation::add);
    }
    solve_bulk(right_hand_side, w, result);
    return result;
  }


  template class CondensedNewton<2>;
  template class CondensedNewton<3>;
} // namespace DynamicContact
