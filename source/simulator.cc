#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/error_messages.h>
#include <dynamic_contact/error_norms.h>
#include <dynamic_contact/simulator.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <iomanip>
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

    /** Columns name_x, name_y (, name_z) of a vector. */
    template <int dim>
    void
    add_vector_columns(TimeSeriesRow &       row,
                       const std::string &   name,
                       const Tensor<1, dim> &v)
    {
      const char *axes[] = {"_x", "_y", "_z"};
      for (unsigned int d = 0; d < dim; ++d)
        row.add(name + axes[d], v[d]);
    }

    /** Everything a row of time_series.csv says about a step. */
    template <int dim>
    struct StepRecord
    {
      unsigned int                         step             = 0;
      double                               time             = 0;
      double                               time_step        = 0;
      double                               normal_force     = 0;
      double                               tangential_force = 0;
      ForceBalance<dim>                    forces;
      EnergyBalanceTerms                   terms;
      double                               previous_energy = 0;
      typename StepSolver<dim>::Statistics statistics;
      double                               remesh_energy_change = 0;
      unsigned int                         cutbacks             = 0;
      unsigned long long                   dofs                 = 0;
      unsigned long long                   cells                = 0;
      bool                                 has_errors           = false;
      Errors                               errors;

      TimeSeriesRow
      row() const
      {
        TimeSeriesRow r;
        r.add_integer("step", step);
        r.add("time", time);
        r.add("time_step", time_step);
        r.add_integer("cutbacks", cutbacks);
        r.add("normal_force", normal_force);
        r.add("tangential_force", tangential_force);
        add_vector_columns(r, "applied_force", forces.applied);
        add_vector_columns(r, "reaction_force", forces.reaction);
        add_vector_columns(r, "inertia_force", forces.inertia);
        r.add("kinetic_energy", terms.energy.kinetic);
        r.add("elastic_energy", terms.energy.elastic);
        r.add("foundation_energy", terms.energy.foundation);
        r.add("total_energy", terms.energy.total());
        r.add("load_work", terms.load_work);
        r.add("dissipation", terms.dissipation());
        r.add("dissipation_inertia", terms.inertia);
        r.add("dissipation_elastic", terms.elastic);
        r.add("dissipation_viscous", terms.viscous);
        r.add("dissipation_compliance", terms.compliance);
        r.add("dissipation_damping", terms.damping);
        r.add("friction_dissipation", terms.friction);
        r.add("energy_balance_defect", terms.defect);
        r.add("relative_energy_defect",
              std::abs(terms.defect) / terms.scale(previous_energy));
        r.add("relative_min_dissipation",
              terms.min_dissipation_term() / terms.scale(previous_energy));
        r.add("remesh_energy_change", remesh_energy_change);
        r.add_integer("newton_iterations", statistics.newton_iterations);
        r.add_integer("convexification_iterations",
                      statistics.convexification_iterations);
        r.add_integer("convexification_converged",
                      statistics.convexification_converged ? 1 : 0);
        r.add("coefficient_residual", statistics.coefficient_residual);
        r.add_integer("factorizations", statistics.factorizations);
        r.add_integer("active_set_cycles", statistics.cycles);
        r.add_integer("line_search_steps", statistics.line_search_steps);
        r.add_integer("linear_iterations", statistics.linear_iterations);
        r.add_integer("n_contact", statistics.n_contact);
        r.add_integer("n_stick", statistics.n_stick);
        r.add_integer("n_slip", statistics.n_slip);
        r.add_integer("dofs", dofs);
        r.add_integer("cells", cells);
        if (has_errors)
          {
            // doc/theory.md section 7; Theorem 6's error is the maximum over the
            // steps of error_theorem6.
            r.add("error_strain", errors.strain);
            r.add("error_velocity", errors.velocity);
            r.add("error_theorem6", errors.strain + errors.velocity);
            r.add("error_energy", errors.energy);
          }
        return r;
      }
    };
  } // namespace


  template <int dim>
  Simulator<dim>::Simulator(const RunParameters &parameters,
                            ParameterHandler &   prm,
                            const MPI_Comm       comm)
    : parameters(parameters)
    , comm(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , details(std::cout,
              Utilities::MPI::this_mpi_process(comm) == 0 &&
                parameters.output.solver_details)
    , scene(parameters, prm)
    , material(parameters.material)
    , foundation(parameters.foundation)
    , friction_law(FrictionLaw::create(parameters.friction))
    , timer(comm,
            pcout,
            parameters.output.print_timings ? TimerOutput::summary :
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
    , mesh_adaptation(parameters.mesh_refinement, scene, discretization)
    , k_current(parameters.time.time_step)
  {
    if (const char *kill = std::getenv("DYNAMIC_CONTACT_KILL"))
      {
        std::istringstream in(kill);
        std::string        where;
        unsigned int       at = 0;
        in >> where >> at;
        AssertThrow(in && (where == "after-step" || where == "in-checkpoint"),
                    ExcMessage("The environment variable DYNAMIC_CONTACT_KILL "
                               "(fault injection for tests) must read "
                               "'after-step N' or 'in-checkpoint N', not '" +
                               std::string(kill) + "'."));
        (where == "after-step" ? kill_after_step : kill_in_checkpoint) = at;
      }
  }


  template <int dim>
  Simulator<dim>::~Simulator() = default;


  template <int dim>
  void
  Simulator<dim>::setup_dofs()
  {
    TimerOutput::Scope t(timer, "Setup: DoFs and Gamma_3");
    discretization.setup_dofs(parameters.boundary_conditions);
    contact_boundary.reinit(discretization,
                            parameters.boundary_conditions.contact,
                            scene.initial_gap());
    for (auto *v : {&u, &w, &u_old, &w_old, &load, &rhs, &scratch})
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
    TimerOutput::Scope t(timer, "Setup: bulk matrices");
    bulk.reinit();
    force_balance.reinit();
    // c_t of the friction complementarity function, like E/h.
    const double c_t =
      parameters.friction.complementarity_constant > 0 ?
        parameters.friction.complementarity_constant :
        parameters.material.young_modulus /
          discretization.minimal_cell_diameter();
    step_solver.reinit(c_t, parameters.time.theta());
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
    if (!parameters.mesh_refinement.contact_following)
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
    const auto &                         nodes  = contact_boundary.nodes();
    const auto &                         lambda = step_solver.friction_forces();
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
    const auto &                nodes = contact_boundary.nodes();
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
    TimerOutput::Scope scope(timer, "Checkpoint");
    RunState           state;
    state.step                     = step;
    state.time                     = current_time;
    state.time_step                = k_current;
    state.good_steps_since_cutback = good_steps_since_cutback;
    state.max_relative_defect      = max_relative_defect;
    state.min_dissipation          = min_dissipation;
    state.total_newton             = total_newton;
    state.vtu_records              = vtu_writer->get_records();
    // The friction forces exactly, as a field of nodal forces saved with the
    // mesh (any number of processes can load it).
    Vector_t friction = friction_field(false);
    write_checkpoint(parameters.output.directory,
                     discretization,
                     {&u, &w, &friction},
                     state,
                     parameters.checkpoint.keep,
                     [this]() {
                       if (kill_in_checkpoint == step)
                         std::raise(SIGKILL);
                     });
  }


  template <int dim>
  void
  Simulator<dim>::refine_initial_mesh()
  {
    // Refine towards the load of the first steps, with the initial
    // conditions interpolated anew on each mesh (no transfer needed).
    const double k  = parameters.time.time_step;
    const double t1 = std::min(parameters.time.end_time,
                               mesh_adaptation.lookahead_steps() * k);
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
    TimerOutput::Scope scope(timer, "Mesh adaptation");
    const double       energy_before = energy_now();
    bool               changed       = false;
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
  Simulator<dim>::prepare_output_directory(const bool resume)
  {
    const std::string &directory = parameters.output.directory;
    bool               ok        = true;
    std::string        reason;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::error_code error;
        std::filesystem::create_directories(directory, error);
        if (error || !std::filesystem::is_directory(directory))
          {
            ok     = false;
            reason = error ? error.message() : "not a directory";
          }
      }
    ok = Utilities::MPI::broadcast(comm, ok, 0);
    AssertThrow(ok,
                ExcMessage("Output/Directory: cannot create '" + directory +
                           "'" + (reason.empty() ? "" : " (" + reason + ")") +
                           "."));
    // Results of an earlier run in the same directory must not pass for
    // ours: remove what this program writes (unless continuing it).
    if (!resume && Utilities::MPI::this_mpi_process(comm) == 0)
      for (const auto &entry : std::filesystem::directory_iterator(directory))
        {
          const std::string name = entry.path().filename().string();
          if (name == "time_series.csv" || name == "solution.pvd" ||
              name == "run_status" || name.rfind("contact_", 0) == 0 ||
              name.rfind("solution_", 0) == 0 ||
              name.rfind("checkpoint_", 0) == 0)
            std::filesystem::remove_all(entry.path());
        }
    MPI_Barrier(comm);
  }


  template <int dim>
  void
  Simulator<dim>::write_status(const std::string &status) const
  {
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ofstream out(parameters.output.directory + "/run_status");
        out << status << '\n';
      }
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
  TimeSeriesRow
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
    record.previous_energy = energy_now(); // of u_old = u, w_old = w

    const double theta = parameters.time.theta();
    {
      TimerOutput::Scope scope(timer, "Step: load and right-hand side");
      bulk.set_time_step(k, theta);
      // f_theta = theta f_n + (1 - theta) f_{n-1}.
      bulk.assemble_load_vector(scene, t, load);
      if (theta < 1)
        {
          bulk.assemble_load_vector(scene, t - k, scratch);
          load *= theta;
          load.add(1 - theta, scratch);
        }
      // b = (rho/k) M w_{n-1} - (1 - theta) A w_{n-1}
      //     - B (u_{n-1} + theta (1 - theta) k w_{n-1}) + f_theta
      bulk.mass().vmult(rhs, w_old);
      rhs *= material.density() / k;
      scratch = u_old;
      scratch.add(theta * (1 - theta) * k, w_old);
      bulk.elasticity().vmult(u, scratch); // u as scratch
      rhs -= u;
      if (theta < 1 && bulk.has_viscosity())
        {
          bulk.viscosity().vmult(u, w_old);
          rhs.add(-(1 - theta), u);
        }
      rhs += load;
    }

    w = w_old; // initial guess
    // At the smallest time step a convexification loop that reaches its
    // cap is kept (reported) rather than failing the run.
    record.statistics =
      step_solver.solve(rhs, u_old, w_old, w, !can_cut_back(k));

    if (!std::isfinite(w.l2_norm()))
      throw StepFailure("the solution is not finite");

    // u_n = u_{n-1} + k (theta w_n + (1 - theta) w_{n-1})
    u = u_old;
    u.add(k * theta, w);
    if (theta < 1)
      u.add(k * (1 - theta), w_old);

    TimerOutput::Scope scope(timer, "Step: energy and force balance");
    record.terms = energy_balance.step_terms(u_old,
                                             w_old,
                                             u,
                                             w,
                                             load,
                                             k,
                                             step_solver.node_states(),
                                             record.previous_energy,
                                             theta);
    const auto &nodes = contact_boundary.nodes();
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
                     w_old_ghosted = discretization.expanded(w_old);
      // The stress of the scheme's equation: at u_theta, w_theta.
      scratch = u;
      scratch *= theta;
      scratch.add(1 - theta, u_old);
      const Vector_t u_theta = discretization.expanded(scratch);
      scratch = w;
      scratch *= theta;
      scratch.add(1 - theta, w_old);
      const Vector_t w_theta = discretization.expanded(scratch);
      record.forces = force_balance.compute(contact_boundary,
                                            step_solver.node_states(),
                                            t,
                                            k,
                                            theta,
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
    record.dofs  = discretization.dof_handler.n_dofs();
    record.cells = discretization.triangulation.n_global_active_cells();
    energy_of_state = record.terms.energy.total(); // the step succeeded
    return record.row();
  }


  template <int dim>
  void
  Simulator<dim>::output_results(const unsigned int n,
                                 const double       t,
                                 const bool         contact_csv,
                                 const bool         vtu)
  {
    TimerOutput::Scope scope(timer, "Output");
    char               name[64];
    std::snprintf(name, sizeof(name), "/contact_%05u.csv", n);
    if (contact_csv)
      write_contact_csv(parameters.output.directory + name,
                        contact_boundary,
                        step_solver.node_states(),
                        u,
                        w,
                        step_solver.has_friction(),
                        comm);
    if (vtu)
      vtu_writer->write(n,
                        t,
                        discretization,
                        material,
                        contact_boundary,
                        step_solver.node_states(),
                        u,
                        w,
                        step_solver.has_friction());
  }


  template <int dim>
  void
  Simulator<dim>::print_progress(const TimeSeriesRow &row) const
  {
    // Iteration counts (like times) follow the round-off of the parallel
    // direct solver near the stopping thresholds: they are left out of the
    // deterministic output of regression runs.
    const bool interactive = parameters.output.print_timings;
    pcout << "step " << std::setw(5) << step << '/' << step + remaining_steps()
          << "  t = " << sig6(row.get("time"));
    if (row.get("time_step") != parameters.time.time_step ||
        row.get("cutbacks") > 0)
      pcout << "  k = " << sig6(row.get("time_step")) << " ("
            << row.get("cutbacks") << " cut-backs)";
    if (interactive)
      {
        pcout << "  Newton " << row.get("newton_iterations");
        if (step_solver.has_friction())
          pcout << "  convexification "
                << row.get("convexification_iterations");
      }
    pcout << "  contact " << row.get("n_contact");
    if (mesh_adaptation.enabled())
      pcout << "  cells " << row.get("cells");
    pcout << "  N = " << sig6(row.get("normal_force"))
          << "  E = " << sig6(row.get("total_energy"));
    if (interactive)
      {
        const double elapsed = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - wall_start)
                                 .count();
        pcout << "  (" << seconds(elapsed);
        if (stepping_start)
          {
            const double stepping =
              std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                            stepping_start->first)
                .count();
            const double simulated = current_time - stepping_start->second;
            if (simulated > 0)
              pcout << ", ~"
                    << seconds(stepping / simulated *
                               (parameters.time.end_time - current_time))
                    << " left";
          }
        pcout << ")";
      }
    pcout << std::endl;
  }


  template <int dim>
  void
  Simulator<dim>::initialize(const bool resume)
  {
    wall_start = std::chrono::steady_clock::now();
    // Everything that can be wrong with the input is checked before any
    // result is written (the scene's functions and boundary ids when the
    // mesh is made).
    if (friction_law)
      friction_law->check_nonnegative(parameters.friction.maximum_slip_rate);
    if (resume)
      {
        // The newest complete checkpoint: mesh, fields, state; the time
        // series continues after its step (later rows are dropped).
        const std::string latest =
          find_latest_checkpoint(parameters.output.directory, comm);
        AssertThrow(!latest.empty(),
                    ExcMessage("--resume: there is no complete checkpoint in "
                               "Output/Directory '" +
                               parameters.output.directory +
                               "' (the interrupted run needs Checkpoint/Every "
                               "> 0)."));
        {
          TimerOutput::Scope t(timer, "Setup: mesh");
          scene.create_mesh(discretization.triangulation, false);
        }
        Vector_t       friction;
        const RunState state = read_checkpoint(latest,
                                               discretization,
                                               {&u, &w, &friction},
                                               [this]() { setup_dofs(); });
        setup_operators();
        set_friction_from_field(friction, false);
        step                     = state.step;
        current_time             = state.time;
        k_current                = state.time_step;
        good_steps_since_cutback = state.good_steps_since_cutback;
        max_relative_defect      = state.max_relative_defect;
        min_dissipation          = state.min_dissipation;
        total_newton             = state.total_newton;

        prepare_output_directory(true);
        write_status("running");
        truncate_time_series(parameters.output.directory + "/time_series.csv",
                             step,
                             comm);
        time_series_writer = std::make_unique<TimeSeriesWriter>(
          parameters.output.directory + "/time_series.csv", comm, true);
        vtu_writer = std::make_unique<VtuWriter<dim>>(
          parameters.output.directory,
          comm,
          parameters.output.vtu_subdivisions);
        vtu_writer->set_records(state.vtu_records);
        print_header();
        pcout << "  resumed from " << latest << " (step " << step
              << ", t = " << sig6(current_time) << " s)" << std::endl;
        return;
      }

    {
      TimerOutput::Scope t(timer, "Setup: mesh");
      scene.create_mesh(discretization.triangulation);
    }
    setup_dofs();
    if (mesh_adaptation.enabled())
      refine_initial_mesh();
    setup_operators();
    prepare_output_directory(false);
    write_status("running");
    time_series_writer = std::make_unique<TimeSeriesWriter>(
      parameters.output.directory + "/time_series.csv", comm);
    vtu_writer = std::make_unique<VtuWriter<dim>>(
      parameters.output.directory, comm, parameters.output.vtu_subdivisions);

    print_header();
    set_initial_conditions();

    StepRecord<dim> record;
    if (scene.has_exact_solution())
      {
        const Vector_t u_ghosted = discretization.expanded(u),
                       w_ghosted = discretization.expanded(w);
        record.has_errors = true;
        record.errors =
          compute_errors(discretization, material, scene, 0., u_ghosted, w_ghosted);
      }
    record.terms.energy    = energy_balance.energy(u, w);
    record.previous_energy = record.terms.energy.total();
    energy_of_state        = record.previous_energy;
    record.dofs            = discretization.dof_handler.n_dofs();
    record.cells = discretization.triangulation.n_global_active_cells();
    const TimeSeriesRow row = record.row();
    time_series_writer->write(row);
    rows.push_back(row);
    output_results(0, 0., true, parameters.output.vtu_every > 0);
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
    if (!stepping_start)
      stepping_start.emplace(std::chrono::steady_clock::now(), current_time);
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    if (current_time >= T - 1e-9 * k0)
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
    const auto          lambda_good = step_solver.friction_forces();
    unsigned int        cutbacks    = 0;
    double              k           = 0;
    TimeSeriesRow       row;
    for (;;)
      {
        k = std::min(k_current, T - current_time);
        if (T - current_time - k < 1e-9 * k0) // no sliver of a last step
          k = T - current_time;
        try
          {
            row = do_time_step(
              step + 1, current_time + k, k, remesh_energy_change, cutbacks);
            break;
          }
        catch (const StepFailure &failure)
          {
            u = u_old;
            w = w_old;
            step_solver.set_friction_forces(lambda_good);
            if (!can_cut_back(k))
              {
                // Stop, with the last good state written out (fields and a
                // checkpoint to continue from with other settings).
                output_results(step, current_time, true, vtu_writer != nullptr);
                checkpoint();
                AssertThrow(false,
                            ExcMessage(
                              "step " + std::to_string(step + 1) +
                              " (from t = " + sig6(current_time) +
                              " s) could not be solved even with the "
                              "minimum time step (Time/Minimum time step = " +
                              sig6(parameters.time.minimum_time_step) +
                              " s): " + failure.what() +
                              ". The last good state (step " +
                              std::to_string(step) + ") is written to '" +
                              parameters.output.directory + "'."));
              }
            k_current = k / 2;
            ++cutbacks;
            good_steps_since_cutback = 0;
            pcout << "  step " << step + 1 << " (t = " << sig6(current_time)
                  << " s): " << failure.what() << "; retrying with k = "
                  << sig6(k_current) << std::endl;
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
    // The time step grows back after good steps.
    if (cutbacks == 0 && k_current < k0 && ++good_steps_since_cutback >= 3)
      {
        k_current                = std::min(2 * k_current, k0);
        good_steps_since_cutback = 0;
      }
    const double t = current_time;

    time_series_writer->write(row);
    rows.push_back(row);

    max_relative_defect =
      std::max(max_relative_defect, row.get("relative_energy_defect"));
    min_dissipation =
      std::min(min_dissipation, row.get("relative_min_dissipation"));
    total_newton += row.get("newton_iterations");

    if (row.get("convexification_converged") == 0)
      pcout << "Warning: step " << step << " (t = " << sig6(t)
            << "): the convexification loop reached Friction/Maximum "
               "convexification iterations = "
            << parameters.friction.max_convexification_iterations
            << " at the minimum time step without converging; kept, with "
               "max |mu_i - mu(|w_tau,i|)| = "
            << sig6(row.get("coefficient_residual")) << std::endl;

    const bool last = (current_time >= T - 1e-9 * k0);
    // An output time is due at the first step reaching it: t - k < t_out <=
    // t, with a round-off allowance that moves both ends up (an output time
    // on the time grid belongs to the step ending there, not the next).
    bool         at_output_time = false;
    const double allowance      = 1e-12 * std::max(std::abs(t), k);
    for (const double t_out : parameters.output.output_times)
      at_output_time = at_output_time || (t_out <= t + allowance &&
                                          t_out > t - k + allowance);
    const unsigned int csv_every = parameters.output.output_every;
    const unsigned int vtu_every = parameters.output.vtu_every;
    output_results(step,
                   t,
                   last || at_output_time ||
                     (csv_every > 0 && step % csv_every == 0),
                   vtu_every > 0 &&
                     (last || at_output_time || step % vtu_every == 0));

    const unsigned int progress = parameters.output.progress_every;
    if (progress > 0 && (step % progress == 0 || last))
      print_progress(row);
    if (parameters.checkpoint.every > 0 &&
        step % parameters.checkpoint.every == 0 && !last)
      checkpoint();
    if (kill_after_step == step)
      std::raise(SIGKILL);
    return true;
  }


  template <int dim>
  void
  Simulator<dim>::finish()
  {
    pcout << "Completed " << step << " steps";
    if (parameters.output.print_timings)
      pcout << ", " << total_newton << " Newton iterations (mean "
            << std::fixed << std::setprecision(2)
            << static_cast<double>(total_newton) / std::max(step, 1u)
            << std::defaultfloat << " per step)";
    pcout << ".\n"
          << "  energy balance: max relative defect "
          << (max_relative_defect < 1e-8 ?
                "below 1e-8" :
                "ABOVE 1e-8 (" + sig6(max_relative_defect) + ")")
          << ", every dissipation term >= 0: "
          << (min_dissipation >= -EnergyBalanceTerms::roundoff ?
                "yes" :
                "NO (" + sig6(min_dissipation) + " of the energy)")
          << std::endl;
    if (parameters.output.print_timings)
      {
        // Peak resident memory, summed over the processes.
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        const double peak_mb =
          Utilities::MPI::sum(static_cast<double>(memory.VmHWM), comm) / 1024.;
        pcout << "  contact solver: " << step_solver.solver_name()
              << ", peak memory: " << std::fixed << std::setprecision(0)
              << peak_mb << " MB (all processes), wall time: "
              << std::setprecision(1)
              << std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                               wall_start)
                   .count()
              << " s" << std::defaultfloat << std::endl;
      }
    write_status("completed");
  }


  template <int dim>
  void
  Simulator<dim>::run(const bool resume)
  {
    initialize(resume);
    while (advance())
      ;
    finish();
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
        const auto cell = GridTools::find_active_cell_around_point(
          discretization.mapping, discretization.dof_handler, point);
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
  Simulator<dim>::abandon(const std::string &reason)
  {
    timer.disable_output();
    if (time_series_writer) // the output directory exists
      write_status("failed: " + reason);
  }


  template <int dim>
  void
  run_dimension(const RunParameters &parameters,
                ParameterHandler &   prm,
                const MPI_Comm       comm,
                const bool           resume)
  {
    // Catch inside the simulator's lifetime, so that it is destroyed with no
    // exception in flight (its timer would otherwise warn about it).
    std::exception_ptr error;
    {
      Simulator<dim> simulator(parameters, prm, comm);
      try
        {
          simulator.run(resume);
        }
      catch (const std::exception &e)
        {
          error = std::current_exception();
          simulator.abandon(error_message(e));
        }
    }
    if (error)
      std::rethrow_exception(error);
  }


  void
  run_simulation(const std::string &             parameter_file,
                 const std::vector<std::string> &overrides,
                 const MPI_Comm                  comm,
                 const bool                      resume)
  {
    ParameterHandler    prm;
    const RunParameters parameters =
      read_parameters(parameter_file, overrides, prm);
    if (parameters.dimension == 2)
      run_dimension<2>(parameters, prm, comm, resume);
    else
      run_dimension<3>(parameters, prm, comm, resume);
  }


  template class Simulator<2>;
  template class Simulator<3>;
} // namespace DynamicContact
