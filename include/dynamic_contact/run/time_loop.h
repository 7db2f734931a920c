#ifndef dynamic_contact_time_loop_h
#define dynamic_contact_time_loop_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/base/fault_injection.h>
#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/output/output_schedule.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/run/provenance.h>
#include <dynamic_contact/run/run_files.h>
#include <dynamic_contact/run/run_report.h>
#include <dynamic_contact/run/run_totals.h>
#include <dynamic_contact/run/simulator.h>
#include <dynamic_contact/run/step_attempts.h>
#include <dynamic_contact/run/step_lengths.h>
#include <dynamic_contact/time/step_record.h>

#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * Runs a Simulator through time and owns the run state alone: the time,
   * the step and its length (cut-backs, Time/Adaptive's controller), when
   * results and checkpoints are written, the progress lines and the end
   * summary, the output directory and run_status, the screen log, and
   * resuming from a checkpoint. The loop state that a checkpoint carries
   * is one RunState (checkpoint.h), kept here as it is saved.
   *
   * The loop decides; three parts it owns do the work: StepLengths (the
   * length of each step), RunFiles (the output directory and every file
   * written into it) and RunReport (what the run prints). They read the
   * RunState, and change it only where the loop calls them to.
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
   * a failed step is retried from its restore point with a shorter time
   * step, and a signal stops the run after the current step with a
   * checkpoint.
   */
  template <int dim>
  class TimeLoop
  {
  public:
    TimeLoop(const RunParameters &parameters,
             ParameterHandler    &prm,
             const MPI_Comm       comm);
    ~TimeLoop();

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
     * Collective: how many processes of this run should take part
     * (Solver/Minimum DoFs per process): the first M of them, at least one.
     * Builds the mesh (initialize() keeps it) to count the DoFs; where M is
     * less than all, @p note is what the run prints about it.
     */
    unsigned int
    processes_taking_part(std::string &note);

    /**
     * A line printed with the header (and into log.txt): which processes
     * take part, for a run on part of them.
     */
    void
    set_process_note(const std::string &note)
    {
      process_note = note;
    }

    /**
     * One time step; false (and nothing done) once the end time is reached
     * or a process received a stop signal.
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
     * After a failure: mark the output as failed (if this run had taken it
     * over) and silence the timer summary. A failure every process knows is
     * written by rank 0; one of this process @p alone (the others may wait
     * in a collective operation) by this process.
     */
    void
    abandon(const std::string &reason, const bool alone = false);

    /** The steps written to time_series.csv so far (step 0 first). */
    const std::vector<StepRecord<dim>> &
    time_series() const
    {
      return rows;
    }

    /** The time of the last step done (0 before the first). */
    double
    time() const
    {
      return state.time;
    }

    /** The discrete problem: mesh, fields, Gamma_3. */
    const Simulator<dim> &
    simulator() const
    {
      return the_simulator;
    }

  private:
    const RunParameters parameters;
    MPI_Comm            comm;
    /** The screen output, and its copy log.txt (rank 0). */
    ScreenLog screen_log;
    /** When the run started (UTC, ISO 8601), for the header. */
    std::string        start_time;
    ConditionalOStream pcout;
    ConditionalOStream details;

    /**
     * The discrete problem. Constructed before the timer it is given (it
     * only keeps the reference until then): its scene parses the input,
     * and an error there must leave no timer behind to complain about an
     * exception in flight.
     */
    Simulator<dim> the_simulator;
    TimerOutput    timer;

    /** What each step writes, and how long it is. */
    const OutputSchedule schedule;
    const StepLengths    step_lengths;
    /**
     * The loop state a checkpoint carries: step, time, the current time
     * step (StepLengths), the run's balances and counts. Its vtu_records
     * are filled from the VTU writer when saved (RunFiles::checkpoint()).
     */
    RunState state;
    /** The output directory and every file written into it, and what the
     *  run prints: both keep references to the members above. */
    RunFiles<dim>                files;
    RunReport<dim>               report;
    std::vector<StepRecord<dim>> rows;

    /** validate(): initialize() stops before the output directory. */
    bool validate_only = false;
    /** The mesh is built (processes_taking_part() or initialize()). */
    bool mesh_created = false;
    /** set_process_note(). */
    std::string           process_note;
    const FaultInjection &faults = FaultInjection::instance();
    /** A stop signal received (on any process). */
    int stopping_signal = 0;
    /** The end summary's counts (those before a resume included). */
    RunTotals totals;
    /** Each step tried until one is accepted (reads and updates the
     *  members above). */
    StepAttempts<dim> attempts;

    /** Build the coarse mesh unless it is built already. */
    void
    create_mesh_once();
    /** --resume: load the newest good checkpoint, or refuse and say why. */
    void
    resume_from_checkpoint();
  };


  /**
   * Read the parameters and run the simulation in the dimension they name;
   * returns the exit code (0, or 128 + N after a stop by signal N). An
   * error every process knows propagates as an AgreedError (main prints it
   * and returns 1); an error of some processes only ends the job from
   * there (abort_run). @p resume_auto: resume if Output/Directory holds a
   * checkpoint (damaged or not: a damaged one is then named), else a new
   * run. @p validate: only check the scene (TimeLoop::validate()), print
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
