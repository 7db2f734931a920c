#ifndef dynamic_contact_fault_injection_h
#define dynamic_contact_fault_injection_h

#include <deal.II/base/types.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * Fault injection for the tests: the one place that reads it from the
   * environment (instance(), read once per process; malformed values are
   * refused with one error naming the variable).
   *
   * - DYNAMIC_CONTACT_KILL = "after-step N" or "in-checkpoint N" (the run
   *   kills itself with SIGKILL after step N, or while writing the
   *   checkpoint of step N: everything written, not yet renamed), or
   *   "signal S after-step N [rank R]" (raise signal S on rank R, default
   *   0, after step N);
   * - DYNAMIC_CONTACT_FAIL = "after-step N [rank R]" (throw an error on
   *   rank R alone after step N);
   * - DYNAMIC_CONTACT_DISK_FULL: a full disk for the output layer
   *   (output_directory.h), see DiskFull.
   *
   * The run loop consults after_step() and in_checkpoint(), the output
   * layer disk_full; nothing else reads these variables.
   */
  struct FaultInjection
  {
    /**
     * DYNAMIC_CONTACT_DISK_FULL: "BYTES" lets this process write that many
     * bytes, then every write fails with "No space left on device";
     * "NAME[:N][@R]" fills the disk during the N-th write (default 1) to a
     * file called NAME (its base name) on rank R (default: any): that write
     * stores half of its bytes and fails, and so does every later one.
     */
    struct DiskFull
    {
      bool           active      = false;
      bool           budget_mode = false;
      std::uintmax_t budget      = 0;
      std::string    name;
      unsigned int   nth   = 1;
      int            rank  = -1;
      unsigned int   count = 0;
      bool           full  = false;

      /** From the value of DYNAMIC_CONTACT_DISK_FULL (nullptr: none). */
      explicit DiskFull(const char *value = nullptr);

      /** How many of @p n bytes a write to @p file may store. */
      std::size_t
      allowance(const std::string &file, const std::size_t n);

      /** Whether @p bytes would fit (without writing them). */
      bool
      fits(const std::string &file, const std::uintmax_t bytes);
    };

    /** The faults this process's environment asks for. */
    static FaultInjection &
    instance();

    unsigned int kill_after_step    = numbers::invalid_unsigned_int;
    unsigned int kill_in_checkpoint = numbers::invalid_unsigned_int;
    int          signal             = 0;
    unsigned int signal_after_step  = numbers::invalid_unsigned_int;
    unsigned int signal_rank        = 0;
    unsigned int fail_after_step    = numbers::invalid_unsigned_int;
    unsigned int fail_rank          = 0;
    DiskFull     disk_full;

    /** After step @p step on process @p rank: kill, raise or throw. */
    void
    after_step(const unsigned int step, const unsigned int rank) const;

    /** While the checkpoint of step @p step is written: kill. */
    void
    in_checkpoint(const unsigned int step) const;

  private:
    /** Read the environment. */
    FaultInjection();
  };
} // namespace DynamicContact

#endif
