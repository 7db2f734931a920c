#include <deal.II/base/exceptions.h>

#include <dynamic_contact/base/fault_injection.h>

#include <mpi.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

namespace DynamicContact
{
  namespace
  {
    /** This process's rank in MPI_COMM_WORLD (0 outside MPI). */
    int
    this_rank()
    {
      int initialized = 0, finalized = 0;
      MPI_Initialized(&initialized);
      MPI_Finalized(&finalized);
      int r = 0;
      if (initialized && !finalized)
        MPI_Comm_rank(MPI_COMM_WORLD, &r);
      return r;
    }
  } // namespace


  FaultInjection &
  FaultInjection::instance()
  {
    static FaultInjection faults;
    return faults;
  }


  FaultInjection::DiskFull::DiskFull(const char *value)
  {
    if (value == nullptr || *value == '\0')
      return;
    active = true;
    std::string text(value);
    if (std::all_of(text.begin(), text.end(), ::isdigit))
      {
        budget_mode = true;
        budget      = std::stoull(text);
        return;
      }
    const auto at = text.find('@');
    if (at != std::string::npos)
      {
        rank = std::stoi(text.substr(at + 1));
        text = text.substr(0, at);
      }
    const auto colon = text.find(':');
    if (colon != std::string::npos)
      {
        nth  = std::stoul(text.substr(colon + 1));
        text = text.substr(0, colon);
      }
    name = text;
  }


  std::size_t
  FaultInjection::DiskFull::allowance(const std::string &file,
                                      const std::size_t  n)
  {
    if (!active)
      return n;
    if (budget_mode)
      {
        const std::size_t allowed =
          static_cast<std::size_t>(std::min<std::uintmax_t>(n, budget));
        budget -= allowed;
        return allowed;
      }
    if (full)
      return 0;
    if (std::filesystem::path(file).filename() == name &&
        (rank < 0 || rank == this_rank()) && ++count == nth)
      {
        full = true;
        return n / 2;
      }
    return n;
  }


  bool
  FaultInjection::DiskFull::fits(const std::string  &file,
                                 const std::uintmax_t bytes)
  {
    if (!active)
      return true;
    if (budget_mode)
      return bytes <= budget;
    return allowance(file, 2) == 2;
  }


  FaultInjection::FaultInjection()
    : disk_full(std::getenv("DYNAMIC_CONTACT_DISK_FULL"))
  {
    if (const char *kill = std::getenv("DYNAMIC_CONTACT_KILL"))
      {
        std::istringstream in(kill);
        std::string        where, word;
        unsigned int       at = 0;
        in >> where;
        bool ok = false;
        if (where == "signal")
          {
            in >> signal >> word >> signal_after_step;
            ok = in && word == "after-step" && signal > 0;
            if (ok && in >> word)
              ok = word == "rank" && static_cast<bool>(in >> signal_rank);
          }
        else
          {
            in >> at;
            ok = in && (where == "after-step" || where == "in-checkpoint");
            if (ok)
              (where == "after-step" ? kill_after_step : kill_in_checkpoint) =
                at;
          }
        AssertThrow(ok,
                    ExcMessage("The environment variable DYNAMIC_CONTACT_KILL "
                               "(fault injection for tests) must read "
                               "'after-step N', 'in-checkpoint N' or 'signal "
                               "S after-step N [rank R]', not '" +
                               std::string(kill) + "'."));
      }
    if (const char *fail = std::getenv("DYNAMIC_CONTACT_FAIL"))
      {
        std::istringstream in(fail);
        std::string        word;
        in >> word >> fail_after_step;
        bool ok = in && word == "after-step";
        if (ok && in >> word)
          ok = word == "rank" && static_cast<bool>(in >> fail_rank);
        AssertThrow(ok,
                    ExcMessage("The environment variable DYNAMIC_CONTACT_FAIL "
                               "(fault injection for tests) must read "
                               "'after-step N [rank R]', not '" +
                               std::string(fail) + "'."));
      }
  }


  void
  FaultInjection::after_step(const unsigned int step,
                             const unsigned int rank) const
  {
    if (kill_after_step == step)
      std::raise(SIGKILL);
    if (signal_after_step == step && signal_rank == rank)
      std::raise(signal);
    if (fail_after_step == step && fail_rank == rank)
      throw std::runtime_error("injected failure after step " +
                               std::to_string(step) +
                               " (DYNAMIC_CONTACT_FAIL)");
  }


  void
  FaultInjection::in_checkpoint(const unsigned int step) const
  {
    if (kill_in_checkpoint == step)
      std::raise(SIGKILL);
  }
} // namespace DynamicContact
