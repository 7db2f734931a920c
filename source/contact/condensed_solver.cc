#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/condensed_solver.h>
#include <dynamic_contact/contact/newton_driver.h>

#include <algorithm>

namespace DynamicContact
{
  template <int dim>
  CondensedSolver<dim>::CondensedSolver(const ContactProblem<dim> &problem)
    : problem(problem)
    , compliance(this->problem, gathered)
    , reduced(gathered, compliance)
  {}


  template <int dim>
  void
  CondensedSolver<dim>::reinit()
  {
    gathered.reinit(problem.boundary);
    compliance.reinit();
    pending.reset();
    free_response_valid = false;
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
  CondensedSolver<dim>::add_nodal_forces(const std::vector<Tensor<1, dim>> &f,
                                         const double factor,
                                         Vector_t    &v) const
  {
    const auto &global = gathered.global_indices();
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return f[global[i]]; }, factor, v);
  }


  template <int dim>
  typename CondensedSolver<dim>::Result
  CondensedSolver<dim>::solve(const ContactStep<dim>      &step,
                              std::vector<Tensor<1, dim>> &lambda,
                              Vector_t                    &w)
  {
    return solve(step, lambda, w, false);
  }


  template <int dim>
  typename CondensedSolver<dim>::Result
  CondensedSolver<dim>::solve_provisional(const ContactStep<dim>      &step,
                                          std::vector<Tensor<1, dim>> &lambda,
                                          Vector_t                    &w,
                                          const double velocity_accuracy)
  {
    return solve(step, lambda, w, true, velocity_accuracy);
  }


  template <int dim>
  std::vector<Tensor<1, dim>>
  CondensedSolver<dim>::provisional_velocities() const
  {
    Assert(pending, ExcInternalError());
    return gathered.owned_part(pending->it.response);
  }



  template <int dim>
  SpectralEstimate
  CondensedSolver<dim>::compliance_radius(
    const std::vector<Tensor<2, dim>> &roots,
    const bool                         certify)
  {
    return compliance.radius(roots, certify);
  }


  template <int dim>
  typename CondensedSolver<dim>::Result
  CondensedSolver<dim>::finalize(Vector_t                    &w,
                                 std::vector<Tensor<1, dim>> &lambda,
                                 Vector_t                    *previous)
  {
    Assert(previous == nullptr || previous_pass, ExcInternalError());
    Result result;
    if (!pending)
      return result;
    const Pending p = std::move(*pending);
    pending.reset();
    step_scheme = p.scheme;
    u_old_all   = gathered.gather(p.u_old);
    w_old_all   = gathered.gather(p.w_old);
    mu_all      = gather_coefficients(p.mu);
    const ContactStep<dim> step{p.scheme, cached_rhs, p.u_old, p.w_old, p.mu};
    if (!p.loose)
      polish(p.it, step, lambda, w, result, previous);
    else
      {
        // The pass stopped early: phase 1 on to the Newton tolerance first
        // (on Gamma_3, cheap), so that phase 2 starts where it would have.
        Iterate it = p.it;
        boundary_newton(it, p.w_scale, 0., result);
        polish(it, step, lambda, w, result, previous);
      }
    return result;
  }


  template <int dim>
  bool
  CondensedSolver<dim>::update_free_response(const Vector_t &rhs,
                                             Result         &result)
  {
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
        compliance.solve(rhs, free_response, result);
        cached_rhs          = rhs;
        force_scale         = resolvable_force(rhs.linfty_norm(),
                                       problem.parameters.newton_tolerance);
        w_free_nodes        = gather_values(free_response);
        free_response_valid = true;
        // A new step: the reduced factorization starts afresh, so a step
        // is solved the same whatever came before it (a resumed run
        // repeats an uninterrupted one to the byte).
        reduced.reset();
      }
    return same_rhs;
  }


  template <int dim>
  std::vector<Tensor<1, dim>>
  CondensedSolver<dim>::take_pending_pass(const bool same_rhs,
                                          const bool provisional)
  {
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
    return previous_velocities;
  }


  template <int dim>
  typename CondensedSolver<dim>::Result
  CondensedSolver<dim>::solve(const ContactStep<dim>      &step,
                              std::vector<Tensor<1, dim>> &lambda,
                              Vector_t                    &w,
                              const bool                   provisional,
                              const double                 velocity_accuracy)
  {
    Assert(step.scheme == problem.bulk.scheme(),
           ExcMessage("K0 is not formed for the step's time scheme."));
    const auto &[scheme, rhs, u_old, w_old, mu] = step;
    Result result;
    step_scheme = scheme;
    if (compliance.prepare(result))
      {
        free_response_valid = false;
        reduced.reset();
      }
    const unsigned int          n        = gathered.all_nodes().size();
    const bool                  same_rhs = update_free_response(rhs, result);
    std::vector<Tensor<1, dim>> previous_velocities =
      take_pending_pass(same_rhs, provisional);
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
        mu_all.weakening_limit   = compliance.weakening_limits(result);
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
          Pending{scheme,
                  u_old,
                  w_old,
                  owned_mu,
                  std::move(it),
                  w_scale,
                  loose_tolerance > problem.parameters.newton_tolerance});
        result.provisional = true;
        return result;
      }
    polish(it, {scheme, cached_rhs, u_old, w_old, owned_mu}, lambda, w, result);
    return result;
  }


  template <int dim>
  void
  CondensedSolver<dim>::polish(const Iterate               &it,
                               const ContactStep<dim>      &step,
                               std::vector<Tensor<1, dim>> &lambda,
                               Vector_t                    &w,
                               Result                      &result,
                               Vector_t                    *previous)
  {
    const Vector_t &rhs = step.rhs;
    // The forces into the bulk: w = K0'^{-1} (b - sum_i P_i^T g_i), i.e.
    // K0 w = b - sum_i P_i^T f_i where w_i is the iterate of phase 1. (A
    // solve: w_free - sum_j X_j g_j from the stored columns costs as much
    // and leaves a bulk residual far larger, which the first Newton step
    // of phase 2 would have to solve for.)
    right_hand_side = rhs;
    add_nodal_forces(it.g, -1., right_hand_side);
    // The earlier provisional pass's velocity alike (finalize()): a sum of
    // the stored whole columns, or in one block solve with w.
    if (previous != nullptr &&
        compliance.apply_full_columns(previous_pass->first,
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
        compliance.solve({&right_hand_side, &scratch}, {&w, previous}, result);
      }
    else
      compliance.solve(right_hand_side, w, result);

    // Phase 2: Newton on the residual of the whole system,
    //   R = K0 w - b + sum_i P_i^T f_i(w),
    // each step solved by the same condensation (newton_step()). Where
    // phase 1 converged this only checks the residual.
    TimerSection           t(problem.timer, "Contact: refinement");
    WholeSystemNewton<dim> system(problem, step, *this, result);
    // The stick condition in velocity units too, relative to |w|; where the
    // body is at rest |w| is itself round-off, which is of order eps
    // |w_free| (w = w_free - C g cancels): 1e-6 |w_free| keeps the test
    // above it.
    system.velocity_scale =
      std::max({w.linfty_norm(), 1e-6 * free_response.linfty_norm(), 1e-300});
    WholeSystemIterate<dim> x;
    x.w      = w;
    x.lambda = gathered.owned_part(it.lambda);
    NewtonPolicy policy;
    policy.monotone          = true;
    policy.stagnation_factor = 0.5;
    policy.name              = "whole system";
    // The solve gives the nodal velocities of phase 1 again only to the
    // round-off of K0' (the compliance C and the solves differ by about
    // eps cond(K0')). Where that moved the slip rates by more than the
    // convexification loop needs, one step makes w consistent to its own
    // round-off; else the loop's coefficient residual, max |mu_i -
    // mu(|w_tau,i|)|, follows that round-off (the steep-friction stress
    // scene, alpha = 2e5 s/m, took more passes without this step, and a
    // different number in SI, mm-tonne-s and inch-lbf-s; with it fewer,
    // and nearly the same in all three).
    const std::vector<Tensor<1, dim>> solved = gather_values(w);
    double                            moved  = 0;
    for (const unsigned int i : it.active)
      moved = std::max(moved, (solved[i] - it.w[i]).norm());
    policy.minimum_iterations = moved > problem.slip_rate_accuracy;
    globalized_newton(
      system, x, policy, problem.parameters, problem.details, result);
    w      = x.w;
    lambda = x.lambda;
  }


  template <int dim>
  void
  CondensedSolver<dim>::newton_step(const WholeSystemNewton<dim>  &system,
                                    const WholeSystemIterate<dim> &x,
                                    WholeSystemIterate<dim>       &full,
                                    Result                        &result)
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
    compliance.compute_columns(it.active, result);

    // The rest of the step, K0'^{-1} sum_i P_i^T (g_i^new - base_i), is a
    // sum of the stored whole columns if they are kept, else a solve. (Tried:
    // z from C times the nodal part of v alone, the rest of v, bulk
    // round-off of about 1e-11 |b|, left out: its response at the nodes is
    // far larger and left a stick node of the critical-speed stress scene
    // slipping above the law's tolerance.)
    compliance.solve(residual, solution, result);
    const auto                  z = gather_values(solution);
    std::vector<Tensor<1, dim>> r(it.active.size()), dw, new_forces;
    for (unsigned int a = 0; a < it.active.size(); ++a)
      r[a] = z[it.active[a]];
    std::vector<Tensor<1, dim>> lambda_full = it.lambda;
    // The dense step on rank 0, which holds C and the reduced system, as
    // in phase 1 (boundary_newton()).
    compliance.on_leader(result, [&]() {
      reduced.step(it, system.scheme, r, dw, lambda_full, new_forces);
    });
    compliance.share(lambda_full);
    compliance.share(new_forces);
    for (const unsigned int j : it.active)
      new_forces[j] -= it.base[j];
    if (!compliance.apply_full_columns(new_forces, it.active, increment))
      {
        right_hand_side = 0;
        add_nodal_forces(new_forces, 1., right_hand_side);
        compliance.solve(right_hand_side, increment, result);
      }
    solution -= increment; // the full step
    full.w = x.w;
    full.w += solution;
    full.lambda = gathered.owned_part(lambda_full);
  }


  template <int dim>
  void
  CondensedSolver<dim>::memory_consumption(MemoryItems &items) const
  {
    compliance.memory_consumption(items);
    items.push_back(
      {"reduced dense system on Gamma_3", reduced.memory_consumption(), false});
  }


  template class CondensedSolver<2>;
  template class CondensedSolver<3>;
} // namespace DynamicContact