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
    , boundary_newton(this->problem, gathered, compliance, reduced, data)
    , whole_system(this->problem,
                   gathered,
                   compliance,
                   reduced,
                   boundary_newton,
                   data)
  {}


  template <int dim>
  void
  CondensedSolver<dim>::reinit()
  {
    gathered.reinit(problem.boundary);
    compliance.reinit();
    pending.reset();
    whole_system.reinit();
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
                                          const PassAccuracy          &accuracy)
  {
    return solve(step, lambda, w, true, accuracy.velocity);
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
    data.scheme = p.scheme;
    data.u_old  = gathered.gather(p.u_old);
    data.w_old  = gathered.gather(p.w_old);
    data.mu     = gather_coefficients(p.mu);
    const ContactStep<dim> step{
      p.scheme, whole_system.last_rhs(), p.u_old, p.w_old, p.mu};
    if (!p.loose)
      whole_system.polish(
        p.it, step, previous_pass, lambda, w, result, previous);
    else
      {
        // The pass stopped early: phase 1 on to the Newton tolerance first
        // (on Gamma_3, cheap), so that phase 2 starts where it would have.
        Iterate it = p.it;
        boundary_newton.solve(it, p.w_scale, 0., result);
        whole_system.polish(
          it, step, previous_pass, lambda, w, result, previous);
      }
    return result;
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
    data.scheme = scheme;
    if (compliance.prepare(result))
      {
        whole_system.invalidate_free_response();
        reduced.reset();
      }
    const unsigned int n = gathered.all_nodes().size();
    const bool same_rhs  = whole_system.update_free_response(rhs, result);
    std::vector<Tensor<1, dim>> previous_velocities =
      take_pending_pass(same_rhs, provisional);
    if (n == 0)
      {
        w = whole_system.free_velocity();
        return result;
      }
    data.u_old = gathered.gather(u_old);
    data.w_old = gathered.gather(w_old);
    // The coupled linearization's limits (WeakeningLimit): at every node
    // for phase 1, at the owned ones for phase 2.
    FrictionCoefficients owned_mu = mu;
    data.mu                       = gather_coefficients(mu);
    if (mu.coupled())
      {
        data.mu.weakening_limit  = compliance.weakening_limits(result);
        owned_mu.weakening_limit = gathered.owned_part(data.mu.weakening_limit);
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
      it.w = gather_nodal_values(gathered, problem.boundary, w);
    it.lambda      = gathered.gather(lambda);
    double w_scale = 1e-300;
    for (unsigned int i = 0; i < n; ++i)
      w_scale = std::max({w_scale, data.w_free[i].norm(), it.w[i].norm()});
    // Phase 1's residual is relative to w_scale (a velocity).
    const double loose_tolerance =
      provisional ? velocity_accuracy / w_scale : 0.;
    boundary_newton.solve(it, w_scale, loose_tolerance, result);

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
    const ContactStep<dim> polished{
      scheme, whole_system.last_rhs(), u_old, w_old, owned_mu};
    whole_system.polish(it, polished, previous_pass, lambda, w, result);
    return result;
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