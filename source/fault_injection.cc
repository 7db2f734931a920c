#include <deal.II/base/exceptions.h>

#include <dynamic_contact/fault_injection.h>

#include <csignal>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace DynamicContact
{
  FaultInjection::FaultInjection()
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
} // namespace DynamicContact
