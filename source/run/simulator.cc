#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/bulk/error_norms.h>
#include <dynamic_contact/parameters/well_posedness_report.h>
#include <dynamic_contact/run/resources.h>
#include <dynamic_contact/run/simulator.h>

#include <unistd.h>

#include <algorithm>
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
    , bulk(discretization,
           material,
           StepSolver<dim>::runs_convexification_loop(friction_law.get()))
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
    , integrator(StepOperators<dim>{parameters.time,
                                    comm,
                                    timer,
                                    scene,
                                    material,
                                    discretization,
                                    contact_boundary,
                                    contact_state,
                                    bulk,
                                    step_solver,
                                    energy_balance,
                                    force_balance})
    , u(integrator.u)
    , w(integrator.w)
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
    integrator.reinit();
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
  Simulator<dim>::setup_operators(const double start_time)
  {
    TimerSection t(timer, "Setup: bulk matrices");
    // c_t of the friction complementarity function, like E/h.
    const double c_t = parameters.friction.complementarity_constant > 0 ?
                         parameters.friction.complementarity_constant :
                         parameters.material.young_modulus /
                           discretization.minimal_cell_diameter();
    MemoryBudget memory;
    memory.bytes_per_process = memory_per_process;
    memory.degree            = parameters.finite_element.degree;
    // The coarsest level's share of the DoFs as its share of the cells.
    const auto &tria = discretization.triangulation;
    memory.coarse_dofs =
      static_cast<double>(discretization.dof_handler.n_dofs()) *
      (tria.n_global_levels() > 1 ?
         static_cast<double>(tria.n_cells(0)) /
           static_cast<double>(tria.n_global_active_cells()) :
         1.);
    step_solver.reinit(c_t, steps_per_matrix(start_time), memory);
    // The bulk forms stored for the condensed solver, applied from the
    // cells for the assembled solver (BulkOperator); K0 stored unless the
    // plan applies it cell by cell.
    const SolverPlan &plan = step_solver.solver_plan();
    bulk.reinit(plan.condensed, !plan.matrix_free_bulk());
    force_balance.reinit();
  }


  template <int dim>
  unsigned int
  Simulator<dim>::steps_per_matrix(const double start_time) const
  {
    const auto &time = parameters.time;
    if (time.adaptive)
      return 1;
    const double left  = std::max(time.end_time - start_time, 0.);
    unsigned int steps = static_cast<unsigned int>(
      std::max(1., std::ceil(left / time.time_step - 1e-9)));
    if (mesh_adaptation.enabled())
      steps = std::min(steps, parameters.mesh_refinement.refine_every);
    return steps;
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
    // mesh (any number of processes can load it), and with a slip length the
    // coefficient states.
    Vector_t friction =
      contact_state.friction_field(discretization, contact_boundary, false);
    Vector_t states =
      contact_state.state_field(discretization, contact_boundary);
    std::vector<Vector_t *> fields{&u, &w, &friction};
    if (parameters.friction.slip_length.active())
      fields.push_back(&states);
    write_checkpoint(directory,
                     discretization,
                     fields,
                     state,
                     parameters_of_run,
                     keep,
                     before_commit);
  }


  template <int dim>
  void
  Simulator<dim>::load_checkpoint(const std::string &path, const double t)
  {
    Vector_t                friction, states;
    std::vector<Vector_t *> fields{&u, &w, &friction};
    if (parameters.friction.slip_length.active())
      fields.push_back(&states);
    DynamicContact::load_checkpoint<dim>(path,
                                         discretization,
                                         fields,
                                         [this]() { setup_dofs(); });
    setup_operators(t);
    contact_state.set_friction_from_field(contact_boundary, friction, false);
    if (parameters.friction.slip_length.active())
      contact_state.set_state_from_field(contact_boundary, states);
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
        Vector_t states =
          contact_state.state_field(discretization, contact_boundary);
        std::vector<Vector_t *> fields{&u, &w, &traction};
        if (parameters.friction.slip_length.active())
          fields.push_back(&states);
        const auto before = mesh_adaptation.fingerprint();
        refine_and_transfer(discretization, fields, [this]() { setup_dofs(); });
        // on the new nodes
        contact_state.set_friction_from_field(contact_boundary, traction, true);
        if (parameters.friction.slip_length.active())
          contact_state.set_state_from_field(contact_boundary, states);
        changed = true;
        if (mesh_adaptation.fingerprint() == before)
          break;
      }
    if (changed)
      {
        // setup_operators() resets the step solver; the nodes stay.
        const auto lambda = contact_state.lambda;
        const auto states = contact_state.coefficient_state;
        setup_operators(t0);
        contact_state.lambda            = lambda;
        contact_state.coefficient_state = states;
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
        memory_per_process = check_resources(parameters, dim, n, comm);
      }
    TimerSection t(timer, "Setup: mesh");
    scene.create_mesh(discretization.triangulation, false);
    if (!rectangle)
      memory_per_process =
        check_resources(parameters,
                        dim,
                        discretization.triangulation.n_cells(0),
                        comm);
  }


  template <int dim>
  double
  Simulator<dim>::initial_dofs_estimate() const
  {
    const unsigned int p = discretization.fe.degree;
    const double       g = std::pow(2., parameters.geometry.global_refinements);
    if (parameters.geometry.type == Parameters::Geometry::Type::rectangle)
      {
        double vertices = 1;
        for (const unsigned int r : parameters.geometry.repetitions)
          vertices *= r * g * p + 1;
        return dim * vertices;
      }
    return dim * std::pow(g * p, dim) *
           discretization.triangulation.n_global_active_cells();
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
    setup_operators(0.);
    set_initial_conditions();
    step_solver.start_coefficient_states(w);
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
  bool
  Simulator<dim>::solution_count_columns() const
  {
    return parameters.friction.count_solutions &&
           StepSolver<dim>::runs_convexification_loop(
             parameters.friction.law.get());
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
    record.solution_count     = solution_count_columns();
    return record;
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
    StepRecord<dim> record;
    record.step      = n;
    record.time      = t;
    record.time_step = k;
    // The energy change of a mesh transfer before this step has its own
    // column: E_{n-1} below is that of the transferred fields.
    record.remesh_energy_change = remesh_energy_change;
    record.cutbacks             = cutbacks;
    record.previous_energy      = energy_now(); // of (u, w) before the step
    integrator.step(record, t, k, accept_unconverged_loop);
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
  std::string
  Simulator<dim>::memory_table() const
  {
    MemoryItems items;
    discretization.memory_consumption(items);
    bulk.memory_consumption(items);
    step_solver.memory_consumption(items);
    items.push_back({"the step's fields and work vectors",
                     integrator.memory_consumption(),
                     false});
    return DynamicContact::memory_table(items,
                                        discretization.dof_handler.n_dofs(),
                                        comm);
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
      pcout << ", one-sided Lipschitz constant on the slip rates [0, "
            << sig6(parameters.friction.maximum_slip_rate) << "]: "
            << sig6(friction_law->one_sided_lipschitz_constant(
                 parameters.friction.maximum_slip_rate))
            << (friction_law->is_constant() ? " (constant: one pass)" : "");
    if (step_solver.has_friction() && parameters.friction.slip_length.active())
      pcout << "; the coefficient a state of each node with "
            << parameters.friction.slip_length.description();
    pcout << '\n';
    pcout << well_posedness_report<dim>(parameters);
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
              throw CollectiveError(
                name + " is not finite at the slip rate s = " + sig6(s[i]) +
                " (" + scientific(mu[i]) + ").");
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
