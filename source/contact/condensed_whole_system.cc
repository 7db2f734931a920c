#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/condensed_whole_system.h>
#include <dynamic_contact/contact/newton_driver.h>

#include <algorithm>

// The condensed solver's work on the whole body: the free response and
// phase 2, the whole-system Newton iteration solved by condensation.

namespace DynamicContact
{
  template <int dim>
  void
  CondensedWholeSystem<dim>::reinit()
  {
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
  CondensedWholeSystem<dim>::add_nodal_forces(
    const std::vector<Tensor<1, dim>> &f,
    const double                       factor,
    Vector_t                          &v) const
  {
    const auto &global = gathered.global_indices();
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return f[global[i]]; }, factor, v);
  }


  template <int dim>
  bool
  CondensedWholeSystem<dim>::update_free_response(const Vector_t &rhs,
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
        cached_rhs = rhs;
        data.force_scale =
          resolvable_force(rhs.linfty_norm(),
                           problem.parameters.newton_tolerance);
        data.w_free =
          gather_nodal_values(gathered, problem.boundary, free_response);
        free_response_valid = true;
        // A new step: the reduced factorization starts afresh, so a step
        // is solved the same whatever came before it (a resumed run
        // repeats an uninterrupted one to the byte).
        reduced.reset();
      }
    return same_rhs;
  }


  template <int dim>
  void
  CondensedWholeSystem<dim>::polish(
    const Iterate                   &it,
    const ContactStep<dim>          &step,
    const std::optional<PassForces> &previous_pass,
    std::vector<Tensor<1, dim>>     &lambda,
    Vector_t                        &w,
    Result                          &result,
    Vector_t                        *previous)
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
    const std::vector<Tensor<1, dim>> solved =
      gather_nodal_values(gathered, problem.boundary, w);
    double moved = 0;
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
  CondensedWholeSystem<dim>::newton_step(const WholeSystemNewton<dim>  &system,
                                         const WholeSystemIterate<dim> &x,
                                         WholeSystemIterate<dim>       &full,
                                         Result                        &result)
  {
    // The linearization at every node (the dense system couples them).
    Iterate it;
    it.w      = gather_nodal_values(gathered, problem.boundary, x.w);
    it.lambda = gathered.gather(x.lambda);
    boundary_newton.linearize(it);

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
    const auto z = gather_nodal_values(gathered, problem.boundary, solution);
    std::vector<Tensor<1, dim>> r(it.active.size()), dw, new_forces;
    for (unsigned int a = 0; a < it.active.size(); ++a)
      r[a] = z[it.active[a]];
    std::vector<Tensor<1, dim>> lambda_full = it.lambda;
    // The dense step on rank 0, which holds C and the reduced system, as
    // in phase 1 (CondensedBoundaryNewton).
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


  template class CondensedWholeSystem<2>;
  template class CondensedWholeSystem<3>;
} // namespace DynamicContact
