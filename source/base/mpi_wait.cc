#include <deal.II/base/exceptions.h>

#include <dynamic_contact/base/mpi_wait.h>

#include <algorithm>
#include <chrono>
#include <thread>

namespace DynamicContact
{
  bool
  wait_sleeping(MPI_Request &request,
                const double longest_sleep,
                const double timeout)
  {
    using clock      = std::chrono::steady_clock;
    const auto start = clock::now();
    double     sleep = 2e-6;
    for (;;)
      {
        int       done = 0;
        const int ierr = MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        AssertThrowMPI(ierr);
        if (done)
          return true;
        if (timeout >= 0 &&
            std::chrono::duration<double>(clock::now() - start).count() >
              timeout)
          return false;
        std::this_thread::sleep_for(std::chrono::duration<double>(sleep));
        sleep = std::min(2 * sleep, longest_sleep);
      }
  }
} // namespace DynamicContact
