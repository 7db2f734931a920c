#ifndef dynamic_contact_simulator_h
#define dynamic_contact_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/mesh/mesh_adaptation.h>
#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/output/output.h>
#include <dynamic_contact/output/output_directory.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/time/energy_balance.h>
#include <dynamic_contact/time/force_balance.h>
#include <dynamic_contact/time/step_integrator.h>
#include <dynamic_contact/time/step_record.h>
#include <dynamic_contact/time/step_solver.h>

#include <functional>
#include <array>
#include <memory>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * The discrete problem and its algorithm, step-42 style: owns the scene
   * and its laws, the mesh, the DoFs, the solution on Gamma_3
   * (ContactState), the operators and the solver, and the StepIntegrator
   * that holds the fields u and w and does the scheme's solves; it calls
   * the steps in functions named after them: set up the mesh and the
   * initial state, adapt the mesh, do a time step (do_time_step: the
   * integrator's step, the errors of a manufactured solution, the row's
   * columns), write the fields.
   *
   * When and how often these happen, what is kept after a failure, and
   * where the results go is the TimeLoop's business (time_loop.h): it owns
   * the run state, and this class never looks at the clock, the schedule or
   * the output directory's status.
   */
  template <int dim>
  class Simulator
  {
  public:
    Simulator(const RunParameters      &parameters,
              ParameterHandler         &prm,
              const MPI_Comm            comm,
              TimerOutput              &timer,
              const ConditionalOStream &details);

    /** @name Set-up */
    /** @{ */

    /**
     * Create the coarse mesh of the scene, refusing a scene that cannot fit
     * (check_resources) before anything is allocated.
     */
    void
    create_mesh();

    /**
     * After create_mesh(): the DoFs of the uniform mesh after Geometry/Global
     * refinements (exact for a rectangle; dim degree^dim per cell of a mesh
     * file), before any adaptive refinement.
     */
    double
    initial_dofs_estimate() const;

    /**
     * A new run: refine the coarse mesh (Geometry/Global refinements, then
     * for the initial load if adaptive), check the input, set up DoFs and
     * operators, interpolate the initial state (throws if not finite).
     */
    void
    set_up_initial_state();

    /**
     * Before anything is written: the friction law (finite, >= 0, not
     * increasing unless allowed) and the functions of the scene sampled on
     * the mesh (loads over the time interval; initial conditions unless
     * @p resume): a NaN or infinity is an error that names the function.
     */
    void
    check_input(const bool resume);

    /**
     * A resumed run: the mesh and the fields (u, w, the friction forces)
     * of the checkpoint @p path, saved at time @p t; DoFs and operators set
     * up for them.
     */
    void
    load_checkpoint(const std::string &path, const double t);

    /**
     * Write a checkpoint of the mesh and the fields with the loop's
     * @p state (write_checkpoint in checkpoint.h).
     */
    void
    save_checkpoint(OutputDirectory             &directory,
                    const RunState              &state,
                    const std::string           &parameters_of_run,
                    const unsigned int           keep,
                    const std::function<void()> &before_commit);

    /** The time series row of step 0: the initial state's energy. */
    StepRecord<dim>
    initial_record();

    /**
     * time_series.csv has the uniqueness measures' columns (a slip-rate
     * dependent law, Friction/Uniqueness monitor not never).
     */
    bool
    uniqueness_columns() const;

    /**
     * time_series.csv has the solution count's columns (Friction/Count
     * solutions with a slip-rate dependent law).
     */
    bool
    solution_count_columns() const;
    /** @} */

    /** @name The steps of the scheme */
    /** @{ */

    /** Whether the mesh is adapted before step @p n, and how far ahead. */
    bool
    adaptation_due(const unsigned int n) const
    {
      return mesh_adaptation.due(n);
    }
    unsigned int
    lookahead_steps() const
    {
      return mesh_adaptation.lookahead_steps();
    }

    /**
     * Adapt the mesh for the times [t0, t1], transferring u, w and the
     * friction forces; returns the change of the energy E the transfer made.
     */
    double
    adapt_mesh(const double t0, const double t1, const double k);

    /**
     * One step from t - k to t (Time/Scheme); returns the time series row
     * (which records the energy change of a mesh transfer just before the
     * step and the cut-backs and rejected tries of the loop). With
     * @p accept_unconverged_loop (the smallest time step) a convexification
     * loop that reaches its cap is kept rather than failing. Throws
     * StepFailure (a cut-back may help) or NonFiniteValue (it may not).
     */
    StepRecord<dim>
    do_time_step(const unsigned int step,
                 const double       t,
                 const double       k,
                 const double       remesh_energy_change,
                 const unsigned int cutbacks,
                 const unsigned int rejected,
                 const bool         accept_unconverged_loop);

    /**
     * The final Newton residual of the last step solved (the larger of
     * the two sub-steps of a composite scheme).
     */
    double
    newton_residual() const
    {
      return integrator.newton_residual();
    }

    /**
     * The state a step starts from, to go back to after a failed or
     * rejected try: the fields, the Gamma_3 solution and their energy.
     */
    struct RestorePoint
    {
      Vector_t              u, w;
      ContactState<dim>     contact;
      std::optional<double> energy;
    };
    RestorePoint
    restore_point() const;
    void
    restore(const RestorePoint &point);
    /** @} */

    /** @name Output of the fields */
    /** @{ */
    void
    write_contact_csv(OutputDirectory   &directory,
                      const unsigned int step,
                      const double       t) const;
    void
    write_vtu(VtuWriter<dim>    &writer,
              const unsigned int step,
              const double       t) const;

    /** "2D, Q1 elements, N cells, M DoFs, K contact nodes". */
    std::string
    summary() const;
    /** The material and friction lines of the header. */
    void
    print_model(const ConditionalOStream &out) const;
    /** @} */

    /** @name What the time loop and the tests read */
    /** @{ */
    std::string
    solver_name() const
    {
      return step_solver.solver_name();
    }

    /** The solver plan of the current mesh, in words (log.txt). */
    std::string
    solver_plan() const
    {
      return step_solver.solver_plan().description();
    }

    /** What the plan of the current mesh chose (SolverPlan::choices()). */
    std::string
    solver_choices() const
    {
      return step_solver.solver_plan().choices();
    }

    /**
     * What the run holds, by part (memory_table(); collective): the mesh
     * and DoFs, the bulk operator's pattern and matrices, the contact
     * solvers' factorizations, preconditioners and tables, the vectors.
     */
    std::string
    memory_table() const;
    bool
    has_friction() const
    {
      return step_solver.has_friction();
    }
    bool
    adaptive_mesh() const
    {
      return mesh_adaptation.enabled();
    }

    const ContactBoundary<dim> &
    contact() const
    {
      return contact_boundary;
    }

    /** The node states of the last step, aligned with contact().nodes(). */
    const std::vector<ContactNodeState<dim>> &
    node_states() const
    {
      return contact_state.nodes;
    }

    /**
     * The displacement at a point of the body (collective). Throws if the
     * point is outside the body.
     */
    Tensor<1, dim>
    point_displacement(const Point<dim> &point) const;

    /** Displacement and velocity, in master form. */
    const Vector_t &
    displacement() const
    {
      return u;
    }
    const Vector_t &
    velocity() const
    {
      return w;
    }

    const Discretization<dim> &
    get_discretization() const
    {
      return discretization;
    }
    /** @} */

  private:
    const RunParameters &parameters;
    MPI_Comm             comm;
    TimerOutput         &timer;

    // The input is parsed (and can fail) before anything else is built.
    Scene<dim>                         scene;
    KelvinVoigtMaterial<dim>           material;
    Foundation                         foundation;
    std::shared_ptr<const FrictionLaw> friction_law;

    Discretization<dim>        discretization;
    ContactBoundary<dim>       contact_boundary;
    ContactState<dim>          contact_state;
    BulkOperator<dim>          bulk;
    StepSolver<dim>            step_solver;
    EnergyBalance<dim>         energy_balance;
    ForceBalanceEvaluator<dim> force_balance;
    MeshAdaptation<dim>        mesh_adaptation;

    /**
     * The time step: the scheme's solves and measures, and the fields (the
     * state u, w and the vectors of a step in progress).
     */
    StepIntegrator<dim> integrator;
    /** The state, in master form (constrained entries zero): integrator's. */
    Vector_t &u, &w;

    /**
     * The total energy E of (u, w) as they stand, once computed: E_{n-1} of
     * the next step is E_n of the last one (reset when the DoFs change).
     */
    std::optional<double> energy_of_state;
    /**
     * The bytes one process may use (Solver/Memory per process, or what
     * the hosts had available at the start: check_resources()), for
     * Preconditioner = auto.
     */
    double memory_per_process = std::numeric_limits<double>::infinity();
    double
    energy_now();

    /** DoFs, constraints, Gamma_3 and vectors for the current mesh. */
    void
    setup_dofs();
    /**
     * The operators that depend on the mesh: bulk matrices, solvers, the
     * solvers planned for the steps from @p start_time on.
     */
    void
    setup_operators(const double start_time);
    /**
     * The steps from @p start_time on that one bulk matrix K0 is expected to
     * serve: those left, at most Mesh refinement/Refine every where the
     * mesh adapts, one where the time step adapts (K0 changes with it).
     */
    unsigned int
    steps_per_matrix(const double start_time) const;
    void
    set_initial_conditions();
    /** Before the first step: refine for the initial load (adaptive runs). */
    void
    refine_initial_mesh();

    /** Positions of the nodes that penetrate the foundation (all processes). */
    std::vector<Point<dim>>
    penetrating_nodes() const;

    /** The errors of a manufactured solution at @p t, of (u, w). */
    void
    record_errors(StepRecord<dim> &record, const double t);
  };
} // namespace DynamicContact

#endif
