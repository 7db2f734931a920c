#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/memory_report.h>

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace DynamicContact
{
  double
  resident_bytes()
  {
    Utilities::System::MemoryStats stats;
    Utilities::System::get_memory_stats(stats);
    return 1024. * stats.VmRSS;
  }


  namespace
  {
    double resident_at_start = 0;


    /**
     * The proportional set size of this process (Linux: Pss of
     * /proc/self/smaps_rollup), in bytes: its resident memory with every
     * page it shares with other processes (the libraries' code, above all)
     * divided among them. 0 where the system does not say.
     */
    double
    proportional_bytes()
    {
      std::FILE *file = std::fopen("/proc/self/smaps_rollup", "r");
      if (file == nullptr)
        return 0;
      char   line[256];
      double kilobytes = 0;
      while (std::fgets(line, sizeof(line), file) != nullptr)
        if (std::sscanf(line, "Pss: %lf kB", &kilobytes) == 1)
          break;
      std::fclose(file);
      return 1024. * kilobytes;
    }
  } // namespace


  void
  note_resident_at_start()
  {
    resident_at_start = resident_bytes();
  }


  double
  heap_in_use()
  {
    const struct mallinfo2 heap = mallinfo2();
    return double(heap.uordblks) + double(heap.hblkhd);
  }


  void
  return_free_memory()
  {
    malloc_trim(0);
  }


  HeapGrowth::HeapGrowth()
    : start(heap_in_use())
  {}


  double
  HeapGrowth::measured() const
  {
    return std::max(0., heap_in_use() - start);
  }


  namespace
  {
    std::string
    table_row(const std::string &name,
              const double       total,
              const double       largest,
              const double       n_dofs,
              const bool         measured)
    {
      char line[160];
      std::snprintf(line,
                    sizeof(line),
                    "    %-34s %10.1f %10.1f %9.0f%s\n",
                    name.c_str(),
                    total / 1048576.,
                    largest / 1048576.,
                    total / std::max(n_dofs, 1.),
                    measured ? "  (measured)" : "");
      return line;
    }
  } // namespace


  std::string
  memory_table(const MemoryItems            &parts,
               const types::global_dof_index n_dofs,
               const MPI_Comm                comm)
  {
    MemoryItems items;
    if (resident_at_start > 0)
      items.push_back(
        {"program, libraries, MPI (at start)", resident_at_start, true});
    items.insert(items.end(), parts.begin(), parts.end());
    // Per process: the items, their sum, what they leave of the resident
    // memory, the resident memory now and at its peak.
    std::vector<double> bytes;
    double              accounted = 0;
    for (const auto &item : items)
      {
        bytes.push_back(item.bytes);
        accounted += item.bytes;
      }
    Utilities::System::MemoryStats stats;
    Utilities::System::get_memory_stats(stats);
    const double resident = 1024. * stats.VmRSS;
    for (const double b : {accounted,
                           std::max(0., resident - accounted),
                           resident,
                           1024. * stats.VmHWM,
                           proportional_bytes()})
      bytes.push_back(b);
    std::vector<double> total(bytes.size()), largest(bytes.size());
    Utilities::MPI::sum(bytes, comm, total);
    Utilities::MPI::max(bytes, comm, largest);
    const double       N = n_dofs;
    const unsigned int n = items.size();

    std::ostringstream out;
    out << "  memory (" << n_dofs << " DoFs on "
        << Utilities::MPI::n_mpi_processes(comm)
        << " processes): MB in all, MB on the largest process, bytes per "
           "DoF\n";
    for (unsigned int i = 0; i < n; ++i)
      out << table_row(
        items[i].name, total[i], largest[i], N, items[i].measured);
    const char *totals[] = {"the items above",
                            "not itemized",
                            "resident now",
                            "peak resident",
                            "resident now, shared pages split"};
    // The last one only where every process could measure it.
    const double least_proportional =
      Utilities::MPI::min(bytes.back(), comm);
    for (unsigned int i = 0; i < 5; ++i)
      if (i < 4 || least_proportional > 0)
        out << table_row(totals[i], total[n + i], largest[n + i], N, i >= 2);
    return out.str();
  }
} // namespace DynamicContact
