#ifndef dynamic_contact_fault_injection_h
#define dynamic_contact_fault_injection_h

#include <deal.II/base/types.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * Fault injection for the tests, from the environment:
   * DYNAMIC_CONTACT_KILL = "after-step N" or "in-checkpoint N" (the run
   * kills itself with SIGKILL after step N, or while writing the
   * checkpoint of step N: everything written, not yet renamed), or
   * "signal S after-step N [rank R]" (raise signal S on rank R, default 0,
   * after step N); DYNAMIC_CONTACT_FAIL = "after-step N [rank R]" (throw
   * an error on rank R alone after step N). Malformed values are refused.
   */
  struct FaultInjection
  {
    FaultInjection();

    unsigned int kill_after_step    = numbers::invalid_unsigned_int;
    unsigned int kill_in_checkpoint = numbers::invalid_unsigned_int;
    int          signal             = 0;
    unsigned int signal_after_step  = numbers::invalid_unsigned_int;
    unsigned int signal_rank        = 0;
    unsigned int fail_after_step    = numbers::invalid_unsigned_int;
    unsigned int fail_rank          = 0;

    /** After step @p step on process @p rank: kill, raise or throw. */
    void
    after_step(const unsigned int step, const unsigned int rank) const;
  };
} // namespace DynamicContact

#endif
