#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/run/time_loop.h>

#include <algorithm>
#include <cstdlib>
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
    output_directory->open(true);

    const std::string latest = newest_good_checkpoint(directory, comm, pcout);
    const RunState    saved  = read_run_state(latest, comm);
    check_resumable(latest, saved, parameters_of_run, parameters, comm);
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
    state                = saved;
    last_checkpoint_step = state.step;

    // A new Time/Time step is honoured from the checkpoint on; otherwise
    // the cut-back state goes on (within the new minimum).
    const std::string old_step =
      parameter_value(old_parameters, "Time/Time step");
    const bool step_changed =
      !old_step.empty() && std::strtod(old_step.c_str(), nullptr) != k0;
    if (step_changed)
      {
        state.time_step                = k0;
        state.good_steps_since_cutback = 0;
      }
    else
      state.time_step = std::max(std::min(state.time_step,
                                          parameters.time.adaptive ?
                                            parameters.time.maximum_time_step :
                                            k0),
                                 parameters.time.minimum_time_step);

    // The rows and the files of the interrupted continuation after the
    // checkpoint are replaced by this run's.
    write_status("running");
    take_over_results_after(*output_directory, on_disk.kept, state.step, comm);
    time_series_writer =
      std::make_unique<TimeSeriesWriter>(*output_directory, comm, true);
    vtu_writer =
      std::make_unique<VtuWriter<dim>>(*output_directory,
                                       comm,
                                       parameters.boundary_conditions.contact,
                                       parameters.output.vtu_subdivisions);
    vtu_writer->set_records(state.vtu_records);
    // The indexes list the VTU files up to the checkpoint only (none: they
    // are removed).
    vtu_writer->write_index();
    write_provenance(true);
    print_header();
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
