#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/time/time_loop.h>

#include <iostream>

namespace DynamicContact
{
  template <int dim>
  int
  run_dimension(const RunParameters &parameters,
                ParameterHandler    &prm,
                const MPI_Comm       comm,
                const bool           resume,
                const bool           validate)
  {
    // Catch inside the simulator's lifetime, so that it is destroyed with no
    // exception in flight (its timer would otherwise warn about it).
    std::string error;
    int         exit_code = 0;
    {
      TimeLoop<dim> simulator(parameters, prm, comm);
      try
        {
          if (validate)
            {
              const std::string summary = simulator.validate();
              if (Utilities::MPI::this_mpi_process(comm) == 0)
                std::cout << "dynamic-contact: the scene '"
                          << parameters.parameter_file << "' is valid ("
                          << summary << "); Output/Directory '"
                          << parameters.output.directory
                          << "' is not looked at." << std::endl;
            }
          else
            exit_code = simulator.run(resume);
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
              simulator.abandon(error, true);
              abort_run(error);
            }
          simulator.abandon(error);
        }
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
