#ifndef dynamic_contact_run_report_h
#define dynamic_contact_run_report_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/output/output_schedule.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/run/provenance.h>
#include <dynamic_contact/run/run_files.h>
#include <dynamic_contact/run/simulator.h>
#include <dynamic_contact/time/step_record.h>

#include <chrono>
#include <optional>
#include <string>
#include <utility>

namespace DynamicContact
{
  /**
   * What the time loop prints (on the screen of rank 0 and into log.txt):
   * the run's header, a resume, cut-backs and steps kept with warnings, a
   * solver plan that changes after remeshing (log.txt), a progress line
   * per step with the estimate of the time left, a stop by signal, and the
   * end of the summary. It reads the loop's RunState and the Simulator.
   * Output/Print timings = false leaves out what differs from run to run
   * (times, memory, provenance; log.txt has the last two always).
   */
  template <int dim>
  class RunReport
  {
  public:
    RunReport(const RunParameters      &parameters,
              const MPI_Comm            comm,
              const ConditionalOStream &pcout,
              ScreenLog                &screen_log,
              const OutputSchedule     &schedule,
              const std::string        &start_time,
              const Simulator<dim>     &simulator,
              const RunState           &state,
              const VtuWriteTimes      &vtu_times)
      : parameters(parameters)
      , comm(comm)
      , pcout(pcout)
      , screen_log(screen_log)
      , schedule(schedule)
      , start_time(start_time)
      , simulator(simulator)
      , state(state)
      , vtu_times(vtu_times)
    {}

    /** The run starts now (the wall time of the progress lines). */
    void
    start();

    /** The header: the scene, @p process_note (set_process_note()), a
     *  note on the coarse mesh, the provenance, the solver plan, the model. */
    void
    print_header(const std::string &process_note) const;

    /**
     * After the mesh was adapted for step state.step + 1: if the new
     * mesh's solver plan chooses otherwise than @p choices_before
     * (SolverPlan::choices()), write it into log.txt, with the step it
     * applies from (the screen shows it only with Output/Solver details,
     * which prints every plan).
     */
    void
    log_changed_plan(const std::string &choices_before) const;

    /** A failed try (@p reason) is retried with the current time step. */
    void
    print_cut_back(const std::string &reason) const;

    /** The step just accepted was kept with an unconverged convexification
     *  loop (coefficient residual @p residual). */
    void
    warn_unconverged(const double residual) const;

    /** After each accepted step: the first of this run starts the
     *  estimate of the time left. */
    void
    after_step();

    /** The progress line of the step of @p record. */
    void
    print_progress(const StepRecord<dim> &record) const;

    /** The end of the summary: with Output/Print timings the peak memory,
     *  wall time and @p timer's table; the memory table (log.txt always). */
    void
    print_end(const TimerOutput &timer) const;

    /** Stopped by @p signal, run_status @p status: where to go on from. */
    void
    print_stopped(const int signal, const std::string &status) const;

  private:
    const RunParameters      &parameters;
    MPI_Comm                  comm;
    const ConditionalOStream &pcout;
    ScreenLog                &screen_log;
    const OutputSchedule     &schedule;
    /** When the run started (UTC, ISO 8601), for the header. */
    const std::string    &start_time;
    const Simulator<dim> &simulator;
    const RunState       &state;
    const VtuWriteTimes  &vtu_times;

    std::chrono::steady_clock::time_point wall_start;
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
     * The wall time spent writing VTU files when stepping_start was set:
     * the estimate counts the VTU files still to come at their mean cost
     * instead of spreading the bursts of the ones written so far over the
     * steps.
     */
    double vtu_seconds_at_start = 0;
  };
} // namespace DynamicContact

#endif
