#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/run/simulator.h>

#include <algorithm>
#include <cmath>

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
    , discretization(comm, parameters.finite_element.degree)
    , operators(parameters,
                scene,
                material,
                discretization,
                contact_boundary,
                contact_state,
                comm,
                timer,
                details)
    , mesh_cycle(parameters, prm, scene, discretization, contact_boundary, comm)
    , integrator(StepOperators<dim>{parameters.time,
                                    comm,
                                    timer,
                                    scene,
                                    material,
                                    discretization,
                                    contact_boundary,
                                    contact_state,
                                    operators.bulk,
                                    operators.step_solver,
                                    operators.energy_balance,
                                    operators.force_balance})
    , u(integrator.u)
    , w(integrator.w)
    , field_io(parameters,
               discretization,
               material,
               contact_boundary,
               contact_state,
               u,
               w,
               operators.step_solver.has_friction(),
               comm)
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
  }


  template <int dim>
  void
  Simulator<dim>::setup_operators(const double start_time)
  {
    TimerSection t(timer, "Setup: bulk matrices");
    operators.setup(start_time,
                    memory_per_process,
                    mesh_cycle.adaptation().enabled());
  }


  template <int dim>
  void
  Simulator<dim>::load_checkpoint(const std::string &path, const double t)
  {
    field_io.load_checkpoint(
      path, [this]() { setup_dofs(); }, [this, t]() { setup_operators(t); });
  }


  template <int dim>
  double
  Simulator<dim>::adapt_mesh(const double t0, const double t1, const double k)
  {
    TimerSection scope(timer, "Mesh adaptation");
    const double energy_before = integrator.energy();
    if (mesh_cycle.adapt(t0, t1, k, u, w, contact_state, [this]() {
          setup_dofs();
        }))
      {
        // setup_operators() resets the step solver; the nodes stay.
        const auto lambda = contact_state.lambda;
        const auto states = contact_state.coefficient_state;
        setup_operators(t0);
        contact_state.lambda            = lambda;
        contact_state.coefficient_state = states;
      }
    return integrator.energy() - energy_before;
  }



  template <int dim>
  void
  Simulator<dim>::create_mesh()
  {
    memory_per_process = mesh_cycle.create(timer);
  }


  template <int dim>
  void
  Simulator<dim>::set_up_initial_state()
  {
    discretization.triangulation.refine_global(
      parameters.geometry.global_refinements);
    check_input(false);
    setup_dofs();
    // Interpolated, then the constraints imposed (clamped and roller
    // conditions, and master form at hanging nodes).
    const auto set_initial_conditions = [this]() {
      discretization.interpolate(scene.initial_displacement(), u);
      discretization.interpolate(scene.initial_velocity(), w);
    };
    if (mesh_cycle.adaptation().enabled())
      mesh_cycle.refine_for_initial_load(u,
                                         w,
                                         set_initial_conditions,
                                         [this]() { setup_dofs(); });
    setup_operators(0.);
    set_initial_conditions();
    operators.step_solver.start_coefficient_states(w);
    const double norm = u.l2_norm() + w.l2_norm();
    if (!std::isfinite(norm))
      throw CollectiveError("Initial conditions: the interpolated initial "
                            "state is not finite.");
  }


  template <int dim>
  StepRecord<dim>
  Simulator<dim>::initial_record()
  {
    StepRecord<dim> record;
    record_state(record, 0.);
    record.terms.energy     = operators.energy_balance.energy(u, w);
    record.previous_energy  = record.terms.energy.total();
    integrator.known_energy = record.previous_energy;
    record.adaptive_time    = parameters.time.adaptive; // the columns, 0
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
    record.previous_energy = integrator.energy(); // of (u, w) before the step
    integrator.step(record, t, k, accept_unconverged_loop);
    if (parameters.time.adaptive)
      {
        record.adaptive_time = true;
        record.rejected      = rejected;
      }
    record_state(record, t);
    integrator.known_energy = record.terms.energy.total(); // the step succeeded
    return record;
  }


  template <int dim>
  void
  Simulator<dim>::record_state(StepRecord<dim> &record, const double t)
  {
    const auto &friction = parameters.friction;
    record.uniqueness_monitor =
      friction.law && !friction.law->is_constant() &&
      friction.uniqueness_monitor != Parameters::Friction::Monitor::never;
    record.solution_count =
      friction.count_solutions &&
      StepSolver<dim>::runs_convexification_loop(friction.law.get());
    record.dofs  = discretization.dof_handler.n_dofs();
    record.cells = discretization.triangulation.n_global_active_cells();
    integrator.record_errors(record, t);
  }


  template <int dim>
  void
  Simulator<dim>::check_input(const bool resume)
  {
    check_friction_law(parameters);
    check_scene_functions(
      parameters, scene, discretization.triangulation, comm, !resume);
  }



  template <int dim>
  void
  Simulator<dim>::restore(const RestorePoint &point)
  {
    u                       = point.u;
    w                       = point.w;
    contact_state           = point.contact;
    integrator.known_energy = point.energy;
  }


  template class Simulator<2>;
  template class Simulator<3>;
} // namespace DynamicContact
