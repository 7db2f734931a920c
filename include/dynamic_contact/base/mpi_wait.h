#ifndef dynamic_contact_mpi_wait_h
#define dynamic_contact_mpi_wait_h

#include <mpi.h>

namespace DynamicContact
{
  /**
   * Wait for @p request (a nonblocking MPI operation) without keeping a
   * core busy: MPI_Test, then sleep, the sleeps growing from a few
   * microseconds to @p longest_sleep seconds. A blocking MPI call polls
   * without pause (Open MPI over shared memory), and a process that waits
   * so for another's long work takes memory bandwidth and, where the
   * machine's cores are hyperthreads of one another, the core itself from
   * the process it waits for. True when the request completed; false
   * after @p timeout seconds (negative: no limit), the request then still
   * pending.
   */
  bool
  wait_sleeping(MPI_Request &request,
                const double longest_sleep,
                const double timeout = -1);
} // namespace DynamicContact

#endif
