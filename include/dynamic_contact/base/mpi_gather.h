#ifndef dynamic_contact_mpi_gather_h
#define dynamic_contact_mpi_gather_h

#include <mpi.h>

#include <vector>

namespace DynamicContact
{
  /**
   * Collective: every process's @p local values, on every process, in rank
   * order (one MPI_Allgather of the sizes and one MPI_Allgatherv; on one
   * process a copy). The same result as deal.II's
   * Utilities::MPI::all_gather(comm, local), which serializes and
   * compresses each vector (boost::serialization and zlib) even on one
   * process: in a short run, the gathers of the contact boundary's
   * per-node values cost as much as the boundary's Newton iterations.
   */
  std::vector<std::vector<double>>
  all_gather_values(const MPI_Comm comm, const std::vector<double> &local);

  /**
   * Collective: the same on @p root only (MPI_Gather of the sizes and
   * MPI_Gatherv; the other processes get an empty list), in place of
   * Utilities::MPI::gather(comm, local, root).
   */
  std::vector<std::vector<double>>
  gather_values(const MPI_Comm             comm,
                const std::vector<double> &local,
                const unsigned int         root);
} // namespace DynamicContact

#endif
