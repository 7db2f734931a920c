#ifndef dynamic_contact_resources_h
#define dynamic_contact_resources_h

#include <deal.II/base/mpi.h>

#include <dynamic_contact/parameters/parameters.h>

namespace DynamicContact
{
  /**
   * Before anything is allocated: the cells, DoFs and memory a scene of
   * dimension @p dim needs for a coarse mesh of @p n_coarse_cells (after
   * Geometry/Global refinements, Finite element/Polynomial degree); refuse
   * (CollectiveError) a scene that cannot fit into the memory of the hosts
   * of the run, or that this build of deal.II cannot count, with the
   * estimate and what to reduce. Returns the bytes one process may use:
   * Solver/Memory per process, or what each host has available now shared
   * by the processes of @p comm on it, the least over the hosts.
   */
  double
  check_resources(const RunParameters &parameters,
                  const unsigned int   dim,
                  const double         n_coarse_cells,
                  const MPI_Comm       comm);
} // namespace DynamicContact

#endif
