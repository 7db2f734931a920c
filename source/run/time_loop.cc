#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/run/time_loop.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <regex>
#include <sstream>

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
  {
    state.time_step = parameters.time.time_step;
    output_directory =
      std::make_unique<OutputDirectory>(parameters.output.directory, comm);
    parameter_files   = ParameterFiles(prm, parameters);
    parameters_of_run = parameters_text(prm,
                                        parameters.geometry.type ==
                                            Parameters::Geometry::Type::gmsh ?
                                          parameters.geometry.mesh_file :
                                          std::string());
  }


  template <int dim>
  TimeLoop<dim>::~TimeLoop()
  {
    forget_timer(timer);
  }


  template <int dim>
  void
  TimeLoop<dim>::write_status(const std::string &status)
  {
    collectively(comm, [&]() { output_directory->write_status(status); });
    took_over = true;
  }


  template <int dim>
  void
  TimeLoop<dim>::write_provenance(const bool resume)
  {
    collectively_on_rank_zero(comm, [&]() {
      screen_log.open(*output_directory, resume);
      parameter_files.write(*output_directory);
    });
  }


  template <int dim>
  void
  TimeLoop<dim>::write_log(const bool close)
  {
    collectively_on_rank_zero(comm, [&]() {
      if (close)
        screen_log.close();
      else
        screen_log.write_pending();
    });
  }


  template <int dim>
  void
  TimeLoop<dim>::output_results(const unsigned int n,
                                const double       t,
                                const bool         contact_csv,
                                const bool         vtu)
  {
    TimerSection scope(timer, "Output");
    if (contact_csv)
      the_simulator.write_contact_csv(*output_directory, n, t);
    if (vtu)
      {
        const auto start = std::chrono::steady_clock::now();
        the_simulator.write_vtu(*vtu_writer, n, t);
        vtu_seconds += std::chrono::duration<double>(
                         std::chrono::steady_clock::now() - start)
                         .count();
        ++vtu_files;
      }
  }


  template <int dim>
  void
  TimeLoop<dim>::checkpoint()
  {
    TimerSection scope(timer, "Checkpoint");
    RunState     saved = state;
    saved.vtu_records  = vtu_writer->get_records();
    the_simulator.save_checkpoint(*output_directory,
                          saved,
                          parameters_of_run,
                          parameters.checkpoint.keep,
                          [this]() { faults.in_checkpoint(state.step); });
    last_checkpoint_step = state.step;
  }


  template <int dim>
  void
  TimeLoop<dim>::stop_with_last_good_state(const std::string &message)
  {
    output_results(state.step,
                   state.time,
                   true,
                   vtu_writer != nullptr && parameters.output.write_vtu);
    checkpoint();
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
    wall_start = std::chrono::steady_clock::now();
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

    // The directory is ours (locked, no foreign results), the results of
    // an earlier run in it are gone.
    output_directory->open(false);
    write_status("running");
    write_provenance(false);
    time_series_writer =
      std::make_unique<TimeSeriesWriter>(*output_directory, comm);
    vtu_writer =
      std::make_unique<VtuWriter<dim>>(*output_directory,
                                       comm,
                                       parameters.boundary_conditions.contact,
                                       parameters.output.vtu_subdivisions);

    print_header();

    const StepRecord<dim> record = the_simulator.initial_record();
    time_series_writer->write(record.row());
    rows.push_back(record);
    output_results(0, 0., true, parameters.output.write_vtu);
  }


  template <int dim>
  std::string
  TimeLoop<dim>::validate()
  {
    validate_only = true;
    initialize(false);
    timer.disable_output(); // set-up times of a run that does not run
    return the_simulator.summary();
  }


  template <int dim>
  unsigned int
  TimeLoop<dim>::processes_taking_part(std::string &note)
  {
    const unsigned int n = Utilities::MPI::n_mpi_processes(comm);
    create_mesh_once();
    const unsigned int minimum = parameters.solver.min_dofs_per_process;
    const double       dofs    = the_simulator.initial_dofs_estimate();
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
  void
  TimeLoop<dim>::set_process_note(const std::string &note)
  {
    process_note = note;
  }


  template <int dim>
  bool
  TimeLoop<dim>::can_cut_back(const double k) const
  {
    return k / 2 >= parameters.time.minimum_time_step * (1 - 1e-12);
  }


  template <int dim>
  double
  TimeLoop<dim>::next_step_length() const
  {
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    double       k  = std::min(state.time_step, T - state.time);
    if (parameters.time.adaptive)
      {
        // Steps end exactly at the Output times and at T; a target less
        // than two steps away is reached in two equal ones (no sliver of a
        // step).
        const double        k_wanted = state.time_step;
        std::vector<double> targets  = parameters.output.output_times;
        targets.push_back(T);
        for (const double target : targets)
          {
            const double left = target - state.time;
            if (left > 1e-9 * k_wanted && left < k + 1e-9 * k_wanted)
              k = left;
            else if (left > 1e-9 * k_wanted && left < 2 * k)
              k = std::min(k, left / 2);
          }
      }
    if (T - state.time - k < 1e-9 * k0) // no sliver of a last step
      k = T - state.time;
    return k;
  }


  template <int dim>
  std::pair<bool, double>
  TimeLoop<dim>::controlled_step_length(const double k,
                                        const double error) const
  {
    // The usual controller: the local error of a scheme of order p scales
    // like k^(p+1).
    const double order = parameters.time.scheme->local_error_order();
    const double factor =
      error > 0 ?
        std::min(2., std::max(0.2, 0.9 * std::pow(error, -1. / order))) :
        2.;
    const double k0    = parameters.time.time_step;
    const double k_min = parameters.time.minimum_time_step;
    // k on the grid Time step * 2^j (rounded down): a new k costs new
    // factorizations of K0, so k changes only by factors of 2 and stays
    // while the estimate allows it.
    const auto on_grid = [k0](const double x) {
      return k0 * std::pow(2., std::floor(std::log2(x / k0) + 1e-9));
    };
    if (error > 1 && k > k_min * (1 + 1e-12))
      return {false, std::max(k_min, on_grid(k * factor))};
    // A step shortened to end at an Output time does not shrink the next
    // one.
    const double k_next = (k < state.time_step && factor >= 1) ?
                            state.time_step :
                            on_grid(k * factor);
    return {true,
            std::min(parameters.time.maximum_time_step,
                     std::max(k_min, k_next))};
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
        k = next_step_length();
        try
          {
            StepRecord<dim> record = the_simulator.do_time_step(state.step + 1,
                                                        state.time + k,
                                                        k,
                                                        remesh_energy_change,
                                                        cutbacks,
                                                        rejected,
                                                        !can_cut_back(k));
            // Nothing that is not finite reaches a file.
            std::string         bad;
            const TimeSeriesRow row = record.row();
            for (const auto &[name, value] : row.columns())
              if (value.find("nan") != std::string::npos ||
                  value.find("inf") != std::string::npos)
                bad += (bad.empty() ? "" : ", ") + name;
            bad = collective_message(comm, bad);
            if (!bad.empty())
              throw NonFiniteValue("step " + std::to_string(state.step + 1) +
                                   " (t = " + sig6(state.time + k) +
                                   " s) produced values that are not "
                                   "finite: " +
                                   bad);
            if (parameters.time.adaptive)
              {
                const auto [accepted, k_new] = controlled_step_length(
                  k, record.time_error / parameters.time.adaptive_tolerance);
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
            if (!can_cut_back(k))
              // Stop, with the last good state written out (fields and a
              // checkpoint to continue from with other settings).
              stop_with_last_good_state(
                "step " + std::to_string(state.step + 1) +
                " (from t = " + sig6(state.time) +
                " s) could not be solved even with the minimum time step "
                "(Time/Minimum time step = " +
                sig6(parameters.time.minimum_time_step) +
                " s): " + failure.what());
            state.time_step = k / 2;
            ++cutbacks;
            state.good_steps_since_cutback = 0;
            pcout << "  step " << state.step + 1 << " (t = " << sig6(state.time)
                  << " s): " << failure.what()
                  << "; retrying with k = " << sig6(state.time_step)
                  << std::endl;
          }
      }
  }


  template <int dim>
  void
  TimeLoop<dim>::accept(const StepRecord<dim> &record,
                        const double           k,
                        const double           k_next)
  {
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    ++state.step;
    state.time += k;
    // Back on the nominal grid (and on T) up to round-off.
    const double n_nominal = std::round(state.time / k0);
    if (std::abs(state.time - n_nominal * k0) < 1e-9 * k0)
      state.time = std::min(n_nominal * k0, T);
    if (std::abs(state.time - T) < 1e-9 * k0)
      state.time = T;
    // The time step grows back after good steps (Time/Adaptive: it follows
    // the error estimate).
    if (parameters.time.adaptive)
      state.time_step = k_next;
    else if (record.cutbacks == 0 && state.time_step < k0 &&
             ++state.good_steps_since_cutback >= 3)
      {
        state.time_step                = std::min(2 * state.time_step, k0);
        state.good_steps_since_cutback = 0;
      }

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
        pcout << "Warning: step " << state.step << " (t = " << sig6(state.time)
              << "): the convexification loop reached Friction/Maximum "
                 "convexification iterations = "
              << parameters.friction.max_convexification_iterations
              << " at the minimum time step without converging; kept, with "
                 "max |mu_i - mu(|w_tau,i|)| = "
              << sig6(statistics.coefficient_residual) << std::endl;
      }
  }


  template <int dim>
  bool
  TimeLoop<dim>::advance()
  {
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    if (state.time >= T - 1e-9 * k0)
      return false;
    // A stop signal on any process stops every one, before the next step.
    stopping_signal = signal_to_stop(comm);
    if (stopping_signal != 0)
      return false;

    double remesh_energy_change = 0;
    if (the_simulator.adaptation_due(state.step + 1))
      {
        const std::string choices_before = the_simulator.solver_choices();
        remesh_energy_change =
          the_simulator.adapt_mesh(state.time,
                           std::min(T,
                                    state.time + the_simulator.lookahead_steps() * k0),
                           k0);
        log_changed_plan(choices_before);
      }

    double                k = 0, k_next = 0;
    const StepRecord<dim> record = take_step(remesh_energy_change, k, k_next);
    accept(record, k, k_next);
    // The estimate of the time left starts after the first step of this
    // run (whose one-off work would inflate it).
    if (!stepping_start)
      {
        stepping_start.emplace(std::chrono::steady_clock::now(), state.time);
        vtu_seconds_at_start = vtu_seconds;
      }
    time_series_writer->write(record.row());
    rows.push_back(record);

    const double t    = state.time;
    const bool   last = (t >= T - 1e-9 * k0);
    output_results(state.step,
                   t,
                   schedule.contact_csv_due(state.step, t, k, last),
                   schedule.vtu_due(state.step, t, k, last));
    if (schedule.progress_due(state.step, last))
      print_progress(record);
    if (schedule.checkpoint_due(state.step, last))
      checkpoint();
    write_log();
    faults.after_step(state.step, Utilities::MPI::this_mpi_process(comm));
    return true;
  }


  template <int dim>
  void
  TimeLoop<dim>::finish()
  {
    time_series_writer->close();
    const std::string status =
      totals.print_summary(pcout, state, parameters, the_simulator.has_friction());
    if (parameters.output.print_timings)
      {
        const double wall = std::chrono::duration<double>(
                              std::chrono::steady_clock::now() - wall_start)
                              .count();
        // Peak resident memory, summed over the processes.
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        const double peak_mb =
          Utilities::MPI::sum(static_cast<double>(memory.VmHWM), comm) / 1024.;
        pcout << "  contact solver: " << the_simulator.solver_name()
              << ", peak memory: " << std::fixed << std::setprecision(0)
              << peak_mb
              << " MB (all processes), wall time: " << std::setprecision(1)
              << wall << " s" << std::defaultfloat << std::endl;
        pcout << timing_table(timer, wall);
      }
    // What the run holds, by part: on the screen with the timings, in
    // log.txt always (resident memory differs from run to run).
    const std::string memory = the_simulator.memory_table();
    if (parameters.output.print_timings)
      pcout << memory;
    else if (Utilities::MPI::this_mpi_process(comm) == 0)
      screen_log.log_only(memory);
    write_log(true);
    write_status(status);
  }



  template <int dim>
  void
  TimeLoop<dim>::stop()
  {
    const int  signal = stopping_signal;
    const bool with_checkpoint =
      parameters.checkpoint.every > 0 && last_checkpoint_step != state.step;
    if (with_checkpoint)
      checkpoint();
    time_series_writer->close();
    const std::string status = "stopped: signal " + std::to_string(signal) +
                               " at step " + std::to_string(state.step);
    write_status(status);
    char name[32];
    std::snprintf(name, sizeof(name), "checkpoint_%05u", state.step);
    pcout << "Stopped by " << signal_name(signal) << " after step "
          << state.step << " (t = " << sig6(state.time) << " s): run_status '"
          << status << "'";
    if (parameters.checkpoint.every > 0)
      pcout << "; --resume continues from " << parameters.output.directory
            << "/" << name;
    else
      pcout << "; no checkpoint (Checkpoint/Every = 0)";
    pcout << "." << std::endl;
    write_log(true);
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
  TimeLoop<dim>::close_log_after_error(const std::string &reason)
  {
    // Rank 0, after an error: log.txt ends with the message main prints
    // (a failed write here is reported; run_status is written anyway).
    if (!screen_log.is_open())
      return;
    try
      {
        screen_log.log_only("dynamic-contact: error: " + reason + "\n");
        screen_log.close();
      }
    catch (const std::exception &e)
      {
        std::cerr << "dynamic-contact: " << e.what() << std::endl;
      }
  }


  template <int dim>
  void
  TimeLoop<dim>::abandon(const std::string &reason, const bool alone)
  {
    timer.disable_output();
    // Only a run that has taken the results over marks them failed (a
    // refused --resume leaves them as they are).
    const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
    if (!took_over || !(root || alone))
      return;
    try
      {
        if (root)
          {
            close_log_after_error(reason);
            output_directory->write_status("failed: " + reason);
          }
        else
          {
            StatusFile status;
            status.open(output_directory->file("run_status"));
            status.write("failed: " + reason);
          }
      }
    catch (const std::exception &e)
      {
        std::cerr << "dynamic-contact: " << e.what() << std::endl;
      }
  }


  template class TimeLoop<2>;
  template class TimeLoop<3>;
} // namespace DynamicContact
