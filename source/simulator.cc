#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/error_messages.h>
#include <dynamic_contact/error_norms.h>
#include <dynamic_contact/failure.h>
#include <dynamic_contact/simulator.h>
#include <dynamic_contact/timing.h>

#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <regex>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    /** Six significant digits: what regression output compares. */
    std::string
    sig6(const double x)
    {
      return scientific(x, 5);
    }

    std::string
    seconds(const double s)
    {
      std::ostringstream out;
      out << std::fixed << std::setprecision(s < 100 ? 1 : 0) << s << " s";
      return out.str();
    }

    /** A value that is not finite where a step needs it (collective). */
    class NonFiniteValue : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

  } // namespace


  template <int dim>
  Simulator<dim>::Simulator(const RunParameters &parameters,
                            ParameterHandler    &prm,
                            const MPI_Comm       comm)
    : parameters(parameters)
    , comm(comm)
    , screen_log(std::cout)
    , start_time(utc_timestamp())
    , pcout(screen_log, Utilities::MPI::this_mpi_process(comm) == 0)
    , details(screen_log,
              Utilities::MPI::this_mpi_process(comm) == 0 &&
                parameters.output.solver_details)
    , scene(parameters, prm)
    , material(parameters.material)
    , foundation(*parameters.foundation.law)
    , friction_law(parameters.friction.law)
    , timer(comm,
            pcout,
            // The table of the sections is printed by finish() (disjoint
            // sections, timing.h), not by TimerOutput.
            TimerOutput::never,
            TimerOutput::wall_times)
    , discretization(comm, parameters.finite_element.degree)
    , bulk(discretization, material)
    , step_solver(discretization,
                  bulk,
                  contact_boundary,
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
    , k_current(parameters.time.time_step)
  {
    output_directory =
      std::make_unique<OutputDirectory>(parameters.output.directory, comm);
    parameter_files   = ParameterFiles(prm, parameters);
    parameters_of_run = parameters_text(prm,
                                        parameters.geometry.type ==
                                            Parameters::Geometry::Type::gmsh ?
                                          parameters.geometry.mesh_file :
                                          std::string());

    // Fault injection (tests): see the members.
    if (const char *kill = std::getenv("DYNAMIC_CONTACT_KILL"))
      {
        std::istringstream in(kill);
        std::string        where, word;
        unsigned int       at = 0;
        in >> where;
        bool ok = false;
        if (where == "signal")
          {
            in >> injected_signal >> word >> signal_after_step;
            ok = in && word == "after-step" && injected_signal > 0;
            if (ok && in >> word)
              ok = word == "rank" && static_cast<bool>(in >> signal_rank);
          }
        else
          {
            in >> at;
            ok = in && (where == "after-step" || where == "in-checkpoint");
            if (ok)
              (where == "after-step" ? kill_after_step : kill_in_checkpoint) =
                at;
          }
        AssertThrow(ok,
                    ExcMessage("The environment variable DYNAMIC_CONTACT_KILL "
                               "(fault injection for tests) must read "
                               "'after-step N', 'in-checkpoint N' or 'signal "
                               "S after-step N [rank R]', not '" +
                               std::string(kill) + "'."));
      }
    if (const char *fail = std::getenv("DYNAMIC_CONTACT_FAIL"))
      {
        std::istringstream in(fail);
        std::string        word;
        in >> word >> fail_after_step;
        bool ok = in && word == "after-step";
        if (ok && in >> word)
          ok = word == "rank" && static_cast<bool>(in >> fail_rank);
        AssertThrow(ok,
                    ExcMessage("The environment variable DYNAMIC_CONTACT_FAIL "
                               "(fault injection for tests) must read "
                               "'after-step N [rank R]', not '" +
                               std::string(fail) + "'."));
      }
  }


  template <int dim>
  Simulator<dim>::~Simulator()
  {
    forget_timer(timer);
  }


  template <int dim>
  void
  Simulator<dim>::setup_dofs()
  {
    TimerSection t(timer, "Setup: DoFs and Gamma_3");
    discretization.setup_dofs(parameters.boundary_conditions);
    contact_boundary.reinit(discretization,
                            parameters.boundary_conditions.contact,
                            scene.initial_gap());
    for (auto *v :
         {&u, &w, &u_old, &w_old, &u_bar, &w_bar, &load, &rhs, &scratch})
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
  Vector_t
  Simulator<dim>::friction_field(const bool per_weight) const
  {
    Vector_t field;
    discretization.reinit_owned(field);
    const auto                          &nodes  = contact_boundary.nodes();
    const auto                          &lambda = step_solver.friction_forces();
    std::vector<types::global_dof_index> indices;
    std::vector<double>                  values;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      for (unsigned int c = 0; c < dim; ++c)
        {
          indices.push_back(nodes[i].dofs[c]);
          values.push_back(i < lambda.size() ?
                             lambda[i][c] /
                               (per_weight ? nodes[i].weight : 1.) :
                             0.);
        }
    field.set(indices, values);
    field.compress(VectorOperation::insert);
    return field;
  }


  template <int dim>
  void
  Simulator<dim>::set_friction_from_field(const Vector_t &field,
                                          const bool      per_weight)
  {
    const auto                 &nodes = contact_boundary.nodes();
    std::vector<Tensor<1, dim>> lambda(nodes.size());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        Tensor<1, dim> raw;
        for (unsigned int c = 0; c < dim; ++c)
          raw[c] = field[nodes[i].dofs[c]];
        // A traction interpolated onto a new mesh: its tangential part,
        // times the new weight; a nodal force of the same mesh: as it was.
        lambda[i] =
          per_weight ? nodes[i].weight * nodes[i].tangential(raw) : raw;
      }
    step_solver.set_friction_forces(lambda);
  }


  template <int dim>
  void
  Simulator<dim>::checkpoint()
  {
    TimerSection scope(timer, "Checkpoint");
    RunState     state;
    state.step                     = step;
    state.time                     = current_time;
    state.time_step                = k_current;
    state.good_steps_since_cutback = good_steps_since_cutback;
    state.max_relative_defect      = max_relative_defect;
    state.min_dissipation          = min_dissipation;
    state.total_newton             = total_newton;
    state.unconverged_steps        = unconverged_steps;
    state.worst_unconverged        = worst_unconverged;
    state.vtu_records              = vtu_writer->get_records();
    // The friction forces exactly, as a field of nodal forces saved with the
    // mesh (any number of processes can load it).
    Vector_t friction = friction_field(false);
    write_checkpoint(*output_directory,
                     discretization,
                     {&u, &w, &friction},
                     state,
                     parameters_of_run,
                     parameters.checkpoint.keep,
                     [this]() {
                       if (kill_in_checkpoint == step)
                         std::raise(SIGKILL);
                     });
    last_checkpoint_step = step;
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
        Vector_t   traction = friction_field(true);
        const auto before   = mesh_adaptation.fingerprint();
        refine_and_transfer(discretization, {&u, &w, &traction}, [this]() {
          setup_dofs();
        });
        set_friction_from_field(traction, true); // on the new nodes
        changed = true;
        if (mesh_adaptation.fingerprint() == before)
          break;
      }
    if (changed)
      {
        // setup_operators() resets the step solver; the nodes stay.
        const auto lambda = step_solver.friction_forces();
        setup_operators();
        step_solver.set_friction_forces(lambda);
      }
    return energy_now() - energy_before;
  }



  template <int dim>
  void
  Simulator<dim>::write_status(const std::string &status)
  {
    collectively(comm, [&]() { output_directory->write_status(status); });
    took_over = true;
  }


  template <int dim>
  void
  Simulator<dim>::write_provenance(const bool resume)
  {
    collectively(comm, [&]() {
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      screen_log.open(*output_directory, resume);
      parameter_files.write(*output_directory);
    });
  }


  template <int dim>
  void
  Simulator<dim>::write_log(const bool close)
  {
    collectively(comm, [&]() {
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      if (close)
        screen_log.close();
      else
        screen_log.write_pending();
    });
  }


  template <int dim>
  void
  Simulator<dim>::print_header() const
  {
    pcout << "dynamic-contact: " << dim << "D, Q" << discretization.fe.degree
          << " elements, "
          << discretization.triangulation.n_global_active_cells() << " cells, "
          << discretization.dof_handler.n_dofs() << " DoFs, "
          << contact_boundary.n_global_nodes() << " contact nodes";
    if (mesh_adaptation.enabled())
      pcout << " (adaptive)";
    pcout << '\n';
    // Which program ran, where and when: on the screen with the timings
    // (output that differs from run to run), in log.txt always.
    const std::string provenance =
      "  " +
      provenance_line(Utilities::MPI::n_mpi_processes(comm), start_time) + "\n";
    if (parameters.output.print_timings)
      pcout << provenance;
    else if (Utilities::MPI::this_mpi_process(comm) == 0)
      screen_log.log_only(provenance);
    if (parameters.output.print_timings)
      pcout << "  MPI processes: " << Utilities::MPI::n_mpi_processes(comm)
            << ", parameter file: " << parameters.parameter_file
            << ", contact solver: " << step_solver.solver_name() << '\n';
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
    {
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

    if (!std::isfinite(w.l2_norm()))
      throw StepFailure("the solution is not finite");

    scheme.advance_displacement(u, u_start, w, w_start);

    TimerSection scope(timer, "Step: energy and force balance");
    terms = energy_balance.step_terms(u_start,
                                      w_start,
                                      u,
                                      w,
                                      load,
                                      scheme,
                                      step_solver.node_states(),
                                      start_energy);
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
                               const unsigned int cutbacks)
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

    const bool accept_unconverged_loop = !can_cut_back(k);
    // The (sub-)step that ends at t and the state it starts from: the force
    // balance is that of its equation.
    TimeScheme      last(k, parameters.time.theta());
    const Vector_t *u_start = &u_old, *w_start = &w_old;
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
        const Energy bar_energy = energy_balance.energy(u_bar, w_bar);
        last                    = composite.second_substep(k);
        u_start                 = &u_bar;
        w_start                 = &w_bar;
        EnergyBalanceTerms second_terms;
        solve_substep(last,
                      t,
                      u_bar,
                      w_bar,
                      bar_energy.total(),
                      accept_unconverged_loop,
                      record.statistics,
                      second_terms);
        record.statistics.add_work(first_statistics);
        last_newton_residual =
          std::max(first_statistics.residual, record.statistics.residual);
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
      }
    else
      solve_substep(last,
                    t,
                    u_old,
                    w_old,
                    record.previous_energy,
                    accept_unconverged_loop,
                    record.statistics,
                    record.terms);

    if (parameters.time.adaptive)
      {
        record.adaptive_time = true;
        record.time_error    = time_error_estimate(k);
        record.rejected      = rejected_this_step;
        last_time_error =
          record.time_error / parameters.time.adaptive_tolerance;
      }

    TimerSection scope(timer, "Step: energy and force balance");
    const auto  &nodes = contact_boundary.nodes();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        record.normal_force +=
          step_solver.node_states()[i].normal_force(nodes[i].weight);
        record.tangential_force +=
          step_solver.node_states()[i].friction_force.norm();
      }
    record.normal_force = Utilities::MPI::sum(record.normal_force, comm);
    record.tangential_force =
      Utilities::MPI::sum(record.tangential_force, comm);
    {
      const Vector_t u_ghosted     = discretization.expanded(u),
                     w_ghosted     = discretization.expanded(w),
                     w_old_ghosted = discretization.expanded(*w_start);
      // The stress of the scheme's equation: at u_theta, w_theta.
      scratch = u;
      last.weigh(scratch, *u_start);
      const Vector_t u_theta = discretization.expanded(scratch);
      scratch                = w;
      last.weigh(scratch, *w_start);
      const Vector_t w_theta = discretization.expanded(scratch);
      record.forces          = force_balance.compute(contact_boundary,
                                            step_solver.node_states(),
                                            t,
                                            last,
                                            u_theta,
                                            w_theta,
                                            w_ghosted,
                                            w_old_ghosted);
      if (scene.has_exact_solution())
        {
          record.has_errors = true;
          record.errors     = compute_errors(
            discretization, material, scene, t, u_ghosted, w_ghosted);
        }
    }
    record.dofs     = discretization.dof_handler.n_dofs();
    record.cells    = discretization.triangulation.n_global_active_cells();
    energy_of_state = record.terms.energy.total(); // the step succeeded
    return record;
  }


  template <int dim>
  void
  Simulator<dim>::output_results(
    const unsigned int                        n,
    const double                              t,
    const bool                                contact_csv,
    const bool                                vtu,
    const std::vector<ContactNodeState<dim>> *states)
  {
    const auto &node_states =
      states != nullptr ? *states : step_solver.node_states();
    TimerSection scope(timer, "Output");
    char         name[64];
    std::snprintf(name, sizeof(name), "contact_%05u.csv", n);
    if (contact_csv)
      write_contact_csv(*output_directory,
                        name,
                        t,
                        contact_boundary,
                        node_states,
                        u,
                        w,
                        step_solver.has_friction(),
                        comm);
    if (vtu)
      {
        const auto start = std::chrono::steady_clock::now();
        vtu_writer->write(n,
                          t,
                          discretization,
                          material,
                          contact_boundary,
                          node_states,
                          u,
                          w,
                          step_solver.has_friction());
        vtu_seconds += std::chrono::duration<double>(
                         std::chrono::steady_clock::now() - start)
                         .count();
        ++vtu_files;
      }
  }


  template <int dim>
  bool
  Simulator<dim>::at_output_time(const double t, const double k) const
  {
    const double allowance = 1e-12 * std::max(std::abs(t), k);
    for (const double t_out : parameters.output.output_times)
      if (t_out <= t + allowance && t_out > t - k + allowance)
        return true;
    return false;
  }


  template <int dim>
  bool
  Simulator<dim>::vtu_due(const unsigned int n,
                          const double       t,
                          const double       k,
                          const bool         last) const
  {
    // Output/Output times and the last step, and every N steps, unless
    // switched off.
    const unsigned int every = parameters.output.vtu_every;
    return parameters.output.write_vtu &&
           (last || at_output_time(t, k) || (every > 0 && n % every == 0));
  }


  template <int dim>
  unsigned int
  Simulator<dim>::vtu_files_left() const
  {
    // The schedule of the steps to come at the nominal time step.
    const unsigned int last    = step + remaining_steps();
    const double       k0      = parameters.time.time_step;
    unsigned int       n_files = 0;
    for (unsigned int n = step + 1; n <= last; ++n)
      n_files += vtu_due(n, current_time + (n - step) * k0, k0, n == last);
    return n_files;
  }


  template <int dim>
  void
  Simulator<dim>::print_progress(const StepRecord<dim> &record) const
  {
    // Output/Print timings and Print iteration counts = false leave out
    // what differs from run to run: the times, and the iteration counts (on
    // several processes they follow the round-off of the parallel direct
    // solver near the stopping thresholds: two runs of tests/paper_small on
    // 2 processes differed by one Newton iteration in 3 of 16 progress
    // lines).
    pcout << "step " << std::setw(5) << step << '/' << step + remaining_steps()
          << "  t = " << sig6(record.time);
    if (record.time_step != parameters.time.time_step || record.cutbacks > 0)
      pcout << "  k = " << sig6(record.time_step) << " (" << record.cutbacks
            << " cut-backs)";
    const auto &statistics = record.statistics;
    if (parameters.output.print_iteration_counts)
      {
        pcout << "  Newton " << statistics.newton_iterations;
        if (step_solver.has_friction())
          pcout << "  convexification "
                << statistics.convexification_iterations;
      }
    pcout << "  contact " << statistics.n_contact;
    if (mesh_adaptation.enabled())
      pcout << "  cells " << record.cells;
    pcout << "  N = " << sig6(record.normal_force)
          << "  E = " << sig6(record.terms.energy.total());
    if (parameters.output.print_timings)
      {
        const auto   now = std::chrono::steady_clock::now();
        const double elapsed =
          std::chrono::duration<double>(now - wall_start).count();
        pcout << "  (" << seconds(elapsed);
        // The wall time per simulated second since the end of the first
        // step of this run (set-up and the first step's one-off work, the
        // factorization and the first compliance columns, left out), times
        // the simulated time left; VTU files (seconds each on large meshes,
        // every few steps) apart: those still to come at their mean cost.
        if (stepping_start)
          {
            const double stepping =
              std::chrono::duration<double>(now - stepping_start->first)
                .count() -
              (vtu_seconds - vtu_seconds_at_start);
            const double simulated = current_time - stepping_start->second;
            if (simulated > 0)
              pcout << ", ~"
                    << seconds(std::max(0., stepping) / simulated *
                                 (parameters.time.end_time - current_time) +
                               (vtu_files > 0 ? vtu_seconds / vtu_files : 0.) *
                                 vtu_files_left())
                    << " left";
          }
        pcout << ")";
      }
    pcout << std::endl;
  }


  template <int dim>
  void
  Simulator<dim>::check_resources(const double n_coarse_cells) const
  {
    // Estimates for the mesh after Geometry/Global refinements (an
    // adaptive mesh may grow beyond it; Mesh refinement/Cell budget bounds
    // it). DoFs as on a box; memory: the four sparse matrices (M, B, A, K0)
    // and at least as much for the factorization of K0, 12 bytes per entry
    // (value and column index): a lower bound, so that no scene that fits
    // is refused.
    const double refinements = parameters.geometry.global_refinements;
    const double cells       = n_coarse_cells * std::pow(2., dim * refinements);
    const double p           = parameters.finite_element.degree;
    const double dofs = dim * std::pow(p * std::pow(cells, 1. / dim) + 1, dim);
    const double entries_per_row = dim * std::pow(2 * p + 1, dim);
    const double bytes           = 5 * 12 * entries_per_row * dofs;

    // The memory available: MemAvailable of every host of the run, once.
    double available = 0;
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string   key;
      double        kb = 0;
      std::string   unit;
      while (meminfo >> key >> kb >> unit)
        if (key == "MemAvailable:")
          {
            available = kb * 1024;
            break;
          }
      if (available == 0)
        available = static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) *
                    static_cast<double>(sysconf(_SC_PAGESIZE));
    }
    char host[MPI_MAX_PROCESSOR_NAME] = {};
    int  length                       = 0;
    MPI_Get_processor_name(host, &length);
    std::map<std::string, double> hosts;
    for (const auto &[name, a] : Utilities::MPI::all_gather(
           comm, std::make_pair(std::string(host, length), available)))
      hosts[name] = std::max(hosts[name], a);
    double total = 0;
    for (const auto &h : hosts)
      total += h.second;

    const auto giga = [](const double b) {
      std::ostringstream s;
      s << std::setprecision(3) << b / 1e9 << " GB";
      return s.str();
    };
    const std::string estimate =
      "about " + scientific(cells, 1) + " cells and " + scientific(dofs, 1) +
      " DoFs (Geometry: " + scientific(n_coarse_cells, 1) + " coarse cells, " +
      std::to_string(parameters.geometry.global_refinements) +
      " global refinements; Q" +
      std::to_string(parameters.finite_element.degree) + ")";
    const std::string fix =
      " Reduce Geometry/Repetitions, Geometry/Global refinements or Finite "
      "element/Polynomial degree.";
    // deal.II (this build: 32-bit indices) counts cells and DoFs in 32 bits.
    const double index_limit = 4294967295.;
    if (cells >= index_limit || dofs >= index_limit)
      throw CollectiveError("The scene is too large: " + estimate +
                            ", more than this build of deal.II can count "
                            "(4.3e+09)." +
                            fix);
    if (bytes > total)
      throw CollectiveError(
        "The scene does not fit into memory: " + estimate + " need at least " +
        giga(bytes) + " for the matrices alone, and " + giga(total) +
        " are available on the " + std::to_string(hosts.size()) + " host" +
        (hosts.size() > 1 ? "s" : "") + " of this run." + fix);
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
  void
  Simulator<dim>::stop_with_last_good_state(const std::string &message)
  {
    u = u_old;
    w = w_old;
    output_results(step,
                   current_time,
                   true,
                   vtu_writer != nullptr && parameters.output.write_vtu,
                   &last_good_states);
    checkpoint();
    std::string m = message;
    while (!m.empty() && m.back() == '.')
      m.pop_back();
    throw CollectiveError(m + ". The last good state (step " +
                          std::to_string(step) + ") is written to '" +
                          parameters.output.directory + "'.");
  }


  template <int dim>
  void
  Simulator<dim>::initialize(const bool resume)
  {
    wall_start = std::chrono::steady_clock::now();
    // Everything that can be wrong with the input is checked before any
    // result is written (the scene's functions and boundary ids when the
    // mesh is made), and the size of the scene before it is allocated.
    const bool rectangle =
      parameters.geometry.type == Parameters::Geometry::Type::rectangle;
    if (rectangle)
      {
        double n = 1;
        for (const unsigned int r : parameters.geometry.repetitions)
          n *= r;
        check_resources(n);
      }
    {
      TimerSection t(timer, "Setup: mesh");
      scene.create_mesh(discretization.triangulation, false);
      if (!rectangle)
        check_resources(discretization.triangulation.n_cells(0));
    }
    if (resume)
      {
        resume_from_checkpoint();
        return;
      }

    discretization.triangulation.refine_global(
      parameters.geometry.global_refinements);
    check_input(false);
    setup_dofs();
    if (mesh_adaptation.enabled())
      refine_initial_mesh();
    setup_operators();
    set_initial_conditions();
    {
      const double norm = u.l2_norm() + w.l2_norm();
      if (!std::isfinite(norm))
        throw CollectiveError("Initial conditions: the interpolated initial "
                              "state is not finite.");
    }

    // --validate: the scene would start; nothing is written.
    if (validate_only)
      return;

    // The directory is ours (locked, no foreign results), the results of
    // an earlier run in it are gone.
    output_directory->open(false);
    write_status("running");
    write_provenance(false);
    time_series_writer =
      std::make_unique<TimeSeriesWriter>(*output_directory, comm);
    vtu_writer =
      std::make_unique<VtuWriter<dim>>(*output_directory,
                                       comm,
                                       parameters.boundary_conditions.contact,
                                       parameters.output.vtu_subdivisions);

    print_header();

    StepRecord<dim> record;
    if (scene.has_exact_solution())
      {
        const Vector_t u_ghosted = discretization.expanded(u),
                       w_ghosted = discretization.expanded(w);
        record.has_errors        = true;
        record.errors            = compute_errors(
          discretization, material, scene, 0., u_ghosted, w_ghosted);
      }
    record.terms.energy    = energy_balance.energy(u, w);
    record.previous_energy = record.terms.energy.total();
    energy_of_state        = record.previous_energy;
    record.dofs            = discretization.dof_handler.n_dofs();
    record.cells         = discretization.triangulation.n_global_active_cells();
    record.adaptive_time = parameters.time.adaptive; // the columns, 0
    time_series_writer->write(record.row());
    rows.push_back(record);
    output_results(0, 0., true, parameters.output.write_vtu);
  }


  template <int dim>
  std::string
  Simulator<dim>::validate()
  {
    validate_only = true;
    initialize(false);
    timer.disable_output(); // set-up times of a run that does not run
    std::ostringstream summary;
    summary << dim << "D, Q" << discretization.fe.degree << " elements, "
            << discretization.triangulation.n_global_active_cells()
            << " cells, " << discretization.dof_handler.n_dofs() << " DoFs, "
            << contact_boundary.n_global_nodes() << " contact nodes";
    return summary.str();
  }


  template <int dim>
  void
  Simulator<dim>::resume_from_checkpoint()
  {
    const std::string &directory = parameters.output.directory;
    check_input(true);
    // The directory: ours, and no other run in it.
    output_directory->open(true);

    // The newest checkpoint whose files match its manifest; damaged ones
    // are named and passed over.
    const auto  checkpoints = list_checkpoints(directory, comm);
    std::string latest;
    std::string damaged;
    for (const auto &name : checkpoints)
      {
        const std::string problem =
          verify_checkpoint(directory + "/" + name, comm);
        if (problem.empty())
          {
            latest = directory + "/" + name;
            break;
          }
        damaged += (damaged.empty() ? "" : "; ") + name + ": " + problem;
        pcout << "Warning: the checkpoint " << directory << "/" << name
              << " is damaged: " << problem << "; it is not used." << std::endl;
      }
    if (checkpoints.empty())
      throw CollectiveError("--resume: there is no complete checkpoint in "
                            "Output/Directory '" +
                            directory +
                            "' (the interrupted run needs Checkpoint/Every "
                            "> 0).");
    if (latest.empty())
      throw CollectiveError(
        "--resume: no checkpoint in Output/Directory '" + directory +
        "' can be used, every one is "
        "damaged (" +
        damaged + "). Nothing was changed; start a new run.");

    // The same problem, or a refusal that says what differs.
    const auto differences =
      scene_differences(read_checkpoint_parameters(latest, comm),
                        parameters_of_run);
    if (!differences.empty())
      {
        std::string list;
        for (const auto &d : differences)
          list += (list.empty() ? "" : "; ") + d;
        throw CollectiveError(
          "--resume: the scene differs from that of the checkpoint '" + latest +
          "' in " + std::to_string(differences.size()) +
          (differences.size() == 1 ? " entry: " : " entries: ") + list +
          ". A resumed run continues the same problem; only Time/End time "
          "(later), Time/Time step, Time/Minimum time step, Solver, Output, "
          "Checkpoint and the convexification loop's settings may change "
          "(README, 'What can go wrong'). Nothing was changed.");
      }
    const std::string old_parameters = read_checkpoint_parameters(latest, comm);
    const RunState    state          = read_run_state(latest, comm);
    const double      T              = parameters.time.end_time;
    const double      k0             = parameters.time.time_step;
    if (T < state.time - 1e-9 * k0)
      throw CollectiveError("--resume: Time/End time = " + sig6(T) +
                            " s is before the time of the checkpoint '" +
                            latest + "' (t = " + sig6(state.time) +
                            " s). Nothing was changed.");
    const std::string      series  = directory + "/time_series.csv";
    const TimeSeriesOnDisk on_disk = read_time_series(series, state.step, comm);
    // The end summary covers the steps before the checkpoint too (rank 0
    // holds the rows; only rank 0 prints).
    {
      const auto lines = Utilities::split_string_list(on_disk.kept, '\n');
      std::vector<std::string> header;
      for (const auto &line : lines)
        {
          const auto values = Utilities::split_string_list(line, ',');
          if (header.empty())
            {
              header = values;
              continue;
            }
          if (values.size() != header.size() || values[0] == "0")
            continue; // row 0 is the initial state
          // The counts of the end summary, by column name.
          const auto value = [&](const std::string &name) {
            const auto c = std::find(header.begin(), header.end(), name);
            return c == header.end() ?
                     0. :
                     std::strtod(values[c - header.begin()].c_str(), nullptr);
          };
          account_for(static_cast<unsigned int>(value("cutbacks")),
                      static_cast<unsigned int>(
                        value("convexification_iterations")),
                      value("coefficient_residual"));
        }
    }
    if (T < on_disk.last_time - 1e-9 * k0)
      throw CollectiveError(
        "--resume: Time/End time = " + sig6(T) +
        " s is before the last row already written to " + series + " (step " +
        std::to_string(on_disk.last_step) + ", t = " + sig6(on_disk.last_time) +
        " s): a resumed run does not delete results. Give an end time of at "
        "least " +
        sig6(on_disk.last_time) +
        " s, or start a new run. Nothing was "
        "changed.");

    // Load the mesh and the fields.
    Vector_t friction;
    load_checkpoint<dim>(latest, discretization, {&u, &w, &friction}, [this]() {
      setup_dofs();
    });
    setup_operators();
    set_friction_from_field(friction, false);
    step                     = state.step;
    current_time             = state.time;
    k_current                = state.time_step;
    good_steps_since_cutback = state.good_steps_since_cutback;
    max_relative_defect      = state.max_relative_defect;
    min_dissipation          = state.min_dissipation;
    total_newton             = state.total_newton;
    unconverged_steps        = state.unconverged_steps;
    worst_unconverged        = state.worst_unconverged;
    last_checkpoint_step     = step;

    // A new Time/Time step is honoured from the checkpoint on; otherwise
    // the cut-back state goes on (within the new minimum).
    const std::string old_step =
      parameter_value(old_parameters, "Time/Time step");
    const bool step_changed =
      !old_step.empty() && std::strtod(old_step.c_str(), nullptr) != k0;
    if (step_changed)
      {
        k_current                = k0;
        good_steps_since_cutback = 0;
      }
    else
      k_current = std::max(std::min(k_current,
                                    parameters.time.adaptive ?
                                      parameters.time.maximum_time_step :
                                      k0),
                           parameters.time.minimum_time_step);

    // Take over: the rows and the files of the interrupted continuation
    // after the checkpoint are replaced by this run's.
    write_status("running");
    collectively(comm, [&]() {
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      output_directory->claim("time_series.csv");
      replace_file(series, on_disk.kept, true);
      static const std::regex result(
        R"((contact|solution|contact_surface)_([0-9]{5,})\.(csv|pvtu|[0-9]+\.vtu))");
      std::vector<std::string> superseded;
      for (const auto &name : output_directory->owned())
        {
          std::smatch m;
          if (std::regex_match(name, m, result) &&
              std::stoul(m[2].str()) > step)
            superseded.push_back(name);
        }
      output_directory->remove(superseded);
    });
    time_series_writer =
      std::make_unique<TimeSeriesWriter>(*output_directory, comm, true);
    vtu_writer =
      std::make_unique<VtuWriter<dim>>(*output_directory,
                                       comm,
                                       parameters.boundary_conditions.contact,
                                       parameters.output.vtu_subdivisions);
    vtu_writer->set_records(state.vtu_records);
    // The indexes list the VTU files up to the checkpoint only (none: they
    // are removed).
    vtu_writer->write_index();
    write_provenance(true);
    print_header();
    pcout << "  resumed from " << latest << " (step " << step
          << ", t = " << sig6(current_time) << " s)" << std::endl;
    if (step_changed)
      pcout << "  Time/Time step changed from " << old_step << " to "
            << sig6(k0) << " s: the run goes on with the new time step"
            << std::endl;
  }


  template <int dim>
  unsigned int
  Simulator<dim>::remaining_steps() const
  {
    const double k0 = parameters.time.time_step;
    return static_cast<unsigned int>(
      std::ceil((parameters.time.end_time - current_time) / k0 - 1e-9));
  }


  template <int dim>
  bool
  Simulator<dim>::can_cut_back(const double k) const
  {
    return k / 2 >= parameters.time.minimum_time_step * (1 - 1e-12);
  }


  template <int dim>
  bool
  Simulator<dim>::advance()
  {
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    if (current_time >= T - 1e-9 * k0)
      return false;
    // A stop signal on any process stops every one, before the next step.
    stopping_signal = signal_to_stop(comm);
    if (stopping_signal != 0)
      return false;

    double remesh_energy_change = 0;
    if (mesh_adaptation.due(step + 1))
      remesh_energy_change = adapt_mesh(
        current_time,
        std::min(T, current_time + mesh_adaptation.lookahead_steps() * k0),
        k0);

    // A step the solver cannot solve is retried from the last good state
    // with half the time step, down to Time/Minimum time step. Of that
    // state, do_time_step keeps u and w as u_old and w_old (its first
    // statements; it throws only after them); the friction forces are kept
    // here.
    const auto lambda_good   = step_solver.friction_forces();
    last_good_states         = step_solver.node_states();
    unsigned int    cutbacks = 0;
    double          k        = 0;
    StepRecord<dim> record;
    const bool      adaptive = parameters.time.adaptive;
    // Time/Adaptive: the k after this step, from its error estimate.
    double k_next      = k_current;
    rejected_this_step = 0;
    for (;;)
      {
        k = std::min(k_current, T - current_time);
        if (adaptive)
          {
            // Steps end exactly at the Output times and at T; a target
            // less than two steps away is reached in two equal ones (no
            // sliver of a step).
            const double        k_wanted = k_current;
            std::vector<double> targets  = parameters.output.output_times;
            targets.push_back(T);
            for (const double target : targets)
              {
                const double left = target - current_time;
                if (left > 1e-9 * k_wanted && left < k + 1e-9 * k_wanted)
                  k = left;
                else if (left > 1e-9 * k_wanted && left < 2 * k)
                  k = std::min(k, left / 2);
              }
          }
        if (T - current_time - k < 1e-9 * k0) // no sliver of a last step
          k = T - current_time;
        try
          {
            record = do_time_step(
              step + 1, current_time + k, k, remesh_energy_change, cutbacks);
            // Nothing that is not finite reaches a file.
            std::string bad;
            for (const auto &[name, value] : record.row().columns())
              if (value.find("nan") != std::string::npos ||
                  value.find("inf") != std::string::npos)
                bad += (bad.empty() ? "" : ", ") + name;
            bad = collective_message(comm, bad);
            if (!bad.empty())
              throw NonFiniteValue("step " + std::to_string(step + 1) +
                                   " (t = " + sig6(current_time + k) +
                                   " s) produced values that are not "
                                   "finite: " +
                                   bad);
            if (adaptive)
              {
                // The usual controller: the local error of a scheme of
                // order p scales like k^(p+1).
                const double order =
                  parameters.time.scheme == Parameters::Time::Scheme::bathe ?
                    3 :
                    2;
                const double factor =
                  last_time_error > 0 ?
                    std::min(2.,
                             std::max(0.2,
                                      0.9 * std::pow(last_time_error,
                                                     -1. / order))) :
                    2.;
                const double k_min = parameters.time.minimum_time_step;
                // k on the grid Time step * 2^j (rounded down): a new k
                // costs new factorizations of K0, so k changes only by
                // factors of 2 and stays while the estimate allows it.
                const auto on_grid = [k0](const double x) {
                  return k0 *
                         std::pow(2., std::floor(std::log2(x / k0) + 1e-9));
                };
                if (last_time_error > 1 && k > k_min * (1 + 1e-12))
                  {
                    // Rejected: again from the last good state.
                    u = u_old;
                    w = w_old;
                    step_solver.set_friction_forces(lambda_good);
                    energy_of_state.reset();
                    k_current = std::max(k_min, on_grid(k * factor));
                    ++rejected_this_step;
                    continue;
                  }
                // A step shortened to end at an Output time does not shrink
                // the next one.
                k_next = (k < k_current && factor >= 1) ? k_current :
                                                          on_grid(k * factor);
                k_next = std::min(parameters.time.maximum_time_step,
                                  std::max(k_min, k_next));
              }
            break;
          }
        catch (const NonFiniteValue &e)
          {
            step_solver.set_friction_forces(lambda_good);
            stop_with_last_good_state(e.what());
          }
        catch (const StepFailure &failure)
          {
            u = u_old;
            w = w_old;
            step_solver.set_friction_forces(lambda_good);
            if (!can_cut_back(k))
              // Stop, with the last good state written out (fields and a
              // checkpoint to continue from with other settings).
              stop_with_last_good_state(
                "step " + std::to_string(step + 1) +
                " (from t = " + sig6(current_time) +
                " s) could not be solved even with the minimum time step "
                "(Time/Minimum time step = " +
                sig6(parameters.time.minimum_time_step) +
                " s): " + failure.what());
            k_current = k / 2;
            ++cutbacks;
            good_steps_since_cutback = 0;
            pcout << "  step " << step + 1 << " (t = " << sig6(current_time)
                  << " s): " << failure.what()
                  << "; retrying with k = " << sig6(k_current) << std::endl;
          }
      }
    ++step;
    current_time += k;
    // Back on the nominal grid (and on T) up to round-off.
    const double n_nominal = std::round(current_time / k0);
    if (std::abs(current_time - n_nominal * k0) < 1e-9 * k0)
      current_time = std::min(n_nominal * k0, T);
    if (std::abs(current_time - T) < 1e-9 * k0)
      current_time = T;
    // The time step grows back after good steps (Time/Adaptive: it follows
    // the error estimate).
    if (adaptive)
      k_current = k_next;
    else if (cutbacks == 0 && k_current < k0 && ++good_steps_since_cutback >= 3)
      {
        k_current                = std::min(2 * k_current, k0);
        good_steps_since_cutback = 0;
      }
    const double t = current_time;
    // The estimate of the time left starts after the first step of this
    // run (whose one-off work would inflate it).
    if (!stepping_start)
      {
        stepping_start.emplace(std::chrono::steady_clock::now(), current_time);
        vtu_seconds_at_start = vtu_seconds;
      }

    time_series_writer->write(record.row());
    rows.push_back(record);
    const auto &statistics = record.statistics;
    account_for(record.cutbacks,
                statistics.convexification_iterations,
                statistics.coefficient_residual);
    if (last_newton_residual > parameters.solver.newton_tolerance)
      ++stagnated_steps;

    max_relative_defect =
      std::max(max_relative_defect, record.relative_energy_defect());
    min_dissipation =
      std::min(min_dissipation, record.relative_min_dissipation());
    total_newton += statistics.newton_iterations;

    if (!statistics.convexification_converged)
      {
        ++unconverged_steps;
        worst_unconverged =
          std::max(worst_unconverged, statistics.coefficient_residual);
        pcout << "Warning: step " << step << " (t = " << sig6(t)
              << "): the convexification loop reached Friction/Maximum "
                 "convexification iterations = "
              << parameters.friction.max_convexification_iterations
              << " at the minimum time step without converging; kept, with "
                 "max |mu_i - mu(|w_tau,i|)| = "
              << sig6(statistics.coefficient_residual) << std::endl;
      }

    const bool last = (current_time >= T - 1e-9 * k0);
    // An output time is due at the first step reaching it; the VTU files
    // on the same schedule with their own cadence, unless switched off.
    const unsigned int csv_every = parameters.output.output_every;
    output_results(step,
                   t,
                   last || at_output_time(t, k) ||
                     (csv_every > 0 && step % csv_every == 0),
                   vtu_due(step, t, k, last));

    const unsigned int progress = parameters.output.progress_every;
    if (progress > 0 && (step % progress == 0 || last))
      print_progress(record);
    if (parameters.checkpoint.every > 0 &&
        step % parameters.checkpoint.every == 0 && !last)
      checkpoint();
    write_log();
    if (kill_after_step == step)
      std::raise(SIGKILL);
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    if (signal_after_step == step && signal_rank == rank)
      std::raise(injected_signal);
    if (fail_after_step == step && fail_rank == rank)
      throw std::runtime_error("injected failure after step " +
                               std::to_string(step) +
                               " (DYNAMIC_CONTACT_FAIL)");
    return true;
  }


  template <int dim>
  void
  Simulator<dim>::account_for(const unsigned int cutbacks,
                              const unsigned int convexification_iterations,
                              const double       coefficient_residual)
  {
    total_cutbacks += cutbacks;
    total_convexification += convexification_iterations;
    max_coefficient_residual =
      std::max(max_coefficient_residual, coefficient_residual);
  }


  template <int dim>
  void
  Simulator<dim>::finish()
  {
    time_series_writer->close();
    const bool friction = step_solver.has_friction();
    pcout << "Completed " << step << " steps (t = " << sig6(current_time)
          << " s)";
    if (parameters.output.print_iteration_counts) // see print_progress()
      {
        pcout << ", " << total_newton << " Newton iterations (mean "
              << std::fixed << std::setprecision(2)
              << static_cast<double>(total_newton) / std::max(step, 1u)
              << std::defaultfloat << " per step)";
        if (friction)
          pcout << ", " << total_convexification << " convexification passes";
      }
    pcout << ".\n";
    const bool balance     = max_relative_defect < 1e-8;
    const bool dissipation = min_dissipation >= -EnergyBalanceTerms::roundoff;
    pcout << "  energy balance: max relative defect "
          << (balance ? "below 1e-8" :
                        "ABOVE 1e-8 (" + sig6(max_relative_defect) + ")")
          << ", every dissipation term >= 0: "
          << (dissipation ? "yes" :
                            "NO (" + sig6(min_dissipation) + " of the energy)")
          << std::endl;
    // The summary: what a user checks before trusting the results.
    pcout << "Summary: results in " << parameters.output.directory << "/\n"
          << "  time step cut-backs: " << total_cutbacks
          << "; steps kept with an unconverged convexification loop: "
          << unconverged_steps
          << "; steps whose Newton iteration ended at stagnation (residual "
             "below the square root of Solver/Newton tolerance): "
          << stagnated_steps << "\n"
          << "  largest relative energy balance defect: "
          << scientific(max_relative_defect, 2);
    if (friction)
      pcout << "; largest friction-law residual max |mu_i - mu(|w_tau,i|)|: "
            << scientific(max_coefficient_residual, 2)
            << " (Friction/Coefficient tolerance "
            << parameters.friction.coefficient_tolerance << ")";
    pcout << std::endl;

    // An honest ending: completed, or completed with what did not hold.
    std::vector<std::string> warnings;
    if (unconverged_steps > 0)
      warnings.push_back(
        std::to_string(unconverged_steps) + " step" +
        (unconverged_steps > 1 ? "s" : "") +
        " kept with an unconverged convexification loop (max |mu_i - "
        "mu(|w_tau,i|)| = " +
        sig6(worst_unconverged) + " > Friction/Coefficient tolerance)");
    if (!balance)
      warnings.push_back("energy balance defect " + sig6(max_relative_defect) +
                         " > 1e-8");
    if (!dissipation)
      warnings.push_back("a dissipation term below zero (" +
                         sig6(min_dissipation) + " of the energy)");
    std::string status = "completed";
    if (!warnings.empty())
      {
        status += " with warnings: ";
        for (unsigned int i = 0; i < warnings.size(); ++i)
          status += (i ? "; " : "") + warnings[i];
        pcout << "Warning: the run " << status
              << ". The results do not meet the tolerances there." << std::endl;
      }
    if (parameters.output.print_timings)
      {
        const double wall = std::chrono::duration<double>(
                              std::chrono::steady_clock::now() - wall_start)
                              .count();
        // Peak resident memory, summed over the processes.
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        const double peak_mb =
          Utilities::MPI::sum(static_cast<double>(memory.VmHWM), comm) / 1024.;
        pcout << "  contact solver: " << step_solver.solver_name()
              << ", peak memory: " << std::fixed << std::setprecision(0)
              << peak_mb
              << " MB (all processes), wall time: " << std::setprecision(1)
              << wall << " s" << std::defaultfloat << std::endl;
        pcout << timing_table(timer, wall);
      }
    write_log(true);
    write_status(status);
  }


  template <int dim>
  void
  Simulator<dim>::stop()
  {
    const int  signal = stopping_signal;
    const bool with_checkpoint =
      parameters.checkpoint.every > 0 && last_checkpoint_step != step;
    if (with_checkpoint)
      checkpoint();
    time_series_writer->close();
    const std::string status = "stopped: signal " + std::to_string(signal) +
                               " at step " + std::to_string(step);
    write_status(status);
    char name[32];
    std::snprintf(name, sizeof(name), "checkpoint_%05u", step);
    pcout << "Stopped by " << signal_name(signal) << " after step " << step
          << " (t = " << sig6(current_time) << " s): run_status '" << status
          << "'";
    if (parameters.checkpoint.every > 0)
      pcout << "; --resume continues from " << parameters.output.directory
            << "/" << name;
    else
      pcout << "; no checkpoint (Checkpoint/Every = 0)";
    pcout << "." << std::endl;
    write_log(true);
  }


  template <int dim>
  int
  Simulator<dim>::run(const bool resume)
  {
    initialize(resume);
    while (advance())
      ;
    if (stopping_signal != 0)
      {
        stop();
        return 128 + stopping_signal;
      }
    finish();
    return 0;
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
  void
  Simulator<dim>::close_log_after_error(const std::string &reason)
  {
    // Rank 0, after an error: log.txt ends with the message main prints
    // (a failed write here is reported; run_status is written anyway).
    if (!screen_log.is_open())
      return;
    try
      {
        screen_log.log_only("dynamic-contact: error: " + reason + "\n");
        screen_log.close();
      }
    catch (const std::exception &e)
      {
        std::cerr << "dynamic-contact: " << e.what() << std::endl;
      }
  }


  template <int dim>
  void
  Simulator<dim>::abandon(const std::string &reason)
  {
    timer.disable_output();
    // Only a run that has taken the results over marks them failed (a
    // refused --resume leaves them as they are).
    if (took_over && Utilities::MPI::this_mpi_process(comm) == 0)
      try
        {
          close_log_after_error(reason);
          output_directory->write_status("failed: " + reason);
        }
      catch (const std::exception &e)
        {
          std::cerr << "dynamic-contact: " << e.what() << std::endl;
        }
  }


  template <int dim>
  void
  Simulator<dim>::abandon_alone(const std::string &reason)
  {
    timer.disable_output();
    if (!took_over)
      return;
    try
      {
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          {
            close_log_after_error(reason);
            output_directory->write_status("failed: " + reason);
          }
        else
          {
            StatusFile status;
            status.open(output_directory->file("run_status"));
            status.write("failed: " + reason);
          }
      }
    catch (const std::exception &e)
      {
        std::cerr << "dynamic-contact: " << e.what() << std::endl;
      }
  }


  template <int dim>
  int
  run_dimension(const RunParameters &parameters,
                ParameterHandler    &prm,
                const MPI_Comm       comm,
                const bool           resume,
                const bool           validate)
  {
    // Catch inside the simulator's lifetime, so that it is destroyed with no
    // exception in flight (its timer would otherwise warn about it).
    std::string error;
    int         exit_code = 0;
    {
      Simulator<dim> simulator(parameters, prm, comm);
      try
        {
          if (validate)
            {
              const std::string summary = simulator.validate();
              if (Utilities::MPI::this_mpi_process(comm) == 0)
                std::cout << "dynamic-contact: the scene '"
                          << parameters.parameter_file << "' is valid ("
                          << summary << "); Output/Directory '"
                          << parameters.output.directory
                          << "' is not looked at." << std::endl;
            }
          else
            exit_code = simulator.run(resume);
        }
      catch (const std::exception &e)
        {
          error = dynamic_cast<const std::bad_alloc *>(&e) ?
                    "out of memory (std::bad_alloc)" :
                    error_message(e);
          if (error.empty())
            error = "unknown error";
          // Known to this process alone: the others may be waiting in a
          // collective operation; end them all from here.
          if (!every_process_failed())
            {
              simulator.abandon_alone(error);
              abort_run(error);
            }
          simulator.abandon(error);
        }
    }
    if (!error.empty())
      throw AgreedError(error);
    return exit_code;
  }


  int
  run_simulation(const std::string              &parameter_file,
                 const std::vector<std::string> &overrides,
                 const MPI_Comm                  comm,
                 bool                            resume,
                 const bool                      resume_auto,
                 const bool                      validate)
  {
    ParameterHandler    prm;
    const RunParameters parameters =
      read_parameters(parameter_file, overrides, prm);
    if (resume_auto)
      {
        resume = !list_checkpoints(parameters.output.directory, comm).empty();
        if (!resume && Utilities::MPI::this_mpi_process(comm) == 0)
          std::cout << "--resume=auto: no checkpoint in Output/Directory '"
                    << parameters.output.directory << "': a new run."
                    << std::endl;
      }
    if (parameters.dimension == 2)
      return run_dimension<2>(parameters, prm, comm, resume, validate);
    else
      return run_dimension<3>(parameters, prm, comm, resume, validate);
  }


  template class Simulator<2>;
  template class Simulator<3>;
} // namespace DynamicContact
