#ifndef dynamic_contact_failure_h
#define dynamic_contact_failure_h

#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/error_messages.h>

#include <stdexcept>
#include <utility>
#include <string>

namespace DynamicContact
{
  /**
   * A step the solver could not solve (Newton did not converge, or the
   * solution is not finite): the time loop answers with a shorter step.
   * Thrown on every process alike (the decisions use global quantities).
   */
  class StepFailure : public std::runtime_error
  {
  public:
    explicit StepFailure(const std::string &what,
                         const unsigned int newton_iterations = 0)
      : std::runtime_error(what)
      , newton_iterations(newton_iterations)
    {}

    /** The Newton iterations spent on the failed solve (if known). */
    unsigned int newton_iterations;
  };


  /**
   * How a run ends when something goes wrong on some of its processes, and
   * how it stops on a signal (README, "What can go wrong").
   *
   * - An error that every process knows is a CollectiveError: it is thrown
   *   on all of them together (check_collectively), so every process leaves
   *   the time loop at the same point, rank 0 writes run_status and prints
   *   the message, and every process exits with code 1.
   * - Any other exception may be known to some processes only (the others
   *   wait in a collective operation for ever). Whoever catches one calls
   *   every_process_failed(): if every process arrives there within a few
   *   seconds the error was collective after all; otherwise the process
   *   writes run_status and the message itself and ends the whole job with
   *   MPI_Abort (abort_run). No error leaves a process waiting.
   * - SIGTERM, SIGINT, SIGHUP and SIGUSR1 only set a flag; the time loop
   *   asks every process for it after each step (signal_to_stop) and stops
   *   all of them after the same step.
   */

  /** An error known to every process of the run, thrown on all of them. */
  class CollectiveError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * An error every process has agreed on (after every_process_failed()):
   * main prints it (rank 0) and returns 1, nothing else to do.
   */
  class AgreedError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * Collective: the message of the lowest rank whose @p local_message is not
   * empty, on every process ("" if every one is empty).
   */
  std::string
  collective_message(const MPI_Comm comm, const std::string &local_message);

  /**
   * Collective. Every process passes its local error message ("" for none);
   * if any process has one, every process throws a CollectiveError with the
   * message of the lowest rank that has one.
   */
  void
  check_collectively(const MPI_Comm comm, const std::string &local_error);

  /**
   * Collective. Run @p f; an exception it throws on any process becomes a
   * CollectiveError on every process (with the message of the lowest rank).
   */
  template <typename F>
  void
  collectively(const MPI_Comm comm, F &&f)
  {
    std::string error;
    try
      {
        f();
      }
    catch (const std::bad_alloc &)
      {
        error = "out of memory (std::bad_alloc)";
      }
    catch (const std::exception &e)
      {
        error = error_message(e);
        if (error.empty())
          error = "unknown error";
      }
    check_collectively(comm, error);
  }

  /**
   * Collective: collectively() for @p f run on rank 0 of @p comm alone (a
   * file that rank 0 writes for all).
   */
  template <typename F>
  void
  collectively_on_rank_zero(const MPI_Comm comm, F &&f)
  {
    collectively(comm, [&]() {
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        f();
    });
  }

  /**
   * Collective, once, right after MPI_Init: the communicator on which the
   * processes that caught an error meet (a duplicate of @p world, so that
   * it cannot be confused with any operation of the run).
   */
  void
  initialize_error_handling(const MPI_Comm world);

  /**
   * Called by a process that caught an error: true if every process of the
   * run calls it too within @p timeout seconds (the error was collective),
   * false if some process does not (it waits elsewhere: call abort_run).
   * Without initialize_error_handling, or on one process: true.
   */
  bool
  every_process_failed(const double timeout = 5);

  /**
   * Collective on @p group: from now on every_process_failed() meets on
   * (a duplicate of) @p group, the processes that take part in the run,
   * not on every process (the others wait in wait_for_ending()).
   */
  void
  restrict_error_handling(const MPI_Comm group);

  /**
   * Collective on @p comm, for a run that only some of its processes take
   * part in (rank 0 among them): every process waits, sleeping between
   * polls, until all have arrived, then gets rank 0's @p exit_code and
   * @p error.
   */
  std::pair<int, std::string>
  wait_for_ending(const MPI_Comm     comm,
                  const int          exit_code,
                  const std::string &error);

  /**
   * End the whole job from this process: print "dynamic-contact: error:
   * @p message" (naming this process if it is not rank 0) and call
   * MPI_Abort on MPI_COMM_WORLD with @p exit_code.
   */
  [[noreturn]] void
  abort_run(const std::string &message, const int exit_code = 1);

  /**
   * Install the handlers of SIGTERM, SIGINT, SIGHUP and SIGUSR1: they record
   * the signal (the first one) and return; the time loop stops after the
   * current step (Simulator::advance).
   */
  void
  install_stop_signal_handlers();

  /**
   * Collective: the signal any process received (the largest number if
   * several), 0 if none.
   */
  int
  signal_to_stop(const MPI_Comm comm);

  /** "SIGTERM" etc. for the signals above, else "signal N". */
  std::string
  signal_name(const int signal);
} // namespace DynamicContact

#endif
