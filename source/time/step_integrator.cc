#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/bulk/error_norms.h>
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
    known_energy.reset();
  }


  template <int dim>
  double
  StepIntegrator<dim>::energy()
  {
    if (!known_energy)
      known_energy = ops.energy_balance.energy(u, w).total();
    return *known_energy;
  }


  template <int dim>
  void
  StepIntegrator<dim>::record_errors(StepRecord<dim> &record,
                                     const double     t) const
  {
    if (!ops.scene.has_exact_solution())
      return;
    TimerSection   scope(ops.timer, "Step: energy and force balance");
    const Vector_t u_ghosted = ops.discretization.expanded(u),
                   w_ghosted = ops.discretization.expanded(w);
    record.has_errors        = true;
    record.errors            = compute_errors(
      ops.discretization, ops.material, ops.scene, t, u_ghosted, w_ghosted);
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
    // The displacement's local error of the step just solved (the
    // scheme's, StepScheme::local_error(): the difference to a solution of
    // higher order of the velocities the step computed). Its energy norm
    // a_E(e, e)^(1/2), relative to the larger of |(u, w)|_E at the two
    // ends, |(u, w)|_E^2 = rho |w|^2 + a_E(u, u).
    Vector_t e;
    e.reinit(u, true);
    ops.time.scheme->local_error(*this, e, k);
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
    ops.time.scheme->step(
      StepArguments<dim>{*this, record, t, k, accept_unconverged_loop});
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



  template class StepIntegrator<2>;
  template class StepIntegrator<3>;
} // namespace DynamicContact
