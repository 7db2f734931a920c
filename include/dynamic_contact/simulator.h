#ifndef dynamic_contact_simulator_h
#define dynamic_contact_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk_operator.h>
#include <dynamic_contact/checkpoint.h>
#include <dynamic_contact/contact_boundary.h>
#include <dynamic_contact/discretization.h>
#include <dynamic_contact/energy_balance.h>
#include <dynamic_contact/force_balance.h>
#include <dynamic_contact/foundation.h>
#include <dynamic_contact/friction_law.h>
#include <dynamic_contact/material.h>
#include <dynamic_contact/mesh_adaptation.h>
#include <dynamic_contact/output.h>
#include <dynamic_contact/output_directory.h>
#include <dynamic_contact/parameters.h>
#include <dynamic_contact/provenance.h>
#include <dynamic_contact/scene.h>
#include <dynamic_contact/step_record.h>
#include <dynamic_contact/step_solver.h>

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

namespace DynamicContact
{
  /**
   * Owns the mesh, the DoFs and the fields, and runs the time loop: for each
   * step, adapt the mesh if due, form K0 for k, assemble the load, solve the
   * step (convexification loop around the active-set Newton), check the
   * energy balance, write the outputs.
   *
   * run() = initialize(), then advance() until it returns false, then
   * finish() (or stop() after a signal); tests drive them themselves to
   * look between steps.
   *
   * What can go wrong around the solver is handled here (README, "What can
   * go wrong"): the output directory is the run's own (OutputDirectory),
   * every write is checked, the input is checked for non-finite values and
   * for the resources it needs before anything is allocated or written, a
   * resumed run continues exactly the problem of its checkpoint or refuses,
   * and a signal stops the run after the current step with a checkpoint.
   */
  template <int dim>
  class Simulator
  {
  public:
    Simulator(const RunParameters &parameters,
              ParameterHandler    &prm,
              const MPI_Comm       comm);
    ~Simulator();

    /**
     * Run the whole simulation; with @p resume from the newest good
     * checkpoint in the output directory. Returns the exit code: 0, or
     * 128 + N after a stop by signal N (stop()).
     */
    int
    run(const bool resume = false);

    /**
     * Build the mesh (refined for the initial load when adaptive), check the
     * input, prepare the output directory, set the initial state and write
     * step 0. With @p resume: load the newest complete checkpoint of the
     * output directory instead, and continue its time_series.csv.
     */
    void
    initialize(const bool resume = false);

    /**
     * --validate: everything initialize() does before the first result is
     * written (the mesh and its boundary ids, the resources, the functions
     * of the scene and the friction law sampled, the operators set up, the
     * initial state), and nothing more: the output directory is not
     * touched. Throws the error the run would stop with; returns
     * "2D, Q1 elements, N cells, M DoFs, K contact nodes".
     */
    std::string
    validate();

    /**
     * One time step; false (and nothing done) once the end time is reached
     * or a process received a stop signal (stop_signal()).
     */
    bool
    advance();

    /**
     * Print the summary and mark the output as complete: run_status
     * "completed", or "completed with warnings: ..." if steps were kept
     * with an unconverged convexification loop (or the energy balance did
     * not hold).
     */
    void
    finish();

    /**
     * After a stop signal: write a checkpoint (with Checkpoint/Every > 0)
     * and run_status "stopped: signal N at step S".
     */
    void
    stop();

    /** The signal that stopped the run (0: none). */
    int
    stop_signal() const
    {
      return stopping_signal;
    }

    /**
     * After a failure that every process knows: mark the output as failed
     * (if this run had taken it over) and silence the timer summary.
     */
    void
    abandon(const std::string &reason);

    /**
     * After a failure of this process alone (the others may wait in a
     * collective operation): write run_status from this process.
     */
    void
    abandon_alone(const std::string &reason);

    /** The steps written to time_series.csv so far (step 0 first). */
    const std::vector<StepRecord<dim>> &
    time_series() const
    {
      return rows;
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
      return step_solver.node_states();
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

    /** The time and number of the last step done (0 before the first). */
    double
    time() const
    {
      return current_time;
    }

  private:
    const RunParameters parameters;
    MPI_Comm            comm;
    /** The screen output, and its copy log.txt (rank 0). */
    mutable ScreenLog screen_log;
    /** When the run started (UTC, ISO 8601), for the header. */
    std::string        start_time;
    ConditionalOStream pcout;
    ConditionalOStream details;

    // The input is parsed (and can fail) before anything else is built.
    Scene<dim>                         scene;
    KelvinVoigtMaterial<dim>           material;
    Foundation                         foundation;
    std::shared_ptr<const FrictionLaw> friction_law;

    TimerOutput timer;

    Discretization<dim>        discretization;
    ContactBoundary<dim>       contact_boundary;
    BulkOperator<dim>          bulk;
    StepSolver<dim>            step_solver;
    EnergyBalance<dim>         energy_balance;
    ForceBalanceEvaluator<dim> force_balance;
    MeshAdaptation<dim>        mesh_adaptation;

    // Fields in master form (constrained entries zero). u_old, w_old: the
    // state at the start of the step (and the cut-back's restore point);
    // u_bar, w_bar: the start of the Bathe scheme's second sub-step.
    Vector_t u, w, u_old, w_old, u_bar, w_bar, load, rhs, scratch;

    /** Created in the constructor, opened (locked, checked) by initialize. */
    std::unique_ptr<OutputDirectory> output_directory;
    /** Whether this run has written run_status (taken over the results). */
    bool took_over = false;
    /** validate(): initialize() stops before the output directory. */
    bool validate_only = false;
    /** The parameters of the run as text (checkpoints, --resume). */
    std::string parameters_of_run;
    /** parameters.prm and parameters.json of the run. */
    ParameterFiles                    parameter_files;
    std::unique_ptr<TimeSeriesWriter> time_series_writer;
    std::unique_ptr<VtuWriter<dim>>   vtu_writer;
    std::vector<StepRecord<dim>>      rows;

    // The time loop: steps of the nominal Time/Time step, or shorter after a
    // cut-back (k_current), growing back after good steps.
    double                                current_time = 0;
    double                                k_current;
    unsigned int                          good_steps_since_cutback = 0;
    unsigned int                          step                     = 0;
    std::chrono::steady_clock::time_point wall_start;
    /**
     * The total energy E of (u, w) as they stand, once computed: E_{n-1} of
     * the next step is E_n of the last one (reset when the DoFs change).
     */
    std::optional<double> energy_of_state;
    double
    energy_now();
    /**
     * Wall clock and simulated time when the first step of this run (since
     * its start or resume) ended: the estimate of the time left is the wall
     * time per simulated second since then (cut-backs included) times the
     * simulated time left; set-up and the one-off work of the first step
     * are left out.
     */
    std::optional<std::pair<std::chrono::steady_clock::time_point, double>>
      stepping_start;
    /**
     * Wall time spent writing VTU files (and how many were written), in all
     * and when stepping_start was set: the estimate of the time left counts
     * the VTU files still to come at their mean cost instead of spreading
     * the bursts of the ones written so far over the steps.
     */
    double       vtu_seconds          = 0;
    unsigned int vtu_files            = 0;
    double       vtu_seconds_at_start = 0;
    /** The VTU files the run will still write after the current step. */
    unsigned int
    vtu_files_left() const;
    /**
     * Whether an Output/Output times entry falls in the step (t - k, t]
     * (with a round-off allowance: an output time on the time grid belongs
     * to the step ending there).
     */
    bool
    at_output_time(const double t, const double k) const;
    /** Whether step @p n, ending at @p t after a step @p k, writes VTU. */
    bool
    vtu_due(const unsigned int n,
            const double       t,
            const double       k,
            const bool         last) const;
    /**
     * Fault injection for the restart test, from the environment variable
     * DYNAMIC_CONTACT_KILL = "after-step N" or "in-checkpoint N": the run
     * kills itself (SIGKILL) after step N, or while writing the checkpoint
     * of step N (everything written, not yet renamed).
     */
    unsigned int kill_after_step    = numbers::invalid_unsigned_int;
    unsigned int kill_in_checkpoint = numbers::invalid_unsigned_int;
    /**
     * More fault injection: DYNAMIC_CONTACT_KILL = "signal S after-step N
     * [rank R]" raises signal S on rank R (default 0) after step N;
     * DYNAMIC_CONTACT_FAIL = "after-step N [rank R]" throws an error on
     * rank R (default 0) alone after step N.
     */
    int          injected_signal   = 0;
    unsigned int signal_after_step = numbers::invalid_unsigned_int;
    unsigned int signal_rank       = 0;
    unsigned int fail_after_step   = numbers::invalid_unsigned_int;
    unsigned int fail_rank         = 0;
    /** A stop signal received (on any process), and the step of the last
     *  checkpoint written. */
    int          stopping_signal      = 0;
    unsigned int last_checkpoint_step = numbers::invalid_unsigned_int;
    /** Steps kept with an unconverged convexification loop. */
    unsigned int unconverged_steps   = 0;
    double       worst_unconverged   = 0;
    double       max_relative_defect = 0;
    double       min_dissipation     = 0;
    unsigned int total_newton        = 0;
    /**
     * For the end summary, from the rows of time_series.csv (those before
     * a resume included): cut-backs, convexification passes, the largest
     * coefficient residual max_i |mu_i - mu(|w_tau,i|)| of a step.
     */
    unsigned int total_cutbacks           = 0;
    unsigned int total_convexification    = 0;
    double       max_coefficient_residual = 0;
    void
    account_for(const unsigned int cutbacks,
                const unsigned int convexification_iterations,
                const double       coefficient_residual);
    /**
     * Steps of this run (since its start or resume) whose Newton iteration
     * ended at stagnation (residual above Solver/Newton tolerance, below
     * its square root), and the final residual of the last step solved.
     */
    unsigned int stagnated_steps      = 0;
    double       last_newton_residual = 0;
    /**
     * Time/Adaptive: the local error estimate of the last step solved,
     * relative to Time/Adaptive tolerance (> 1: reject), and the steps
     * rejected before the current one was accepted.
     */
    double       last_time_error    = 0;
    unsigned int rejected_this_step = 0;
    /** The error estimate of the step just solved (doc/theory.md 2.5). */
    double
    time_error_estimate(const double k) const;

    /** DoFs, constraints, Gamma_3 and vectors for the current mesh. */
    void
    setup_dofs();
    /** The operators that depend on the mesh: bulk matrices, solvers. */
    void
    setup_operators();
    void
    set_initial_conditions();
    /** Before the first step: refine for the initial load (adaptive runs). */
    void
    refine_initial_mesh();
    /**
     * Adapt the mesh for the times [t0, t1], transferring u, w and the
     * friction forces; returns the change of the energy E the transfer made.
     */
    double
    adapt_mesh(const double t0, const double t1, const double k);
    /**
     * The friction forces as a finite element field at the nodes of Gamma_3
     * (zero elsewhere), and back: with @p per_weight the traction
     * lambda_i/m_i, the form in which they survive a change of the mesh
     * (interpolated); without, the nodal forces lambda_i themselves, which a
     * checkpoint stores exactly with the mesh.
     */
    Vector_t
    friction_field(const bool per_weight) const;
    void
    set_friction_from_field(const Vector_t &field, const bool per_weight);

    /** Write a checkpoint of the current state (Checkpoint/Every). */
    void
    checkpoint();

    /**
     * Before anything is allocated: the cells, DoFs and memory the scene
     * needs for a coarse mesh of @p n_coarse_cells; refuse (collective
     * error) a scene that cannot fit, with the estimate.
     */
    void
    check_resources(const double n_coarse_cells) const;

    /**
     * Before anything is written: the friction law (finite, >= 0, not
     * increasing unless allowed) and the functions of the scene sampled on
     * the mesh (loads over the time interval; initial conditions unless
     * @p resume): a NaN or infinity is an error that names the function.
     */
    void
    check_input(const bool resume);

    /** --resume: load the newest good checkpoint, or refuse and say why. */
    void
    resume_from_checkpoint();

    /**
     * A step produced no good state: u, w and the friction forces are
     * those of the last good step; write it out (contact CSV, VTU, a
     * checkpoint) and throw @p message (collective).
     */
    [[noreturn]] void
    stop_with_last_good_state(const std::string &message);

    /** Positions of the nodes that penetrate the foundation (all processes). */
    std::vector<Point<dim>>
    penetrating_nodes() const;

    void
    print_header() const;
    /**
     * One step from t - k to t; returns the time series row (which records
     * the energy change of a mesh transfer just before the step).
     */
    StepRecord<dim>
    do_time_step(const unsigned int step,
                 const double       t,
                 const double       k,
                 const double       remesh_energy_change,
                 const unsigned int cutbacks);
    /**
     * One (sub-)step of the theta-scheme @p scheme that ends at @p t, from
     * (@p u_start, @p w_start) whose energy is @p start_energy: assemble the
     * right-hand side, solve for w, set u; the solver's statistics and the
     * energy balance terms of the (sub-)step.
     */
    void
    solve_substep(const TimeScheme                     &scheme,
                  const double                          t,
                  const Vector_t                       &u_start,
                  const Vector_t                       &w_start,
                  const double                          start_energy,
                  const bool                            accept_unconverged_loop,
                  typename StepSolver<dim>::Statistics &statistics,
                  EnergyBalanceTerms                   &terms);

    /** Steps left at the nominal time step (for progress lines). */
    unsigned int
    remaining_steps() const;
    /** Whether a step of size @p k that fails may be retried with k/2
     *  (Time/Minimum time step). */
    bool
    can_cut_back(const double k) const;
    /**
     * Write the contact CSV and/or the VTU fields of the current step, with
     * the node states @p states (default: those of the last solve).
     */
    void
    output_results(const unsigned int                        step,
                   const double                              t,
                   const bool                                contact_csv,
                   const bool                                vtu,
                   const std::vector<ContactNodeState<dim>> *states = nullptr);
    /** The node states of the last good step (before a step is tried). */
    std::vector<ContactNodeState<dim>> last_good_states;
    void
    print_progress(const StepRecord<dim> &record) const;
    /** Collective: write run_status (a failure is a CollectiveError). */
    void
    write_status(const std::string &status);
    /**
     * Collective: open log.txt (with the screen output so far) and write
     * parameters.prm and parameters.json; with @p resume continue log.txt.
     */
    void
    write_provenance(const bool resume);
    /** Collective: write the screen output since the last call to log.txt;
     *  with @p close close it (before the final run_status). */
    void
    write_log(const bool close = false);
    /** Rank 0 after an error: the message into log.txt, and close it. */
    void
    close_log_after_error(const std::string &reason);
  };


  /**
   * Read the parameters and run the simulation in the dimension they name;
   * returns the exit code (0, or 128 + N after a stop by signal N). An
   * error every process knows propagates as an AgreedError (main prints it
   * and returns 1); an error of some processes only ends the job from
   * there (abort_run). @p resume_auto: resume if Output/Directory holds a
   * checkpoint (damaged or not: a damaged one is then named), else a new
   * run. @p validate: only check the scene (Simulator::validate()), print
   * that it is valid and return 0.
   */
  int
  run_simulation(const std::string              &parameter_file,
                 const std::vector<std::string> &overrides,
                 const MPI_Comm                  comm,
                 const bool                      resume      = false,
                 const bool                      resume_auto = false,
                 const bool                      validate    = false);
} // namespace DynamicContact

#endif
