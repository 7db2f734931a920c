#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/run/time_loop.h>

#include <chrono>
#include <iomanip>
#include <sstream>

// What the time loop prints: the run's header (screen and log.txt), a
// solver plan that changes after remeshing (log.txt), and a progress line
// per step with the estimate of the time left.

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
  TimeLoop<dim>::print_header() const
  {
    pcout << "dynamic-contact: " << the_simulator.summary();
    if (the_simulator.adaptive_mesh())
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
                           the_simulator.adaptive_mesh());
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
      "  solver plan: " + the_simulator.solver_plan() + "\n";
    if (parameters.output.print_timings)
      pcout << provenance << plan;
    else if (Utilities::MPI::this_mpi_process(comm) == 0)
      screen_log.log_only(provenance + plan);
    if (parameters.output.print_timings)
      pcout << "  MPI processes: " << Utilities::MPI::n_mpi_processes(comm)
            << ", parameter file: " << parameters.parameter_file
            << ", contact solver: " << the_simulator.solver_name() << '\n';
    the_simulator.print_model(pcout);
  }


  template <int dim>
  void
  TimeLoop<dim>::log_changed_plan(const std::string &choices_before)
  {
    // With Output/Solver details the step solver prints every plan, on the
    // screen and so in log.txt.
    if (parameters.output.solver_details ||
        Utilities::MPI::this_mpi_process(comm) != 0 ||
        the_simulator.solver_choices() == choices_before)
      return;
    screen_log.log_only("  solver plan from step " +
                        std::to_string(state.step + 1) +
                        " (mesh adapted at t = " + sig6(state.time) +
                        "): " + the_simulator.solver_plan() + "\n");
  }


  template <int dim>
  void
  TimeLoop<dim>::print_progress(const StepRecord<dim> &record) const
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
        if (the_simulator.has_friction())
          pcout << "  convexification "
                << statistics.convexification_iterations;
      }
    pcout << "  contact " << statistics.n_contact;
    if (the_simulator.adaptive_mesh())
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
              (vtu_seconds - vtu_seconds_at_start);
            const double simulated = state.time - stepping_start->second;
            if (simulated > 0)
              pcout << ", ~"
                    << seconds(
                         std::max(0., stepping) / simulated *
                           (parameters.time.end_time - state.time) +
                         (vtu_files > 0 ? vtu_seconds / vtu_files : 0.) *
                           schedule.vtu_files_left(state.step, state.time))
                    << " left";
          }
        pcout << ")";
      }
    pcout << std::endl;
  }


  template void
  TimeLoop<2>::print_header() const;
  template void
  TimeLoop<3>::print_header() const;
  template void
  TimeLoop<2>::log_changed_plan(const std::string &);
  template void
  TimeLoop<3>::log_changed_plan(const std::string &);
  template void
  TimeLoop<2>::print_progress(const StepRecord<2> &) const;
  template void
  TimeLoop<3>::print_progress(const StepRecord<3> &) const;
} // namespace DynamicContact
