#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/bulk/error_norms.h>
#include <dynamic_contact/run/simulator.h>

#include <cmath>

namespace DynamicContact
{
  // The time step of the Simulator (assemble, solve and measure one step),
  // in a file of its own; the rest of the class is in simulator.cc.

  template <int dim>
  void
  Simulator<dim>::assemble_rhs(const TimeScheme &scheme,
                               const double      t,
                               const Vector_t   &u_start,
                               const Vector_t   &w_start)
  {
    const double k = scheme.time_step();
    {
      // K0 for a new mesh or time scheme.
      TimerSection assembly(timer, "Setup: bulk matrices");
      bulk.set_time_step(scheme);
    }
    TimerSection scope(timer, "Step: load and right-hand side");
    // f_theta = theta f_n + (1 - theta) f_{n-1}.
    bulk.assemble_load_vector(scene, t, load);
    if (!scheme.is_backward_euler())
      {
        bulk.assemble_load_vector(scene, t - k, scratch);
        scheme.weigh(load, scratch);
      }
    // b = (rho/k) M w_{n-1} - (1 - theta) A w_{n-1}
    //     - B (u_{n-1} + theta (1 - theta) k w_{n-1}) + f_theta
    bulk.mass_vmult(rhs, w_start);
    rhs *= scheme.mass_coefficient(material.density());
    scratch = u_start;
    scratch.add(scheme.elastic_old_velocity_factor(), w_start);
    bulk.elasticity_vmult(u, scratch); // u as scratch
    rhs -= u;
    if (!scheme.is_backward_euler() && bulk.has_viscosity())
      {
        bulk.viscosity_vmult(u, w_start);
        rhs.add(-scheme.viscosity_old_factor(), u);
      }
    rhs += load;
  }


  template <int dim>
  void
  Simulator<dim>::solve_substep(
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
        std::string where = collective_message(
          comm,
          scene.non_finite_value(discretization.triangulation, times, false));
        throw NonFiniteValue(where.empty() ?
                               "the load vector at t = " + sig6(t) +
                                 " s is not finite (the loads overflow)" :
                               where);
      }

    w = w_start; // initial guess
    // At the smallest time step a convexification loop that reaches its
    // cap is kept (reported) rather than failing the run.
    statistics = step_solver.solve(
      scheme, rhs, u_start, w_start, w, accept_unconverged_loop);
    last_newton_residual = statistics.residual;
    // Time/Cut back where not unique (doc/theory.md section 5.2); at the
    // smallest time step the step is kept, and the summary lists it.
    if (parameters.time.cut_back_where_not_unique &&
        statistics.contraction_factor >= 1 && !accept_unconverged_loop)
      throw StepFailure("the contraction factor of the step's solution is " +
                        sig6(statistics.contraction_factor) +
                        " >= 1: the step's solution may not be unique "
                        "(Time/Cut back where not unique)");

    if (!std::isfinite(w.l2_norm()))
      throw StepFailure("the solution is not finite");

    scheme.advance_displacement(u, u_start, w, w_start);

    TimerSection scope(timer, "Step: energy and force balance");
    terms = energy_balance.step_terms(
      u_start, w_start, u, w, load, scheme, contact_state.nodes, start_energy);
  }



  template <int dim>
  double
  Simulator<dim>::time_error_estimate(const double k) const
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
    if (parameters.time.scheme == Parameters::Time::Scheme::bathe)
      parameters.time.composite.local_error(e, w, w_bar, w_old, k);
    else if (parameters.time.scheme == Parameters::Time::Scheme::sdirk)
      // With w = W2, before the stages are combined (measure_last_solve).
      parameters.time.sdirk.local_error(e, w, w_stage, w_old, k);
    else
      {
        e = w;
        e -= w_old;
        e *= k / 2;
      }
    const double density = material.density();
    const double scale =
      std::max(density * bulk.mass_product(w, w) + bulk.elastic_product(u, u),
               density * bulk.mass_product(w_old, w_old) +
                 bulk.elastic_product(u_old, u_old));
    const double error = bulk.elastic_product(e, e);
    return scale > 0 ? std::sqrt(error / scale) : (error > 0 ? 1e300 : 0.);
  }


  template <int dim>
  StepRecord<dim>
  Simulator<dim>::do_time_step(const unsigned int n,
                               const double       t,
                               const double       k,
                               const double       remesh_energy_change,
                               const unsigned int cutbacks,
                               const unsigned int rejected,
                               const bool         accept_unconverged_loop)
  {
    u_old = u;
    w_old = w;
    StepRecord<dim> record;
    record.step      = n;
    record.time      = t;
    record.time_step = k;
    // The energy change of a mesh transfer before this step has its own
    // column: E_{n-1} below is that of the transferred fields.
    record.remesh_energy_change = remesh_energy_change;
    record.cutbacks             = cutbacks;
    record.previous_energy      = energy_now(); // of u_old = u, w_old = w

    if (parameters.time.scheme == Parameters::Time::Scheme::bathe)
      bathe_step(record, t, k, accept_unconverged_loop);
    else if (parameters.time.scheme == Parameters::Time::Scheme::sdirk)
      sdirk_step(record, t, k, accept_unconverged_loop);
    else
      theta_step(record, t, k, accept_unconverged_loop);
    if (parameters.time.adaptive)
      {
        record.adaptive_time = true;
        record.rejected      = rejected;
      }
    record.uniqueness_monitor = uniqueness_columns();
    record.solution_count     = solution_count_columns();
    record_errors(record, t);
    record.dofs     = discretization.dof_handler.n_dofs();
    record.cells    = discretization.triangulation.n_global_active_cells();
    energy_of_state = record.terms.energy.total(); // the step succeeded
    return record;
  }



  template <int dim>
  void
  Simulator<dim>::bathe_step(StepRecord<dim> &record,
                             const double     t,
                             const double     k,
                             const bool       accept_unconverged_loop)
  {
    // The Bathe composite scheme (doc/theory.md section 2.4). Sub-step
    // 1: the trapezoidal rule from t - k to t - k/2.
    const CompositeScheme               &composite = parameters.time.composite;
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
    const Energy       bar_energy = energy_balance.energy(u_bar, w_bar);
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
  Simulator<dim>::theta_step(StepRecord<dim> &record,
                             const double     t,
                             const double     k,
                             const bool       accept_unconverged_loop)
  {
    const TimeScheme scheme(k, parameters.time.theta());
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
  Simulator<dim>::measure_last_solve(StepRecord<dim>  &record,
                                     const TimeScheme &last,
                                     const Vector_t   &u_start,
                                     const Vector_t   &w_start,
                                     const double      t_last,
                                     const double      k)
  {
    if (parameters.time.adaptive)
      record.time_error = time_error_estimate(k);
    TimerSection scope(timer, "Step: energy and force balance");
    std::tie(record.normal_force, record.tangential_force) =
      contact_state.force_sums(contact_boundary, comm);
    const Vector_t w_ghosted     = discretization.expanded(w),
                   w_old_ghosted = discretization.expanded(w_start);
    // The stress of the scheme's equation: at u_theta, w_theta.
    scratch = u;
    last.weigh(scratch, u_start);
    const Vector_t u_theta = discretization.expanded(scratch);
    scratch                = w;
    last.weigh(scratch, w_start);
    const Vector_t w_theta = discretization.expanded(scratch);
    record.forces          = force_balance.compute(contact_boundary,
                                          contact_state.nodes,
                                          t_last,
                                          last,
                                          u_theta,
                                          w_theta,
                                          w_ghosted,
                                          w_old_ghosted);
  }



  template <int dim>
  void
  Simulator<dim>::solve_second_substep(
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
  Simulator<dim>::record_errors(StepRecord<dim> &record, const double t)
  {
    if (!scene.has_exact_solution())
      return;
    TimerSection   scope(timer, "Step: energy and force balance");
    const Vector_t u_ghosted = discretization.expanded(u),
                   w_ghosted = discretization.expanded(w);
    record.has_errors        = true;
    record.errors =
      compute_errors(discretization, material, scene, t, u_ghosted, w_ghosted);
  }



  template <int dim>
  void
  Simulator<dim>::sdirk_step(StepRecord<dim> &record,
                             const double     t,
                             const double     k,
                             const bool       accept_unconverged_loop)
  {
    // The two-stage SDIRK scheme (doc/theory.md section 2.6). Stage 1:
    // backward Euler over gamma k from y_{n-1}.
    const SdirkScheme                   &sdirk = parameters.time.sdirk;
    const TimeScheme                     stage = sdirk.stage(k);
    const double                         t0    = t - k;
    typename StepSolver<dim>::Statistics first_statistics;
    EnergyBalanceTerms                   first_terms;
    const double old_foundation = energy_balance.foundation_energy(u_old);
    solve_substep(stage,
                  t0 + sdirk.first_stage_time() * k,
                  u_old,
                  w_old,
                  record.previous_energy,
                  accept_unconverged_loop,
                  first_statistics,
                  first_terms);
    u_stage                 = u;
    w_stage                 = w;
    const auto first_forces = contact_state.force_sums(contact_boundary, comm);

    // Stage 2: backward Euler over gamma k from y_hat = y_{n-1} +
    // alpha (Y1 - y_{n-1}), to t_{n-1} + (1 - gamma) k.
    sdirk.second_stage_start(u_bar, u_stage, u_old);
    sdirk.second_stage_start(w_bar, w_stage, w_old);
    const Energy       hat_energy = energy_balance.energy(u_bar, w_bar);
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
    const double density = material.density();
    scratch              = u_stage;
    scratch -= u_old;
    scratch -= u;
    scratch += u_bar;
    double d2 = bulk.elastic_product(scratch, scratch);
    scratch   = w_stage;
    scratch -= w_old;
    scratch -= w;
    scratch += w_bar;
    d2 += density * bulk.mass_product(scratch, scratch);

    sdirk.combine(u, u_stage, u_bar, u_old);
    sdirk.combine(w, w_stage, w_bar, w_old);
    record.terms = sdirk_terms(first_terms,
                               second_terms,
                               record.previous_energy,
                               old_foundation,
                               hat_energy,
                               energy_balance.energy(u, w),
                               sdirk.numerical_dissipation_factor() * d2,
                               sdirk.stage_weight());
  }


// The members defined in this file, for 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                                      \
  template void Simulator<dim>::assemble_rhs(const TimeScheme &,              \
                                             const double,                    \
                                             const Vector_t &,                \
                                             const Vector_t &);               \
  template void Simulator<dim>::solve_substep(                                \
    const TimeScheme &,                                                       \
    const double,                                                             \
    const Vector_t &,                                                         \
    const Vector_t &,                                                         \
    const double,                                                             \
    const bool,                                                               \
    typename StepSolver<dim>::Statistics &,                                   \
    EnergyBalanceTerms &);                                                    \
  template double Simulator<dim>::time_error_estimate(const double) const;    \
  template StepRecord<dim> Simulator<dim>::do_time_step(const unsigned int,   \
                                                        const double,         \
                                                        const double,         \
                                                        const double,         \
                                                        const unsigned int,   \
                                                        const unsigned int,   \
                                                        const bool);          \
  template void Simulator<dim>::measure_last_solve(StepRecord<dim> &,         \
                                                   const TimeScheme &,        \
                                                   const Vector_t &,          \
                                                   const Vector_t &,          \
                                                   const double,              \
                                                   const double);             \
  template void Simulator<dim>::solve_second_substep(                         \
    const TimeScheme &,                                                       \
    const double,                                                             \
    const double,                                                             \
    const bool,                                                               \
    const typename StepSolver<dim>::Statistics &,                             \
    StepRecord<dim> &,                                                        \
    EnergyBalanceTerms &);                                                    \
  template void Simulator<dim>::record_errors(StepRecord<dim> &,              \
                                              const double);                  \
  template void Simulator<dim>::sdirk_step(StepRecord<dim> &,                 \
                                           const double,                      \
                                           const double,                      \
                                           const bool);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
