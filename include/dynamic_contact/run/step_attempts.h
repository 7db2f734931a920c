#ifndef dynamic_contact_step_attempts_h
#define dynamic_contact_step_attempts_h

#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/run/run_files.h>
#include <dynamic_contact/run/run_report.h>
#include <dynamic_contact/run/run_totals.h>
#include <dynamic_contact/run/simulator.h>
#include <dynamic_contact/run/step_lengths.h>
#include <dynamic_contact/time/step_record.h>

#include <string>

namespace DynamicContact
{
  /**
   * One step of the run, tried until a try is accepted: each try starts
   * from the restore point of the last good state; a try the solver cannot
   * solve is retried with half the time step (down to Time/Minimum time
   * step), one whose error estimate is too large (Time/Adaptive) with the
   * controller's shorter one. When no step can be had, the last good state
   * is written out and the run stops. An accepted step updates the
   * RunState (its time, step and next time step) and the run's totals.
   *
   * The TimeLoop owns everything this part reads and changes; it keeps
   * references to them.
   */
  template <int dim>
  class StepAttempts
  {
  public:
    StepAttempts(const RunParameters &parameters,
                 const MPI_Comm       comm,
                 Simulator<dim>      &simulator,
                 const StepLengths   &step_lengths,
                 RunState            &state,
                 RunTotals           &totals,
                 RunFiles<dim>       &files,
                 RunReport<dim>      &report)
      : parameters(parameters)
      , comm(comm)
      , simulator(simulator)
      , step_lengths(step_lengths)
      , state(state)
      , totals(totals)
      , files(files)
      , report(report)
    {}

    /**
     * The next step, after a mesh transfer that changed the energy by
     * @p remesh_energy_change: tried until accepted, then the time, the
     * next time step and the totals updated. Returns its record and its
     * length @p k. Throws (collective) with the last good state written if
     * no step can be had.
     */
    StepRecord<dim>
    take(const double remesh_energy_change, double &k);

  private:
    const RunParameters &parameters;
    MPI_Comm             comm;
    Simulator<dim>      &simulator;
    const StepLengths   &step_lengths;
    RunState            &state;
    RunTotals           &totals;
    RunFiles<dim>       &files;
    RunReport<dim>      &report;

    /**
     * Try the next step, with cut-backs and rejections, until one is
     * accepted; returns its record, its length @p k and (Time/Adaptive)
     * the length @p k_next of the step after it.
     */
    StepRecord<dim>
    try_until_accepted(const double remesh_energy_change,
                       double      &k,
                       double      &k_next);
    /**
     * After an accepted step of @p k: the time, the next time step
     * (@p k_next with Time/Adaptive), the run's totals.
     */
    void
    accept(const StepRecord<dim> &record, const double k, const double k_next);
    /**
     * A step produced no good state: the simulator is back at the last
     * good one; write it out (contact CSV, VTU, a checkpoint) and throw
     * @p message (collective).
     */
    [[noreturn]] void
    stop_with_last_good_state(const std::string &message);
  };
} // namespace DynamicContact

#endif
