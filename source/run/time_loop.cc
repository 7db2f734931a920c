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
  namespace
  {
    /**
     * Collective: nothing that is not finite reaches a file. Throws
     * NonFiniteValue naming the columns of @p row (of step @p n, ending at
     * @p t) that are not finite on some process.
     */
    void
    check_finite(const TimeSeriesRow &row,
                 const unsigned int   n,
                 const double         t,
                 const MPI_Comm       comm)
    {
      std::string bad;
      for (const auto &[name, value] : row.columns())
        if (value.find("nan") != std::string::npos ||
            value.find("inf") != std::string::npos)
          bad += (bad.empty() ? "" : ", ") + name;
      bad = collective_message(comm, bad);
      if (!bad.empty())
        throw NonFiniteValue("step " + std::to_string(n) + " (t = " + sig6(t) +
                             " s) produced values that are not "
                             "finite: " +
                             bad);
    }
  } // namespace


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
  TimeLoop<dim>::stop_with_last_good_state(const std::string &message)
  {
    files.write_last_good_state();
    std::string m = message;
    while (!m.empty() && m.back() == '.')
      m.pop_back();
    throw CollectiveError(m + ". The last good state (step " +
                          std::to_string(state.step) + ") is written to '" +
                          parameters.output.directory + "'.");
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
    const unsigned int n = Utilities::MPI::n_mpi_processes(comm);
    create_mesh_once();
    const unsigned int minimum = parameters.solver.min_dofs_per_process;
    const double       dofs    = the_simulator.mesh().initial_dofs_estimate();
    if (n == 1 || minimum == 0 || dofs >= double(n) * minimum)
      return n;
    const unsigned int m =
      std::max(1u, static_cast<unsigned int>(dofs / minimum));
    note = std::to_string(m) + " of " + std::to_string(n) +
           " processes take part (about " +
           std::to_string(static_cast<long long>(std::llround(dofs))) +
           " DoFs in the initial mesh, Solver/Minimum DoFs per process = " +
           std::to_string(minimum) + "); the others wait for them";
    return m;
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
  StepRecord<dim>
  TimeLoop<dim>::take_step(const double remesh_energy_change,
                           double      &k,
                           double      &k_next)
  {
    // A step the solver cannot solve is retried from the last good state
    // with half the time step, down to Time/Minimum time step; a step
    // whose error estimate is too large (Time/Adaptive) with a shorter one.
    const auto   good     = the_simulator.restore_point();
    unsigned int cutbacks = 0, rejected = 0;
    k_next = state.time_step;
    for (;;)
      {
        k = step_lengths.next(state);
        try
          {
            StepRecord<dim> record =
              the_simulator.do_time_step(state.step + 1,
                                         state.time + k,
                                         k,
                                         remesh_energy_change,
                                         cutbacks,
                                         rejected,
                                         !step_lengths.can_cut_back(k));
            check_finite(record.row(), state.step + 1, state.time + k, comm);
            if (parameters.time.adaptive)
              {
                const auto [accepted, k_new] =
                  step_lengths.controlled(state,
                                          k,
                                          record.time_error /
                                            parameters.time.adaptive_tolerance);
                if (!accepted)
                  {
                    // Rejected: again from the last good state.
                    the_simulator.restore(good);
                    state.time_step = k_new;
                    ++rejected;
                    continue;
                  }
                k_next = k_new;
              }
            return record;
          }
        catch (const NonFiniteValue &e)
          {
            the_simulator.restore(good);
            stop_with_last_good_state(e.what());
          }
        catch (const StepFailure &failure)
          {
            the_simulator.restore(good);
            if (!step_lengths.can_cut_back(k))
              // Stop, with the last good state written out (fields and a
              // checkpoint to continue from with other settings).
              stop_with_last_good_state(
                "step " + std::to_string(state.step + 1) +
                " (from t = " + sig6(state.time) +
                " s) could not be solved even with the minimum time step "
                "(Time/Minimum time step = " +
                sig6(parameters.time.minimum_time_step) +
                " s): " + failure.what());
            step_lengths.cut_back(state, k);
            ++cutbacks;
            report.print_cut_back(failure.what());
          }
      }
  }


  template <int dim>
  void
  TimeLoop<dim>::accept(const StepRecord<dim> &record,
                        const double           k,
                        const double           k_next)
  {
    step_lengths.accept(state, k, k_next, record.cutbacks);

    const auto &statistics = record.statistics;
    totals.add(
      {state.step,
       record.cutbacks,
       statistics.convexification_iterations,
       statistics.coefficient_residual,
       statistics.coupled_fallbacks,
       record.uniqueness_monitor ? statistics.uniqueness_bound : -1.,
       record.uniqueness_monitor ? statistics.uniqueness_certificate : -1.,
       record.uniqueness_monitor ? statistics.contraction_factor : -1.,
       statistics.cycles,
       statistics.solutions,
       statistics.failed_starts});
    if (the_simulator.newton_residual() > parameters.solver.newton_tolerance)
      ++totals.stagnated_steps;
    state.max_relative_defect =
      std::max(state.max_relative_defect, record.relative_energy_defect());
    state.min_dissipation =
      std::min(state.min_dissipation, record.relative_min_dissipation());
    state.total_newton += statistics.newton_iterations;
    if (!statistics.convexification_converged)
      {
        ++state.unconverged_steps;
        state.worst_unconverged =
          std::max(state.worst_unconverged, statistics.coefficient_residual);
        report.warn_unconverged(statistics.coefficient_residual);
      }
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
        const double      T              = parameters.time.end_time;
        const double      k0             = parameters.time.time_step;
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

    double                k = 0, k_next = 0;
    const StepRecord<dim> record = take_step(remesh_energy_change, k, k_next);
    accept(record, k, k_next);
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
