#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/time/step_integrator.h>

#include <cmath>

namespace DynamicContact
{
  template <int dim>
  StepIntegrator<dim>::StepIntegrator(const StepOperators<dim> &operators)
    : ops(operators)
  {}


  template <int dim>
  void
  StepIntegrator<dim>::reinit()
  {
    for (Vector_t *v : fields(*this))
      ops.discretization.reinit_owned(*v);
  }


  template <int dim>
  double
  StepIntegrator<dim>::memory_consumption() const
  {
    double bytes = 0;
    for (const Vector_t *v : fields(*this))
      bytes += v->locally_owned_size() * sizeof(double);
    return bytes;
  }


  template <int dim>
  void
  StepIntegrator<dim>::assemble_rhs(const TimeScheme &scheme,
                                    const double      t,
                                    const Vector_t   &u_start,
                                    const Vector_t   &w_start)
  {
    const double k = scheme.time_step();
    {
      // K0 for a new mesh or time scheme.
      TimerSection assembly(ops.timer, "Setup: bulk matrices");
      ops.bulk.set_time_step(scheme);
    }
    TimerSection scope(ops.timer, "Step: load and right-hand side");
    // f_theta = theta f_n + (1 - theta) f_{n-1}.
    ops.bulk.assemble_load_vector(ops.scene, t, load);
    if (!scheme.is_backward_euler())
      {
        ops.bulk.assemble_load_vector(ops.scene, t - k, scratch);
        scheme.weigh(load, scratch);
      }
    // b = (rho/k) M w_{n-1} - (1 - theta) A w_{n-1}
    //     - B (u_{n-1} + theta (1 - theta) k w_{n-1}) + f_theta
    ops.bulk.mass_vmult(rhs, w_start);
    rhs *= scheme.mass_coefficient(ops.material.density());
    scratch = u_start;
    scratch.add(scheme.elastic_old_velocity_factor(), w_start);
    ops.bulk.elasticity_vmult(u, scratch); // u as scratch
    rhs -= u;
    if (!scheme.is_backward_euler() && ops.bulk.has_viscosity())
      {
        ops.bulk.viscosity_vmult(u, w_start);
        rhs.add(-scheme.viscosity_old_factor(), u);
      }
    rhs += load;
  }


  template <int dim>
  void
  StepIntegrator<dim>::solve_substep(
    const TimeScheme                     &scheme,
    const double                          t,
    const Vector_t                       &u_start,
    const Vector_t                       &w_start,
    const double                          start_energy,
    const bool                            accept_unconverged_loop,
    typename StepSolver<dim>::Statistics &statistics,
    EnergyBalanceTerms                   &terms)
  {
    const double k = scheme.time_step();
    assemble_rhs(scheme, t, u_start, w_start);
    // A load that is not finite (an expression that blows up at this time)
    // is not a failure of the solver: no cut-back, the run stops with the
    // last good state, naming the function.
    if (!std::isfinite(load.l2_norm()))
      {
        std::vector<double> times = {t};
        if (!scheme.is_backward_euler())
          times.push_back(t - k);
        std::string where =
          collective_message(ops.comm,
                             ops.scene.non_finite_value(
                               ops.discretization.triangulation, times, false));
        throw NonFiniteValue(where.empty() ?
                               "the load vector at t = " + sig6(t) +
                                 " s is not finite (the loads overflow)" :
                               where);
      }

    w = w_start; // initial guess
    // At the smallest time step a convexification loop that reaches its
    // cap is kept (reported) rather than failing the run.
    statistics = ops.step_solver.solve(
      scheme, rhs, u_start, w_start, w, accept_unconverged_loop);
    last_newton_residual = statistics.residual;
    // Time/Cut back where not unique (doc/theory.md section 5.2); at the
    // smallest time step the step is kept, and the summary lists it.
    if (ops.time.cut_back_where_not_unique &&
        statistics.contraction_factor >= 1 && !accept_unconverged_loop)
      throw StepFailure("the contraction factor of the step's solution is " +
                        sig6(statistics.contraction_factor) +
                        " >= 1: the step's solution may not be unique "
                        "(Time/Cut back where not unique)");

    if (!std::isfinite(w.l2_norm()))
      throw StepFailure("the solution is not finite");

    scheme.advance_displacement(u, u_start, w, w_start);

    TimerSection scope(ops.timer, "Step: energy and force balance");
    terms = ops.energy_balance.step_terms(u_start,
                                          w_start,
                                          u,
                                          w,
                                          load,
                                          scheme,
                                          ops.contact_state.nodes,
                                          start_energy);
  }



  template <int dim>
  double
  StepIntegrator<dim>::time_error_estimate(const double k) const
  {
    // The displacement's local error, from the step just solved (u, w from
    // u_old, w_old; for the Bathe scheme w_{n-1/2} = (3 w_bar + w_old)/4
    // at rho_inf = 0, CompositeScheme::local_error for any rho_inf):
    //   backward Euler: e = u_n - (u_{n-1} + k (w_{n-1} + w_n)/2)
    //                     = (k/2) (w_n - w_{n-1}),
    //   Bathe:          e = u_n - (u_{n-1} + k (w_{n-1} + 4 w_{n-1/2}
    //                     + w_n)/6) = (k/6) (w_{n-1} - 2 w_{n-1/2} + w_n),
    // the difference to a solution of higher order (the trapezoidal rule,
    // Simpson's rule) of the velocities the step computed. Its energy norm
    // a_E(e, e)^(1/2), relative to the larger of |(u, w)|_E at the two
    // ends, |(u, w)|_E^2 = rho |w|^2 + a_E(u, u).
    Vector_t e;
    e.reinit(u, true);
    if (ops.time.scheme == Parameters::Time::Scheme::bathe)
      ops.time.composite.local_error(e, w, w_bar, w_old, k);
    else if (ops.time.scheme == Parameters::Time::Scheme::sdirk)
      // With w = W2, before the stages are combined (measure_last_solve).
      ops.time.sdirk.local_error(e, w, w_stage, w_old, k);
    else
      {
        e = w;
        e -= w_old;
        e *= k / 2;
      }
    const double density = ops.material.density();
    const double scale =
      std::max(density * ops.bulk.mass_product(w, w) +
                 ops.bulk.elastic_product(u, u),
               density * ops.bulk.mass_product(w_old, w_old) +
                 ops.bulk.elastic_product(u_old, u_old));
    const double error = ops.bulk.elastic_product(e, e);
    return scale > 0 ? std::sqrt(error / scale) : (error > 0 ? 1e300 : 0.);
  }


  template <int dim>
  void
  StepIntegrator<dim>::step(StepRecord<dim> &record,
                            const double     t,
                            const double     k,
                            const bool       accept_unconverged_loop)
  {
    u_old = u;
    w_old = w;
    if (ops.time.scheme == Parameters::Time::Scheme::bathe)
      bathe_step(record, t, k, accept_unconverged_loop);
    else if (ops.time.scheme == Parameters::Time::Scheme::sdirk)
      sdirk_step(record, t, k, accept_unconverged_loop);
    else
      theta_step(record, t, k, accept_unconverged_loop);
  }


  template <int dim>
  void
  StepIntegrator<dim>::bathe_step(StepRecord<dim> &record,
                                  const double     t,
                                  const double     k,
                                  const bool       accept_unconverged_loop)
  {
    // The Bathe composite scheme (doc/theory.md section 2.4). Sub-step
    // 1: the trapezoidal rule from t - k to t - k/2.
    const CompositeScheme               &composite = ops.time.composite;
    const TimeScheme                     first     = composite.first_substep(k);
    typename StepSolver<dim>::Statistics first_statistics;
    EnergyBalanceTerms                   first_terms;
    solve_substep(first,
                  t - k / 2,
                  u_old,
                  w_old,
                  record.previous_energy,
                  accept_unconverged_loop,
                  first_statistics,
                  first_terms);
    // Sub-step 2: a theta-step from the extrapolated state x_bar =
    // (1 + a) x_{n-1/2} - a x_{n-1} to t (at rho_inf = 0 the three-point
    // backward difference: backward Euler over k/3 from
    // (4 x_{n-1/2} - x_{n-1})/3).
    composite.extrapolate(u_bar, u, u_old);
    composite.extrapolate(w_bar, w, w_old);
    const Energy       bar_energy = ops.energy_balance.energy(u_bar, w_bar);
    const TimeScheme   last       = composite.second_substep(k);
    EnergyBalanceTerms second_terms;
    solve_second_substep(last,
                         t,
                         bar_energy.total(),
                         accept_unconverged_loop,
                         first_statistics,
                         record,
                         second_terms);
    // (f, u_bar - u_{n-1/2}) = a/(1 + a) (f, u_bar - u_{n-1}) with the
    // second sub-step's load f (f_n at rho_inf = 0).
    scratch = u_bar;
    scratch -= u_old;
    const double extrapolation_work =
      composite.extrapolation_share() * (load * scratch);
    record.terms = bathe_terms(first_terms,
                               bar_energy,
                               second_terms,
                               extrapolation_work,
                               record.previous_energy);
    measure_last_solve(record, last, u_bar, w_bar, t, k);
  }


  template <int dim>
  void
  StepIntegrator<dim>::theta_step(StepRecord<dim> &record,
                                  const double     t,
                                  const double     k,
                                  const bool       accept_unconverged_loop)
  {
    const TimeScheme scheme(k, ops.time.theta());
    solve_substep(scheme,
                  t,
                  u_old,
                  w_old,
                  record.previous_energy,
                  accept_unconverged_loop,
                  record.statistics,
                  record.terms);
    measure_last_solve(record, scheme, u_old, w_old, t, k);
  }


  template <int dim>
  void
  StepIntegrator<dim>::measure_last_solve(StepRecord<dim>  &record,
                                          const TimeScheme &last,
                                          const Vector_t   &u_start,
                                          const Vector_t   &w_start,
                                          const double      t_last,
                                          const double      k)
  {
    if (ops.time.adaptive)
      record.time_error = time_error_estimate(k);
    TimerSection scope(ops.timer, "Step: energy and force balance");
    std::tie(record.normal_force, record.tangential_force) =
      ops.contact_state.force_sums(ops.contact_boundary, ops.comm);
    const Vector_t w_ghosted     = ops.discretization.expanded(w),
                   w_old_ghosted = ops.discretization.expanded(w_start);
    // The stress of the scheme's equation: at u_theta, w_theta.
    scratch = u;
    last.weigh(scratch, u_start);
    const Vector_t u_theta = ops.discretization.expanded(scratch);
    scratch                = w;
    last.weigh(scratch, w_start);
    const Vector_t w_theta = ops.discretization.expanded(scratch);
    record.forces          = ops.force_balance.compute(ops.contact_boundary,
                                              ops.contact_state.nodes,
                                              t_last,
                                              last,
                                              u_theta,
                                              w_theta,
                                              w_ghosted,
                                              w_old_ghosted);
  }



  template <int dim>
  void
  StepIntegrator<dim>::solve_second_substep(
    const TimeScheme                           &scheme,
    const double                                t,
    const double                                start_energy,
    const bool                                  accept_unconverged_loop,
    const typename StepSolver<dim>::Statistics &first_statistics,
    StepRecord<dim>                            &record,
    EnergyBalanceTerms                         &terms)
  {
    solve_substep(scheme,
                  t,
                  u_bar,
                  w_bar,
                  start_energy,
                  accept_unconverged_loop,
                  record.statistics,
                  terms);
    record.statistics.add_work(first_statistics);
    last_newton_residual =
      std::max(first_statistics.residual, record.statistics.residual);
  }



  template <int dim>
  void
  StepIntegrator<dim>::sdirk_step(StepRecord<dim> &record,
                                  const double     t,
                                  const double     k,
                                  const bool       accept_unconverged_loop)
  {
    // The two-stage SDIRK scheme (doc/theory.md section 2.6). Stage 1:
    // backward Euler over gamma k from y_{n-1}.
    const SdirkScheme                   &sdirk = ops.time.sdirk;
    const TimeScheme                     stage = sdirk.stage(k);
    const double                         t0    = t - k;
    typename StepSolver<dim>::Statistics first_statistics;
    EnergyBalanceTerms                   first_terms;
    const double old_foundation = ops.energy_balance.foundation_energy(u_old);
    solve_substep(stage,
                  t0 + sdirk.first_stage_time() * k,
                  u_old,
                  w_old,
                  record.previous_energy,
                  accept_unconverged_loop,
                  first_statistics,
                  first_terms);
    u_stage = u;
    w_stage = w;
    const auto first_forces =
      ops.contact_state.force_sums(ops.contact_boundary, ops.comm);

    // Stage 2: backward Euler over gamma k from y_hat = y_{n-1} +
    // alpha (Y1 - y_{n-1}), to t_{n-1} + (1 - gamma) k.
    sdirk.second_stage_start(u_bar, u_stage, u_old);
    sdirk.second_stage_start(w_bar, w_stage, w_old);
    const Energy       hat_energy = ops.energy_balance.energy(u_bar, w_bar);
    EnergyBalanceTerms second_terms;
    const double       t2 = t0 + sdirk.second_stage_time() * k;
    solve_second_substep(stage,
                         t2,
                         hat_energy.total(),
                         accept_unconverged_loop,
                         first_statistics,
                         record,
                         second_terms);

    // The error estimate (with w = W2) and the force balance of stage 2's
    // equation; the contact force sums extrapolated from the stages to t_n.
    measure_last_solve(record, stage, u_bar, w_bar, t2, k);
    record.normal_force =
      sdirk.value_at_end(first_forces.first, record.normal_force);
    record.tangential_force =
      sdirk.value_at_end(first_forces.second, record.tangential_force);

    // The numerical dissipation from the stage increments,
    // d = (Y1 - y_{n-1}) - (Y2 - y_hat), before u, w become y_n.
    const double density = ops.material.density();
    scratch              = u_stage;
    scratch -= u_old;
    scratch -= u;
    scratch += u_bar;
    double d2 = ops.bulk.elastic_product(scratch, scratch);
    scratch   = w_stage;
    scratch -= w_old;
    scratch -= w;
    scratch += w_bar;
    d2 += density * ops.bulk.mass_product(scratch, scratch);

    sdirk.combine(u, u_stage, u_bar, u_old);
    sdirk.combine(w, w_stage, w_bar, w_old);
    record.terms = sdirk_terms(first_terms,
                               second_terms,
                               record.previous_energy,
                               old_foundation,
                               hat_energy,
                               ops.energy_balance.energy(u, w),
                               sdirk.numerical_dissipation_factor() * d2,
                               sdirk.stage_weight());
  }


  template class StepIntegrator<2>;
  template class StepIntegrator<3>;
} // namespace DynamicContact
