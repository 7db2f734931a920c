#ifndef dynamic_contact_run_files_h
#define dynamic_contact_run_files_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/base/fault_injection.h>
#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/output/output.h>
#include <dynamic_contact/output/output_directory.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/run/provenance.h>
#include <dynamic_contact/run/simulator.h>

#include <memory>
#include <string>

namespace DynamicContact
{
  /** The wall time spent writing VTU files and how many were written (the
   *  estimate of the time left, RunReport). */
  struct VtuWriteTimes
  {
    double       seconds = 0;
    unsigned int files   = 0;
  };


  /**
   * The output directory of a run and what the run writes into it
   * (README, "The output directory"): run_status, log.txt (the ScreenLog's
   * copy of the screen), parameters.prm and parameters.json,
   * time_series.csv, the contact CSVs and VTU files of the Simulator's
   * fields, and checkpoints of the loop's RunState. The directory is the
   * run's own (OutputDirectory), every write is checked, and the
   * collective members throw a CollectiveError on every process. When
   * each is written is the TimeLoop's business.
   */
  template <int dim>
  class RunFiles
  {
  public:
    /** Reads the parameters of the run from @p prm (as text and as the
     *  parameter files); writes nothing. */
    RunFiles(const RunParameters &parameters,
             ParameterHandler    &prm,
             const MPI_Comm       comm,
             Simulator<dim>      &simulator,
             TimerOutput         &timer,
             ScreenLog           &screen_log,
             const RunState      &state);

    /**
     * Collective, a new run: take the output directory over (locked, no
     * foreign results, the results of an earlier run removed), write
     * run_status "running", log.txt and the parameter files, and start
     * time_series.csv and the VTU output.
     */
    void
    start_new_run();

    /** Collective, --resume before anything is read: the directory is
     *  ours (locked, no foreign results); nothing in it is removed. */
    void
    open_for_resume();

    /**
     * Collective, --resume with the checkpoint of the state's step loaded:
     * run_status "running"; the rows @p kept of time_series.csv and the
     * files up to the checkpoint stay, those after it go; log.txt goes on.
     */
    void
    take_over(const std::string &kept);

    /** The parameters of the run as text (checkpoints, --resume). */
    const std::string &
    parameters_of_run() const
    {
      return parameters_as_text;
    }

    /** time_series.csv (once started). */
    TimeSeriesWriter &
    time_series_csv()
    {
      return *time_series_writer;
    }

    /** Write the contact CSV and/or the VTU fields of step @p n at @p t. */
    void
    output_results(const unsigned int n,
                   const double       t,
                   const bool         contact_csv,
                   const bool         vtu);

    /** Write a checkpoint of the current state (Checkpoint/Every). */
    void
    checkpoint();

    /** The step of the last checkpoint written or resumed from. */
    unsigned int
    last_checkpoint() const
    {
      return last_checkpoint_step;
    }

    /** After a step that produced no good state, the simulator back at the
     *  state's step: its contact CSV, VTU fields and a checkpoint. */
    void
    write_last_good_state();

    /** Collective: write run_status (a failure is a CollectiveError). */
    void
    write_status(const std::string &status);

    /** Collective: write the screen output since the last call to log.txt;
     *  with @p close close it (before the final run_status). */
    void
    write_log(const bool close = false);

    /**
     * After a failure: mark the output as failed (if this run had taken it
     * over), with @p reason at the end of log.txt. Written by rank 0, or by
     * this process for an error of its own (@p alone).
     */
    void
    abandon(const std::string &reason, const bool alone);

    /** The VTU files written so far, and the time they took. */
    const VtuWriteTimes &
    vtu_write_times() const
    {
      return vtu_times;
    }

  private:
    const RunParameters  &parameters;
    MPI_Comm              comm;
    Simulator<dim>       &simulator;
    TimerOutput          &timer;
    ScreenLog            &screen_log;
    const RunState       &state;
    const FaultInjection &faults = FaultInjection::instance();

    OutputDirectory directory;
    /** parameters.prm and parameters.json of the run. */
    ParameterFiles parameter_files;
    std::string    parameters_as_text;
    /** Whether this run has written run_status (taken over the results). */
    bool                              took_over = false;
    std::unique_ptr<TimeSeriesWriter> time_series_writer;
    std::unique_ptr<VtuWriter<dim>>   vtu_writer;
    VtuWriteTimes                     vtu_times;
    unsigned int last_checkpoint_step = numbers::invalid_unsigned_int;

    /** Collective: time_series.csv (with @p resume continued) and the VTU
     *  output. */
    void
    start_writers(const bool resume);

    /**
     * Collective: open log.txt (with the screen output so far) and write
     * parameters.prm and parameters.json; with @p resume continue log.txt.
     */
    void
    write_provenance(const bool resume);

    /** Rank 0 after an error: the message into log.txt, and close it. */
    void
    close_log_after_error(const std::string &reason);
  };
} // namespace DynamicContact

#endif
