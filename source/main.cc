#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/run/command_line.h>
#include <dynamic_contact/run/mpi_startup.h>
#include <dynamic_contact/run/provenance.h>
#include <dynamic_contact/run/time_loop.h>

#include <iostream>

namespace
{
  using namespace DynamicContact;

  /**
   * --print-parameters: the declarations, the moved entries, the defaults
   * (with the overrides) or a scene's values, on rank 0.
   */
  void
  print_parameters_command(const CommandLine &command_line, const bool root)
  {
    PrintFormat format = PrintFormat::prm;
    parse_print_format(command_line.print_format, format);
    if (format == PrintFormat::markdown || format == PrintFormat::moved)
      {
        // The declarations (both dimensions) or the moved entries,
        // not the values of a scene.
        if (root)
          print_parameters(std::cout, dealii::ParameterHandler(), format);
        return;
      }
    dealii::ParameterHandler prm;
    if (command_line.parameter_file.empty())
      {
        // Defaults, for the dimension an override may choose.
        dealii::ParameterHandler dimension_only;
        dimension_only.declare_entry("Dimension",
                                     "2",
                                     dealii::Patterns::Integer(2, 3));
        for (const auto &o : command_line.overrides)
          if (o.rfind("Dimension", 0) == 0)
            apply_override(dimension_only, o);
        RunParameters::declare_parameters(
          prm, dimension_only.get_integer("Dimension"));
        for (const auto &o : command_line.overrides)
          apply_override(prm, o);
      }
    else
      read_parameters(command_line.parameter_file, command_line.overrides, prm);
    if (root)
      print_parameters(std::cout, prm, format);
  }
} // namespace


int
main(int argc, char *argv[])
{
  using namespace DynamicContact;
  // A process started without mpirun (an MPI singleton) is started cheaply:
  // Open MPI without its daemon and its network probing (mpi_startup.h;
  // nothing changes under a launcher, and a setting of the user's wins).
  set_open_mpi_singleton_defaults();
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                           comm = MPI_COMM_WORLD;
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  // No error leaves a process waiting, and a signal stops the run after a
  // step with a checkpoint (README, "What can go wrong").
  initialize_error_handling(comm);
  install_stop_signal_handlers();
  note_resident_at_start();

  const CommandLine command_line = CommandLine::parse(argc, argv);
  if (!command_line.error.empty())
    {
      if (root)
        std::cerr << "dynamic-contact: error: " << command_line.error << "\n\n"
                  << CommandLine::usage();
      return 2;
    }
  if (command_line.help)
    {
      if (root)
        std::cout << CommandLine::usage();
      return 0;
    }
  if (command_line.version)
    {
      if (root)
        std::cout << CommandLine::version_text() << std::endl;
      return 0;
    }

  try
    {
      if (command_line.print_parameters)
        {
          print_parameters_command(command_line, root);
          return 0;
        }

      return run_simulation(command_line.parameter_file,
                            command_line.overrides,
                            comm,
                            command_line.resume,
                            command_line.resume_auto,
                            command_line.validate);
    }
  catch (const AgreedError &e)
    {
      // Every process has it (the run is over on all of them).
      if (root)
        std::cerr << "dynamic-contact: error: " << e.what() << std::endl;
      return 1;
    }
  catch (const std::exception &e)
    {
      const std::string message = dynamic_cast<const std::bad_alloc *>(&e) ?
                                    "out of memory (std::bad_alloc)" :
                                    error_message(e);
      if (!every_process_failed())
        abort_run(message);
      if (root)
        std::cerr << "dynamic-contact: error: " << message << std::endl;
      return 1;
    }
  catch (...)
    {
      if (!every_process_failed())
        abort_run("unknown exception");
      if (root)
        std::cerr << "dynamic-contact: error: unknown exception" << std::endl;
      return 1;
    }
}
