#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/run/run_report.h>

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    std::string
    seconds(const double s)
    {
      std::ostringstream out;
      out << std::fixed << std::setprecision(s < 100 ? 1 : 0) << s << " s";
      return out.str();
    }
  } // namespace


  template <int dim>
  void
  RunReport<dim>::start()
  {
    wall_start = std::chrono::steady_clock::now();
  }


  template <int dim>
  void
  RunReport<dim>::print_header(const std::string &process_note) const
  {
    pcout << "dynamic-contact: " << simulator.mesh().summary();
    if (simulator.mesh().adaptation().enabled())
      pcout << " (adaptive)";
    pcout << '\n';
    if (!process_note.empty())
      pcout << "  " << process_note << ".\n";
    if (parameters.geometry.type == Parameters::Geometry::Type::rectangle)
      {
        const std::string note =
          coarse_mesh_note(parameters.geometry.repetitions,
                           parameters.geometry.global_refinements,
                           Utilities::MPI::n_mpi_processes(comm),
                           simulator.mesh().adaptation().enabled());
        if (!note.empty())
          pcout << "  note: " << note << ".\n";
      }
    // Which program ran, where and when: on the screen with the timings
    // (output that differs from run to run), in log.txt always.
    const std::string provenance =
      "  " +
      provenance_line(Utilities::MPI::n_mpi_processes(comm),
                      Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
                      start_time) +
      "\n";
    // With the solver plan (it names the number of processes).
    const std::string plan =
      "  solver plan: " + simulator.solver().solver_plan().description() + "\n";
    if (parameters.output.print_timings)
      pcout << provenance << plan;
    else if (Utilities::MPI::this_mpi_process(comm) == 0)
      screen_log.log_only(provenance + plan);
    if (parameters.output.print_timings)
      pcout << "  MPI processes: " << Utilities::MPI::n_mpi_processes(comm)
            << ", parameter file: " << parameters.parameter_file
            << ", contact solver: " << simulator.solver().solver_name() << '\n';
    simulator.print_model(pcout);
  }


  template <int dim>
  void
  RunReport<dim>::log_changed_plan(const std::string &choices_before) const
  {
    // With Output/Solver details the step solver prints every plan, on the
    // screen and so in log.txt.
    if (parameters.output.solver_details ||
        Utilities::MPI::this_mpi_process(comm) != 0 ||
        simulator.solver().solver_plan().choices() == choices_before)
      return;
    screen_log.log_only(
      "  solver plan from step " + std::to_string(state.step + 1) +
      " (mesh adapted at t = " + sig6(state.time) +
      "): " + simulator.solver().solver_plan().description() + "\n");
  }


  template <int dim>
  void
  RunReport<dim>::print_cut_back(const std::string &reason) const
  {
    pcout << "  step " << state.step + 1 << " (t = " << sig6(state.time)
          << " s): " << reason
          << "; retrying with k = " << sig6(state.time_step) << std::endl;
  }


  template <int dim>
  void
  RunReport<dim>::warn_unconverged(const double residual) const
  {
    pcout << "Warning: step " << state.step << " (t = " << sig6(state.time)
          << "): the convexification loop reached Friction/Maximum "
             "convexification iterations = "
          << parameters.friction.max_convexification_iterations
          << " at the minimum time step without converging; kept, with "
             "max |mu_i - mu(|w_tau,i|)| = "
          << sig6(residual) << std::endl;
  }


  template <int dim>
  void
  RunReport<dim>::after_step()
  {
    if (!stepping_start)
      {
        stepping_start.emplace(std::chrono::steady_clock::now(), state.time);
        vtu_seconds_at_start = vtu_times.seconds;
      }
  }


  template <int dim>
  void
  RunReport<dim>::print_progress(const StepRecord<dim> &record) const
  {
    // Output/Print timings and Print iteration counts = false leave out
    // what differs from run to run: the times, and the iteration counts (on
    // several processes they follow the round-off of the parallel direct
    // solver near the stopping thresholds: two runs of tests/paper_small on
    // 2 processes differed by one Newton iteration in some progress
    // lines).
    pcout << "step " << std::setw(5) << state.step << '/'
          << state.step + schedule.remaining_steps(state.time)
          << "  t = " << sig6(record.time);
    if (record.time_step != parameters.time.time_step || record.cutbacks > 0)
      pcout << "  k = " << sig6(record.time_step) << " (" << record.cutbacks
            << " cut-backs)";
    const auto &statistics = record.statistics;
    if (parameters.output.print_iteration_counts)
      {
        pcout << "  Newton " << statistics.newton_iterations;
        if (simulator.solver().has_friction())
          pcout << "  convexification "
                << statistics.convexification_iterations;
      }
    pcout << "  contact " << statistics.n_contact;
    if (simulator.mesh().adaptation().enabled())
      pcout << "  cells " << record.cells;
    pcout << "  N = " << sig6(record.normal_force)
          << "  E = " << sig6(record.terms.energy.total());
    if (parameters.output.print_timings)
      {
        const auto   now = std::chrono::steady_clock::now();
        const double elapsed =
          std::chrono::duration<double>(now - wall_start).count();
        pcout << "  (" << seconds(elapsed);
        // The wall time per simulated second since the end of the first
        // step of this run (set-up and the first step's one-off work, the
        // factorization and the first compliance columns, left out), times
        // the simulated time left; VTU files (seconds each on large meshes,
        // every few steps) apart: those still to come at their mean cost.
        if (stepping_start)
          {
            const double stepping =
              std::chrono::duration<double>(now - stepping_start->first)
                .count() -
              (vtu_times.seconds - vtu_seconds_at_start);
            const double simulated = state.time - stepping_start->second;
            if (simulated > 0)
              pcout << ", ~"
                    << seconds(
                         std::max(0., stepping) / simulated *
                           (parameters.time.end_time - state.time) +
                         (vtu_times.files > 0 ?
                            vtu_times.seconds / vtu_times.files :
                            0.) *
                           schedule.vtu_files_left(state.step, state.time))
                    << " left";
          }
        pcout << ")";
      }
    pcout << std::endl;
  }


  template <int dim>
  void
  RunReport<dim>::print_end(const TimerOutput &timer) const
  {
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
        pcout << "  contact solver: " << simulator.solver().solver_name()
              << ", peak memory: " << std::fixed << std::setprecision(0)
              << peak_mb
              << " MB (all processes), wall time: " << std::setprecision(1)
              << wall << " s" << std::defaultfloat << std::endl;
        pcout << timing_table(timer, wall);
      }
    // What the run holds, by part: on the screen with the timings, in
    // log.txt always (resident memory differs from run to run).
    const std::string memory = simulator.memory_table();
    if (parameters.output.print_timings)
      pcout << memory;
    else if (Utilities::MPI::this_mpi_process(comm) == 0)
      screen_log.log_only(memory);
  }


  template <int dim>
  void
  RunReport<dim>::print_stopped(const int          signal,
                                const std::string &status) const
  {
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
  }


  template class RunReport<2>;
  template class RunReport<3>;
} // namespace DynamicContact
