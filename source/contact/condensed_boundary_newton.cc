#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/condensed_boundary_newton.h>
#include <dynamic_contact/contact/newton_driver.h>

#include <algorithm>

namespace DynamicContact
{
  // Phase 1 of CondensedSolver, the iteration on Gamma_3 alone.


  template <int dim>
  void
  CondensedBoundaryNewton<dim>::linearize(Iterate &it) const
  {
    const auto        &u_old   = data.u_old;
    const auto        &w_old   = data.w_old;
    const auto        &mu      = data.mu;
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
    // WholeSystemNewton's floor.
    it.f_scale      = std::max(data.force_scale, 1e-300);
    it.law_residual = 0;
    it.law_squares  = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const NodeEvaluation<dim> e = evaluate_node(problem,
                                                    data.scheme,
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
        const double s = compliance.spring_stiffness(i);
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


  /**
   * Phase 1 of CondensedSolver::solve() as globalized_newton() sees it: the
   * iterates are the velocities and friction forces at every node of
   * Gamma_3, the equilibrium is w_i = w_free,i - sum_j C_ij g_j, the merit
   * half the sum of the squared equilibrium and law residuals (each relative
   * to its scale).
   */
  template <int dim>
  class CondensedBoundaryNewton<dim>::BoundaryProblem
  {
  public:
    using Iterate = typename CondensedBoundaryNewton<dim>::Iterate;

    BoundaryProblem(CondensedBoundaryNewton<dim> &solver,
                    const double                  w_scale,
                    Result                       &result)
      : solver(solver)
      , w_scale(w_scale)
      , result(result)
    {}

    NewtonMeasure
    evaluate(Iterate &x)
    {
      solver.linearize(x);
      solver.compliance.compute_columns(x.active, result);
      solver.compliance.response(solver.data.w_free, x.g, x.active, x.response);
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
      solver.compliance.subtract(difference, differing, response);
      r.resize(x.active.size());
      for (unsigned int a = 0; a < x.active.size(); ++a)
        r[a] = response[x.active[a]] - x.w[x.active[a]];
      full.lambda = x.lambda;
      // Far from the solution (residual above 1e-3) the step's round-off
      // does not matter: the next residual is of the order of the square
      // of this one.
      solver.reduced.step(x,
                          solver.data.scheme,
                          r,
                          dw,
                          full.lambda,
                          new_forces,
                          residual(x) >= far_above);
      solver.compliance.response(solver.data.w_free,
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
    static constexpr double       far_above = 1e-3;
    CondensedBoundaryNewton<dim> &solver;
    const double                  w_scale;
    Result                       &result;
    std::vector<Tensor<1, dim>>   response, r, dw, new_forces, difference;
    std::vector<unsigned int>     differing;
  };


  template <int dim>
  void
  CondensedBoundaryNewton<dim>::solve(Iterate     &it,
                                      const double w_scale,
                                      const double tolerance,
                                      Result      &result)
  {
    TimerSection t(problem.timer, "Contact: boundary Newton");
    // On rank 0, which holds C; the others compute the new columns of C
    // with it (the distributed factorization needs them all) and are sent
    // the iterate.
    BoundaryProblem boundary_problem(*this, w_scale, result);
    NewtonPolicy    policy; // non-monotone, stagnation factor 0.1
    policy.name      = "on Gamma_3";
    policy.tolerance = tolerance;
    // Phase 1 stops early at stagnation (sqrt(tol)): phase 2 polishes.
    compliance.on_leader(result, [&]() {
      globalized_newton(boundary_problem,
                        it,
                        policy,
                        problem.parameters,
                        problem.details,
                        result);
    });
    // What CondensedSolver's solve() and finalize() and
    // CondensedWholeSystem::polish() use of the iterate.
    compliance.share(it.w);
    compliance.share(it.lambda);
    compliance.share(it.g);
    compliance.share(it.response);
    compliance.share(it.active);
    compliance.share(result);
  }


  template class CondensedBoundaryNewton<2>;
  template class CondensedBoundaryNewton<3>;
} // namespace DynamicContact
