#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/parameters/well_posedness_report.h>
#include <dynamic_contact/run/time_loop.h>

#include <iostream>
#include <memory>
#include <tuple>

namespace DynamicContact
{
  namespace
  {
    /**
     * On process 0 (@p rank): the scene is valid (with the @p summary of
     * its validation), and the report on its well-posedness.
     */
    template <int dim>
    void
    report_valid_scene(const RunParameters &parameters,
                       const std::string   &summary,
                       const unsigned int   rank)
    {
      if (rank == 0)
        std::cout << "dynamic-contact: the scene '" << parameters.parameter_file
                  << "' is valid (" << summary << "); Output/Directory '"
                  << parameters.output.directory << "' is not looked at."
                  << std::endl
                  << well_posedness_report<dim>(parameters) << std::flush;
    }


    /**
     * Run the @p simulator, on the first processes only where the scene is
     * small (Solver/Minimum DoFs per process): then the @p simulator is
     * made anew on the communicator @p group of the @p taking_part first
     * processes, and the others (where it is left empty) wait. Returns the
     * run's exit code (0 where it did not run).
     */
    template <int dim>
    int
    run_on_processes_taking_part(std::unique_ptr<TimeLoop<dim>> &simulator,
                                 const RunParameters            &parameters,
                                 ParameterHandler               &prm,
                                 const MPI_Comm                  comm,
                                 const bool                      resume,
                                 unsigned int                   &taking_part,
                                 MPI_Comm                       &group)
    {
      const unsigned int n_processes = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int rank        = Utilities::MPI::this_mpi_process(comm);
      int                exit_code   = 0;
      // A small scene runs on the first processes only
      // (Solver/Minimum DoFs per process); the others wait.
      std::string note;
      taking_part = simulator->processes_taking_part(note);
      if (taking_part < n_processes)
        {
          simulator.reset();
          MPI_Comm_split(comm,
                         rank < taking_part ? 0 : MPI_UNDEFINED,
                         rank,
                         &group);
          if (rank < taking_part)
            {
              restrict_error_handling(group);
              simulator =
                std::make_unique<TimeLoop<dim>>(parameters, prm, group);
              simulator->set_process_note(note);
            }
        }
      if (simulator)
        exit_code = simulator->run(resume);
      return exit_code;
    }
  } // namespace


  template <int dim>
  int
  run_dimension(const RunParameters &parameters,
                ParameterHandler    &prm,
                const MPI_Comm       comm,
                const bool           resume,
                const bool           validate)
  {
    const unsigned int n_processes = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int rank        = Utilities::MPI::this_mpi_process(comm);
    // Catch inside the simulator's lifetime, so that it is destroyed with no
    // exception in flight (its timer would otherwise warn about it).
    std::string  error;
    int          exit_code   = 0;
    unsigned int taking_part = n_processes;
    MPI_Comm     group       = MPI_COMM_NULL;
    {
      auto simulator = std::make_unique<TimeLoop<dim>>(parameters, prm, comm);
      try
        {
          if (validate)
            report_valid_scene<dim>(parameters, simulator->validate(), rank);
          else
            exit_code = run_on_processes_taking_part(
              simulator, parameters, prm, comm, resume, taking_part, group);
        }
      catch (const std::exception &e)
        {
          error = dynamic_cast<const std::bad_alloc *>(&e) ?
                    "out of memory (std::bad_alloc)" :
                    error_message(e);
          if (error.empty())
            error = "unknown error";
          // Known to this process alone: the others may be waiting in a
          // collective operation; end them all from here.
          if (!every_process_failed())
            {
              if (simulator)
                simulator->abandon(error, true);
              abort_run(error);
            }
          if (simulator)
            simulator->abandon(error);
        }
    }
    if (taking_part < n_processes)
      {
        // Every process ends as the processes that took part did.
        std::tie(exit_code, error) = wait_for_ending(comm, exit_code, error);
        if (group != MPI_COMM_NULL)
          MPI_Comm_free(&group);
      }
    if (!error.empty())
      throw AgreedError(error);
    return exit_code;
  }


  int
  run_simulation(const std::string              &parameter_file,
                 const std::vector<std::string> &overrides,
                 const MPI_Comm                  comm,
                 bool                            resume,
                 const bool                      resume_auto,
                 const bool                      validate)
  {
    ParameterHandler    prm;
    const RunParameters parameters =
      read_parameters(parameter_file, overrides, prm);
    if (resume_auto)
      {
        resume = !list_checkpoints(parameters.output.directory, comm).empty();
        if (!resume && Utilities::MPI::this_mpi_process(comm) == 0)
          std::cout << "--resume=auto: no checkpoint in Output/Directory '"
                    << parameters.output.directory << "': a new run."
                    << std::endl;
      }
    if (parameters.dimension == 2)
      return run_dimension<2>(parameters, prm, comm, resume, validate);
    else
      return run_dimension<3>(parameters, prm, comm, resume, validate);
  }
} // namespace DynamicContact
