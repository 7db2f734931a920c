#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/bulk/error_norms.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/resources.h>
#include <dynamic_contact/run/simulator.h>
#include <dynamic_contact/base/timing.h>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace DynamicContact
{
  template <int dim>
  Simulator<dim>::Simulator(const RunParameters      &parameters,
                            ParameterHandler         &prm,
                            const MPI_Comm            comm,
                            TimerOutput              &timer,
                            const ConditionalOStream &details)
    : parameters(parameters)
    , comm(comm)
    , timer(timer)
    , scene(parameters, prm)
    , material(parameters.material)
    , foundation(*parameters.foundation.law)
    , friction_law(parameters.friction.law)
    , discretization(comm, parameters.finite_element.degree)
    , bulk(discretization, material)
    , step_solver(discretization,
                  bulk,
                  contact_boundary,
                  contact_state,
                  foundation,
                  friction_law.get(),
                  parameters.solver,
                  parameters.friction,
                  timer,
                  details)
    , energy_balance(bulk,
                     contact_boundary,
                     foundation,
                     material.density(),
                     comm)
    , force_balance(discretization, material, scene)
    , mesh_adaptation(parameters.mesh_refinement, scene, discretization, prm)
  {}


  template <int dim>
  void
  Simulator<dim>::setup_dofs()
  {
    TimerSection t(timer, "Setup: DoFs and Gamma_3");
    discretization.setup_dofs(parameters.boundary_conditions);
    contact_boundary.reinit(discretization,
                            parameters.boundary_conditions.contact,
                            scene.initial_gap());
    for (auto *v : {&u,
                    &w,
                    &u_old,
                    &w_old,
                    &u_bar,
                    &w_bar,
                    &u_stage,
                    &w_stage,
                    &load,
                    &rhs,
                    &scratch})
      discretization.reinit_owned(*v);
    energy_of_state.reset();
  }


  template <int dim>
  double
  Simulator<dim>::energy_now()
  {
    if (!energy_of_state)
      energy_of_state = energy_balance.energy(u, w).total();
    return *energy_of_state;
  }


  template <int dim>
  void
  Simulator<dim>::setup_operators()
  {
    TimerSection t(timer, "Setup: bulk matrices");
    bulk.reinit();
    force_balance.reinit();
    // c_t of the friction complementarity function, like E/h.
    const double c_t = parameters.friction.complementarity_constant > 0 ?
                         parameters.friction.complementarity_constant :
                         parameters.material.young_modulus /
                           discretization.minimal_cell_diameter();
    step_solver.reinit(c_t);
  }


  template <int dim>
  void
  Simulator<dim>::set_initial_conditions()
  {
    // Interpolate, then impose the constraints (clamped and roller
    // conditions, and master form at hanging nodes).
    VectorTools::interpolate(discretization.mapping,
                             discretization.dof_handler,
                             scene.initial_displacement(),
                             u);
    VectorTools::interpolate(discretization.mapping,
                             discretization.dof_handler,
                             scene.initial_velocity(),
                             w);
    discretization.constraints.set_zero(u);
    discretization.constraints.set_zero(w);
  }


  template <int dim>
  std::vector<Point<dim>>
  Simulator<dim>::penetrating_nodes() const
  {
    // Only contact following asks for them (the same on every process).
    if (!mesh_adaptation.needs_contact_points())
      return {};
    std::vector<Point<dim>> local;
    for (const auto &node : contact_boundary.nodes())
      if (node.value(u) * node.normal - node.gap > 0)
        local.push_back(node.position);
    std::vector<Point<dim>> all;
    for (const auto &part : Utilities::MPI::all_gather(comm, local))
      all.insert(all.end(), part.begin(), part.end());
    return all;
  }



  template <int dim>
  void
  Simulator<dim>::save_checkpoint(OutputDirectory   &directory,
                                  const RunState    &state,
                                  const std::string &parameters_of_run,
                                  const unsigned int keep,
                                  const std::function<void()> &before_commit)
  {
    // The friction forces exactly, as a field of nodal forces saved with the
    // mesh (any number of processes can load it).
    Vector_t friction =
      contact_state.friction_field(discretization, contact_boundary, false);
    write_checkpoint(directory,
                     discretization,
                     {&u, &w, &friction},
                     state,
                     parameters_of_run,
                     keep,
                     before_commit);
  }


  template <int dim>
  void
  Simulator<dim>::load_checkpoint(const std::string &path)
  {
    Vector_t friction;
    DynamicContact::load_checkpoint<dim>(path,
                                         discretization,
                                         {&u, &w, &friction},
                                         [this]() { setup_dofs(); });
    setup_operators();
    contact_state.set_friction_from_field(contact_boundary, friction, false);
  }


  template <int dim>
  void
  Simulator<dim>::refine_initial_mesh()
  {
    // Refine towards the load of the first steps, with the initial
    // conditions interpolated anew on each mesh (no transfer needed).
    const double k = parameters.time.time_step;
    const double t1 =
      std::min(parameters.time.end_time, mesh_adaptation.lookahead_steps() * k);
    for (unsigned int cycle = 0; cycle < mesh_adaptation.max_cycles(); ++cycle)
      {
        set_initial_conditions();
        const Vector_t u_ghosted = discretization.expanded(u),
                       w_ghosted = discretization.expanded(w);
        if (!mesh_adaptation.flag_cells(
              0., t1, k, penetrating_nodes(), u_ghosted, w_ghosted))
          break;
        const auto before = mesh_adaptation.fingerprint();
        discretization.triangulation.execute_coarsening_and_refinement();
        setup_dofs();
        if (mesh_adaptation.fingerprint() == before)
          break;
      }
  }


  template <int dim>
  double
  Simulator<dim>::adapt_mesh(const double t0, const double t1, const double k)
  {
    TimerSection scope(timer, "Mesh adaptation");
    const double energy_before = energy_now();
    bool         changed       = false;
    for (unsigned int cycle = 0; cycle < mesh_adaptation.max_cycles(); ++cycle)
      {
        const Vector_t u_ghosted = discretization.expanded(u),
                       w_ghosted = discretization.expanded(w);
        if (!mesh_adaptation.flag_cells(
              t0, t1, k, penetrating_nodes(), u_ghosted, w_ghosted))
          break;

        // What the next step needs, as finite element fields: u, w, and the
        // friction forces as a traction at the nodes of Gamma_3.
        Vector_t traction =
          contact_state.friction_field(discretization, contact_boundary, true);
        const auto before = mesh_adaptation.fingerprint();
        refine_and_transfer(discretization, {&u, &w, &traction}, [this]() {
          setup_dofs();
        });
        // on the new nodes
        contact_state.set_friction_from_field(contact_boundary, traction, true);
        changed = true;
        if (mesh_adaptation.fingerprint() == before)
          break;
      }
    if (changed)
      {
        // setup_operators() resets the step solver; the nodes stay.
        const auto lambda = contact_state.lambda;
        setup_operators();
        contact_state.lambda = lambda;
      }
    return energy_now() - energy_before;
  }



  template <int dim>
  void
  Simulator<dim>::create_mesh()
  {
    // The size of the scene is checked before it is allocated.
    const bool rectangle =
      parameters.geometry.type == Parameters::Geometry::Type::rectangle;
    if (rectangle)
      {
        double n = 1;
        for (const unsigned int r : parameters.geometry.repetitions)
          n *= r;
        check_resources(parameters, dim, n, comm);
      }
    TimerSection t(timer, "Setup: mesh");
    scene.create_mesh(discretization.triangulation, false);
    if (!rectangle)
      check_resources(parameters,
                      dim,
                      discretization.triangulation.n_cells(0),
                      comm);
  }


  template <int dim>
  void
  Simulator<dim>::set_up_initial_state()
  {
    discretization.triangulation.refine_global(
      parameters.geometry.global_refinements);
    check_input(false);
    setup_dofs();
    if (mesh_adaptation.enabled())
      refine_initial_mesh();
    setup_operators();
    set_initial_conditions();
    const double norm = u.l2_norm() + w.l2_norm();
    if (!std::isfinite(norm))
      throw CollectiveError("Initial conditions: the interpolated initial "
                            "state is not finite.");
  }


  template <int dim>
  bool
  Simulator<dim>::uniqueness_columns() const
  {
    return parameters.friction.law && !parameters.friction.law->is_constant() &&
           parameters.friction.uniqueness_monitor !=
             Parameters::Friction::Monitor::never;
  }


  template <int dim>
  StepRecord<dim>
  Simulator<dim>::initial_record()
  {
    StepRecord<dim> record;
    record_errors(record, 0.);
    record.terms.energy    = energy_balance.energy(u, w);
    record.previous_energy = record.terms.energy.total();
    energy_of_state        = record.previous_energy;
    record.dofs            = discretization.dof_handler.n_dofs();
    record.cells         = discretization.triangulation.n_global_active_cells();
    record.adaptive_time = parameters.time.adaptive; // the columns, 0
    record.uniqueness_monitor = uniqueness_columns();  // -1: not evaluated
    return record;
  }


  template <int dim>
  std::string
  Simulator<dim>::summary() const
  {
    std::ostringstream summary;
    summary << dim << "D, Q" << discretization.fe.degree << " elements, "
            << discretization.triangulation.n_global_active_cells()
            << " cells, " << discretization.dof_handler.n_dofs() << " DoFs, "
            << contact_boundary.n_global_nodes() << " contact nodes";
    return summary.str();
  }


  template <int dim>
  void
  Simulator<dim>::print_model(const ConditionalOStream &pcout) const
  {
    pcout << "  material: rho = " << material.density()
          << ", lambda = " << sig6(material.lambda())
          << ", mu = " << sig6(material.mu())
          << (material.has_viscosity() ? ", viscous" : ", elastic (C = 0)")
          << '\n';
    pcout << "  friction: "
          << (step_solver.has_friction() ? friction_law->description() :
                                           std::string("none"));
    if (step_solver.has_friction())
      pcout << ", one-sided Lipschitz constant on [0, "
            << parameters.friction.maximum_slip_rate << "] m/s: "
            << sig6(friction_law->one_sided_lipschitz_constant(
                 parameters.friction.maximum_slip_rate))
            << (friction_law->is_constant() ? " (constant: one pass)" : "");
    pcout << '\n';
  }


  template <int dim>
  void
  Simulator<dim>::assemble_rhs(const TimeScheme &scheme,
                               const double      t,
                               const Vector_t   &u_start,
                               const Vector_t   &w_start)
  {
    const double k = scheme.time_step();
    TimerSection scope(timer, "Step: load and right-hand side");
    bulk.set_time_step(scheme);
    // f_theta = theta f_n + (1 - theta) f_{n-1}.
    bulk.assemble_load_vector(scene, t, load);
    if (!scheme.is_backward_euler())
      {
        bulk.assemble_load_vector(scene, t - k, scratch);
        scheme.weigh(load, scratch);
      }
    // b = (rho/k) M w_{n-1} - (1 - theta) A w_{n-1}
    //     - B (u_{n-1} + theta (1 - theta) k w_{n-1}) + f_theta
    bulk.mass().vmult(rhs, w_start);
    rhs *= scheme.mass_coefficient(material.density());
    scratch = u_start;
    scratch.add(scheme.elastic_old_velocity_factor(), w_start);
    bulk.elasticity().vmult(u, scratch); // u as scratch
    rhs -= u;
    if (!scheme.is_backward_euler() && bulk.has_viscosity())
      {
        bulk.viscosity().vmult(u, w_start);
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
    statistics =
      step_solver.solve(rhs, u_start, w_start, w, accept_unconverged_loop);
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
      {
        // The Bathe composite scheme (doc/theory.md section 2.4). Sub-step
        // 1: the trapezoidal rule from t - k to t - k/2.
        const CompositeScheme &composite = parameters.time.composite;
        const TimeScheme       first     = composite.first_substep(k);
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
    else if (parameters.time.scheme == Parameters::Time::Scheme::sdirk)
      sdirk_step(record, t, k, accept_unconverged_loop);
    else
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
    if (parameters.time.adaptive)
      {
        record.adaptive_time = true;
        record.rejected      = rejected;
      }
    record.uniqueness_monitor = uniqueness_columns();
    record_errors(record, t);
    record.dofs     = discretization.dof_handler.n_dofs();
    record.cells    = discretization.triangulation.n_global_active_cells();
    energy_of_state = record.terms.energy.total(); // the step succeeded
    return record;
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

  template <int dim>
  void
  Simulator<dim>::check_input(const bool resume)
  {
    // The friction law: finite and >= 0 on [0, s_max], and not increasing
    // unless asked for (the convexification loop does not converge for an
    // increasing mu: README, "What can go wrong").
    if (friction_law)
      {
        const double      s_max = parameters.friction.maximum_slip_rate;
        const std::string name  = "Friction/" +
                                 PluginRegistry<FrictionLaw>::subsection(
                                   parameters.friction.law_name) +
                                 ": " + friction_law->description();
        const std::vector<double> s = FrictionLaw::sample_points(s_max);
        std::vector<double>       mu(s.size());
        for (unsigned int i = 0; i < s.size(); ++i)
          {
            mu[i] = friction_law->value(s[i]);
            if (!std::isfinite(mu[i]))
              throw CollectiveError(name +
                                    " is not finite at s = " + sig6(s[i]) +
                                    " m/s (" + scientific(mu[i]) + ").");
          }
        friction_law->check_nonnegative(s_max);
        double mu_max = 0; // the largest |mu| so far
        if (!parameters.friction.allow_velocity_strengthening)
          for (unsigned int i = 1; i < s.size(); ++i)
            {
              mu_max = std::max(mu_max, std::abs(mu[i - 1]));
              if (mu[i] - mu[i - 1] > 1e-9 * std::max(1., mu_max))
                throw CollectiveError(
                  name + " increases with the slip rate (mu(" + sig6(s[i - 1]) +
                  ") = " + sig6(mu[i - 1]) + ", mu(" + sig6(s[i]) +
                  ") = " + sig6(mu[i]) +
                  "): a velocity-strengthening law. The convexification "
                  "loop (doc/theory.md section 4) freezes mu at the last "
                  "slip rate; with an increasing mu a node then alternates "
                  "between stick and slip and the loop does not converge, "
                  "not even with the smallest time step. Set "
                  "Friction/Velocity strengthening = allow to run it "
                  "anyway (such steps are kept and reported: run_status "
                  "'completed with warnings').");
            }
      }

    // The functions of the scene, sampled where and when the run uses them.
    const double        T     = parameters.time.end_time;
    const double        k     = parameters.time.time_step;
    std::vector<double> times = {0., std::min(k, T), T};
    for (unsigned int i = 1; i < 16; ++i)
      times.push_back(T * i / 16.);
    check_collectively(comm,
                       scene.non_finite_value(discretization.triangulation,
                                              times,
                                              !resume));
  }



  template <int dim>
  Tensor<1, dim>
  Simulator<dim>::point_displacement(const Point<dim> &point) const
  {
    const Vector_t ghosted = discretization.expanded(u);
    Vector<double> value(dim);
    double         found = 0;
    try
      {
        const auto cell =
          GridTools::find_active_cell_around_point(discretization.mapping,
                                                   discretization.dof_handler,
                                                   point);
        if (cell.first->is_locally_owned())
          {
            VectorTools::point_value(discretization.mapping,
                                     discretization.dof_handler,
                                     ghosted,
                                     point,
                                     value);
            found = 1;
          }
      }
    catch (const std::exception &)
      {}
    const double n_found = Utilities::MPI::sum(found, comm);
    AssertThrow(n_found > 0, ExcMessage("The point is not inside the body."));
    Tensor<1, dim> result;
    for (unsigned int c = 0; c < dim; ++c)
      result[c] = Utilities::MPI::sum(found * value(c), comm) / n_found;
    return result;
  }



  template <int dim>
  typename Simulator<dim>::RestorePoint
  Simulator<dim>::restore_point() const
  {
    return {u, w, contact_state, energy_of_state};
  }


  template <int dim>
  void
  Simulator<dim>::restore(const RestorePoint &point)
  {
    u               = point.u;
    w               = point.w;
    contact_state   = point.contact;
    energy_of_state = point.energy;
  }


  template <int dim>
  void
  Simulator<dim>::write_contact_csv(OutputDirectory   &directory,
                                    const unsigned int n,
                                    const double       t) const
  {
    char name[64];
    std::snprintf(name, sizeof(name), "contact_%05u.csv", n);
    DynamicContact::write_contact_csv(directory,
                                      name,
                                      t,
                                      contact_boundary,
                                      contact_state.nodes,
                                      u,
                                      w,
                                      step_solver.has_friction(),
                                      comm);
  }


  template <int dim>
  void
  Simulator<dim>::write_vtu(VtuWriter<dim>    &writer,
                            const unsigned int n,
                            const double       t) const
  {
    writer.write(n,
                 t,
                 discretization,
                 material,
                 contact_boundary,
                 contact_state.nodes,
                 u,
                 w,
                 step_solver.has_friction());
  }


  template class Simulator<2>;
  template class Simulator<3>;
} // namespace DynamicContact
