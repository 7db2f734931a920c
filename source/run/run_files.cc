#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/output/resume.h>
#include <dynamic_contact/run/run_files.h>

#include <chrono>
#include <iostream>

namespace DynamicContact
{
  template <int dim>
  RunFiles<dim>::RunFiles(const RunParameters &parameters,
                          ParameterHandler    &prm,
                          const MPI_Comm       comm,
                          Simulator<dim>      &simulator,
                          TimerOutput         &timer,
                          ScreenLog           &screen_log,
                          const RunState      &state)
    : parameters(parameters)
    , comm(comm)
    , simulator(simulator)
    , timer(timer)
    , screen_log(screen_log)
    , state(state)
    , directory(parameters.output.directory, comm)
    , parameter_files(prm, parameters)
    , parameters_as_text(parameters_text(prm,
                                         parameters.geometry.type ==
                                             Parameters::Geometry::Type::gmsh ?
                                           parameters.geometry.mesh_file :
                                           std::string()))
  {}


  template <int dim>
  void
  RunFiles<dim>::start_new_run()
  {
    // The directory is ours (locked, no foreign results), the results of
    // an earlier run in it are gone.
    directory.open(false);
    write_status("running");
    write_provenance(false);
    start_writers(false);
  }


  template <int dim>
  void
  RunFiles<dim>::open_for_resume()
  {
    directory.open(true);
  }


  template <int dim>
  void
  RunFiles<dim>::take_over(const std::string &kept)
  {
    last_checkpoint_step = state.step;
    write_status("running");
    take_over_results_after(directory, kept, state.step, comm);
    start_writers(true);
    vtu_writer->set_records(state.vtu_records);
    // The indexes list the VTU files up to the checkpoint only (none: they
    // are removed).
    vtu_writer->write_index();
    write_provenance(true);
  }


  template <int dim>
  void
  RunFiles<dim>::start_writers(const bool resume)
  {
    time_series_writer =
      std::make_unique<TimeSeriesWriter>(directory, comm, resume);
    vtu_writer =
      std::make_unique<VtuWriter<dim>>(directory,
                                       comm,
                                       parameters.boundary_conditions.contact,
                                       parameters.output.vtu_subdivisions);
  }


  template <int dim>
  void
  RunFiles<dim>::output_results(const unsigned int n,
                                const double       t,
                                const bool         contact_csv,
                                const bool         vtu)
  {
    TimerSection scope(timer, "Output");
    if (contact_csv)
      simulator.fields().write_contact_csv(directory, n, t);
    if (vtu)
      {
        const auto start = std::chrono::steady_clock::now();
        simulator.fields().write_vtu(*vtu_writer, n, t);
        vtu_times.seconds += std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
        ++vtu_times.files;
      }
  }


  template <int dim>
  void
  RunFiles<dim>::checkpoint()
  {
    TimerSection scope(timer, "Checkpoint");
    RunState     saved = state;
    saved.vtu_records  = vtu_writer->get_records();
    simulator.fields().save_checkpoint(directory,
                                       saved,
                                       parameters_as_text,
                                       parameters.checkpoint.keep,
                                       [this]() { faults.in_checkpoint(state.step);
                                       });
    last_checkpoint_step = state.step;
  }


  template <int dim>
  void
  RunFiles<dim>::write_last_good_state()
  {
    output_results(state.step,
                   state.time,
                   true,
                   vtu_writer != nullptr && parameters.output.write_vtu);
    checkpoint();
  }


  template <int dim>
  void
  RunFiles<dim>::write_status(const std::string &status)
  {
    collectively(comm, [&]() { directory.write_status(status); });
    took_over = true;
  }


  template <int dim>
  void
  RunFiles<dim>::write_provenance(const bool resume)
  {
    collectively_on_rank_zero(comm, [&]() {
      screen_log.open(directory, resume);
      parameter_files.write(directory);
    });
  }


  template <int dim>
  void
  RunFiles<dim>::write_log(const bool close)
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
  RunFiles<dim>::close_log_after_error(const std::string &reason)
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
  RunFiles<dim>::abandon(const std::string &reason, const bool alone)
  {
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
            directory.write_status("failed: " + reason);
          }
        else
          {
            StatusFile status;
            status.open(directory.file("run_status"));
            status.write("failed: " + reason);
          }
      }
    catch (const std::exception &e)
      {
        std::cerr << "dynamic-contact: " << e.what() << std::endl;
      }
  }


  template class RunFiles<2>;
  template class RunFiles<3>;
} // namespace DynamicContact
