#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/run/time_loop.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace DynamicContact
{
  template <int dim>
  TimeLoop<dim>::TimeLoop(const RunParameters &parameters,
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
    , the_simulator(this->parameters, prm, comm, timer, details)
    , timer(comm,
            pcout,
            // The table of the sections is printed by finish() (disjoint
            // sections, timing.h), not by TimerOutput.
            TimerOutput::never,
            TimerOutput::wall_times)
    , schedule(this->parameters)
    , step_lengths(this->parameters)
    , files(this->parameters,
            prm,
            comm,
            the_simulator,
            timer,
            screen_log,
            state)
    , report(this->parameters,
             comm,
             pcout,
             screen_log,
             schedule,
             start_time,
             the_simulator,
             state,
             files.vtu_write_times())
    , attempts(this->parameters,
               comm,
               the_simulator,
               step_lengths,
               state,
               totals,
               files,
               report)
  {
    state.time_step = parameters.time.time_step;
  }


  template <int dim>
  TimeLoop<dim>::~TimeLoop()
  {
    forget_timer(timer);
  }


  template <int dim>
  void
  TimeLoop<dim>::initialize(const bool resume)
  {
    report.start();
    // Everything that can be wrong with the input is checked before any
    // result is written (the scene's functions and boundary ids when the
    // mesh is made), and the size of the scene before it is allocated.
    create_mesh_once();
    if (resume)
      {
        resume_from_checkpoint();
        return;
      }
    the_simulator.set_up_initial_state();

    // --validate: the scene would start; nothing is written.
    if (validate_only)
      return;

    files.start_new_run();
    report.print_header(process_note);

    const StepRecord<dim> record = the_simulator.initial_record();
    files.time_series_csv().write(record.row());
    rows.push_back(record);
    files.output_results(0, 0., true, parameters.output.write_vtu);
  }


  template <int dim>
  std::string
  TimeLoop<dim>::validate()
  {
    validate_only = true;
    initialize(false);
    timer.disable_output(); // set-up times of a run that does not run
    return the_simulator.mesh().summary();
  }


  template <int dim>
  unsigned int
  TimeLoop<dim>::processes_taking_part(std::string &note)
  {
    create_mesh_once();
    return the_simulator.mesh().processes_taking_part(note);
  }


  template <int dim>
  void
  TimeLoop<dim>::create_mesh_once()
  {
    if (!mesh_created)
      the_simulator.create_mesh();
    mesh_created = true;
  }


  template <int dim>
  bool
  TimeLoop<dim>::advance()
  {
    if (step_lengths.at_end(state.time))
      return false;
    // A stop signal on any process stops every one, before the next step.
    stopping_signal = signal_to_stop(comm);
    if (stopping_signal != 0)
      return false;

    double remesh_energy_change = 0;
    if (the_simulator.mesh().adaptation().due(state.step + 1))
      {
        const double      T  = parameters.time.end_time;
        const double      k0 = parameters.time.time_step;
        const std::string choices_before =
          the_simulator.solver().solver_plan().choices();
        remesh_energy_change = the_simulator.adapt_mesh(
          state.time,
          std::min(T,
                   state.time +
                     the_simulator.mesh().adaptation().lookahead_steps() * k0),
          k0);
        report.log_changed_plan(choices_before);
      }

    double                k      = 0;
    const StepRecord<dim> record = attempts.take(remesh_energy_change, k);
    // The estimate of the time left starts after the first step of this
    // run (whose one-off work would inflate it).
    report.after_step();
    files.time_series_csv().write(record.row());
    rows.push_back(record);

    const double t    = state.time;
    const bool   last = step_lengths.at_end(t);
    files.output_results(state.step,
                         t,
                         schedule.contact_csv_due(state.step, t, k, last),
                         schedule.vtu_due(state.step, t, k, last));
    if (schedule.progress_due(state.step, last))
      report.print_progress(record);
    if (schedule.checkpoint_due(state.step, last))
      files.checkpoint();
    files.write_log();
    faults.after_step(state.step, Utilities::MPI::this_mpi_process(comm));
    return true;
  }


  template <int dim>
  void
  TimeLoop<dim>::finish()
  {
    files.time_series_csv().close();
    const std::string status = totals.print_summary(
      pcout, state, parameters, the_simulator.solver().has_friction());
    report.print_end(timer);
    files.write_log(true);
    files.write_status(status);
  }


  template <int dim>
  void
  TimeLoop<dim>::stop()
  {
    const int signal = stopping_signal;
    if (parameters.checkpoint.every > 0 &&
        files.last_checkpoint() != state.step)
      files.checkpoint();
    files.time_series_csv().close();
    const std::string status = "stopped: signal " + std::to_string(signal) +
                               " at step " + std::to_string(state.step);
    files.write_status(status);
    report.print_stopped(signal, status);
    files.write_log(true);
  }


  template <int dim>
  int
  TimeLoop<dim>::run(const bool resume)
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
  void
  TimeLoop<dim>::abandon(const std::string &reason, const bool alone)
  {
    timer.disable_output();
    files.abandon(reason, alone);
  }


  template class TimeLoop<2>;
  template class TimeLoop<3>;
} // namespace DynamicContact
