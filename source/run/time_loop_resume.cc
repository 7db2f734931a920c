#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/output/resume.h>
#include <dynamic_contact/run/time_loop.h>

#include <string>

// --resume: the time loop taken up again from the newest complete
// checkpoint in Output/Directory.

namespace DynamicContact
{
  template <int dim>
  void
  TimeLoop<dim>::resume_from_checkpoint()
  {
    const std::string &directory = parameters.output.directory;
    the_simulator.check_input(true);
    // The directory: ours, and no other run in it.
    files.open_for_resume();

    const std::string latest = newest_good_checkpoint(directory, comm, pcout);
    const RunState    saved  = read_run_state(latest, comm);
    check_resumable(latest, saved, files.parameters_of_run(), parameters, comm);
    const std::string old_parameters = read_checkpoint_parameters(latest, comm);
    const double      T              = parameters.time.end_time;
    const double      k0             = parameters.time.time_step;
    const std::string series         = directory + "/time_series.csv";
    const TimeSeriesOnDisk on_disk = read_time_series(series, saved.step, comm);
    totals.add_rows(on_disk.kept);
    if (T < on_disk.last_time - 1e-9 * k0)
      throw CollectiveError(
        "--resume: Time/End time = " + sig6(T) +
        " s is before the last row already written to " + series + " (step " +
        std::to_string(on_disk.last_step) + ", t = " + sig6(on_disk.last_time) +
        " s): a resumed run does not delete results. Give an end time of at "
        "least " +
        sig6(on_disk.last_time) +
        " s, or start a new run. Nothing was "
        "changed.");

    // The mesh, the fields and the loop state of the checkpoint.
    the_simulator.load_checkpoint(latest, saved.time);
    state = saved;

    // A new Time/Time step is honoured from the checkpoint on; otherwise
    // the cut-back state goes on (within the new minimum).
    const std::string old_step =
      parameter_value(old_parameters, "Time/Time step");
    const bool step_changed = step_lengths.resume(state, old_step);

    // The rows and the files of the interrupted continuation after the
    // checkpoint are replaced by this run's.
    files.take_over(on_disk.kept);
    report.print_header(process_note);
    pcout << "  resumed from " << latest << " (step " << state.step
          << ", t = " << sig6(state.time) << " s)" << std::endl;
    if (step_changed)
      pcout << "  Time/Time step changed from " << old_step << " to "
            << sig6(k0) << " s: the run goes on with the new time step"
            << std::endl;
  }


  template void
  TimeLoop<2>::resume_from_checkpoint();
  template void
  TimeLoop<3>::resume_from_checkpoint();
} // namespace DynamicContact
