#ifndef dynamic_contact_memory_report_h
#define dynamic_contact_memory_report_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <algorithm>
#include <string>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * What one part of the program holds on this process: counted from its
   * sizes (a matrix's values, a vector's entries), or measured as the growth
   * of the heap in use while it was built (a factorization or an AMG
   * hierarchy, whose libraries do not say).
   */
  struct MemoryItem
  {
    std::string name;
    double      bytes    = 0;
    bool        measured = false;
  };

  using MemoryItems = std::vector<MemoryItem>;

  /** The resident memory (VmRSS) of this process now, in bytes. */
  double
  resident_bytes();

  /**
   * Note the resident memory now as that of the program, its libraries and
   * MPI (the program calls this after MPI_Init, before it reads its
   * input); memory_table() lists it.
   */
  void
  note_resident_at_start();

  /**
   * The bytes this process has allocated and not freed (glibc's count of
   * the heap in use, memory mapped blocks included).
   */
  double
  heap_in_use();

  /**
   * Give the heap's free pages back to the system (malloc_trim). A library
   * that builds a large object (an AMG hierarchy, a factorization) frees
   * several times what it keeps; without this, the process's resident
   * memory stays at that peak.
   */
  void
  return_free_memory();

  /**
   * Measures the growth of this process's heap in use from its
   * construction to measured(): what a library allocated in between and
   * still holds (its temporaries, freed again, are not counted).
   */
  class HeapGrowth
  {
  public:
    HeapGrowth();

    double
    measured() const;

    /**
     * @p largest = max(@p largest, measured()): what a library's first
     * build of an object holds (a rebuild that frees the object it
     * replaces measures only the difference).
     */
    void
    keep_largest(double &largest) const
    {
      largest = std::max(largest, measured());
    }

  private:
    const double start;
  };

  /**
   * The memory table of a run (collective): each item summed over the
   * processes and the largest share of one process, in MB and in bytes per
   * DoF of @p n_dofs; then their total, the resident memory now and the
   * peak (VmHWM), both summed over the processes, and what the items do
   * not account for (libraries, the mesh's and the output's temporaries,
   * the heap's free space); last, where the system says it (Linux), the
   * resident memory now with each page that processes share (the
   * libraries' code) divided among them: summed over the processes of a
   * node, what the node holds, where the sum of the resident memory counts
   * the shared pages once per process.
   */
  std::string
  memory_table(const MemoryItems            &items,
               const types::global_dof_index n_dofs,
               const MPI_Comm                comm);
} // namespace DynamicContact

#endif
