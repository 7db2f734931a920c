#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/mpi_wait.h>

#include <chrono>
#include <csignal>
#include <iostream>
#include <thread>

namespace DynamicContact
{
  using namespace dealii;

  std::string
  collective_message(const MPI_Comm comm, const std::string &local_message)
  {
    const unsigned int n_processes = Utilities::MPI::n_mpi_processes(comm);
    if (n_processes == 1)
      return local_message;
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    const unsigned int first =
      Utilities::MPI::min(local_message.empty() ? n_processes : rank, comm);
    if (first == n_processes)
      return "";
    return Utilities::MPI::broadcast(comm, local_message, first);
  }


  void
  check_collectively(const MPI_Comm comm, const std::string &local_error)
  {
    const std::string message = collective_message(comm, local_error);
    if (!message.empty())
      throw CollectiveError(message);
  }


  namespace
  {
    MPI_Comm error_communicator = MPI_COMM_NULL;

    volatile std::sig_atomic_t stop_signal = 0;

    extern "C" void
    record_stop_signal(int signal)
    {
      if (stop_signal == 0)
        stop_signal = signal;
    }
  } // namespace


  void
  initialize_error_handling(const MPI_Comm world)
  {
    if (error_communicator == MPI_COMM_NULL)
      MPI_Comm_dup(world, &error_communicator);
  }


  namespace
  {
    /**
     * Wait, sleeping between polls, until every process of @p comm has
     * arrived here (true) or @p timeout seconds have passed (false; the
     * barrier is left pending). A negative timeout waits for ever.
     */
    bool
    meet(const MPI_Comm comm, const double timeout)
    {
      MPI_Request request;
      MPI_Ibarrier(comm, &request);
      // Up to 20 ms between polls: processes that wait for a whole run
      // (wait_for_ending()) wake 50 times a second.
      return wait_sleeping(request, 0.02, timeout);
    }
  } // namespace


  bool
  every_process_failed(const double timeout)
  {
    if (error_communicator == MPI_COMM_NULL)
      return true;
    int size = 1;
    MPI_Comm_size(error_communicator, &size);
    if (size == 1)
      return true;
    return meet(error_communicator, timeout);
  }


  void
  restrict_error_handling(const MPI_Comm group)
  {
    // The duplicate of every process is left as it is: the processes that
    // do not take part never meet on it again.
    MPI_Comm restricted = MPI_COMM_NULL;
    MPI_Comm_dup(group, &restricted);
    error_communicator = restricted;
  }


  std::pair<int, std::string>
  wait_for_ending(const MPI_Comm     comm,
                  const int          exit_code,
                  const std::string &error)
  {
    meet(comm, -1);
    return {Utilities::MPI::broadcast(comm, exit_code, 0),
            Utilities::MPI::broadcast(comm, error, 0)};
  }


  void
  abort_run(const std::string &message, const int exit_code)
  {
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    std::cerr << "dynamic-contact: error: " << message;
    if (size > 1)
      std::cerr << " (on process " << rank << " of " << size
                << " only: ending all of them)";
    std::cerr << std::endl;
    // mpirun forwards this process's output through a pipe that it reads
    // in the same loop in which it handles the abort: without a pause, the
    // message can be lost when mpirun ends the processes first.
    if (size > 1)
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    MPI_Abort(MPI_COMM_WORLD, exit_code);
    std::_Exit(exit_code); // not reached
  }


  void
  install_stop_signal_handlers()
  {
    struct sigaction action = {};
    action.sa_handler       = record_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    for (const int s : {SIGTERM, SIGINT, SIGHUP, SIGUSR1})
      sigaction(s, &action, nullptr);
  }


  int
  signal_to_stop(const MPI_Comm comm)
  {
    return Utilities::MPI::max(static_cast<int>(stop_signal), comm);
  }


  std::string
  signal_name(const int signal)
  {
    switch (signal)
      {
        case SIGTERM:
          return "SIGTERM";
        case SIGINT:
          return "SIGINT";
        case SIGHUP:
          return "SIGHUP";
        case SIGUSR1:
          return "SIGUSR1";
        default:
          return "signal " + std::to_string(signal);
      }
  }
} // namespace DynamicContact
