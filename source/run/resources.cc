#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/contact/cost_model.h>
#include <dynamic_contact/run/resources.h>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    /**
     * A lower bound of the memory of a scene of @p dofs DoFs (elements of
     * @p degree): a third of what the memory model predicts with the
     * preconditioner of least memory that Solver/Preconditioner of
     * @p parameters allows.
     */
    double
    least_memory_bound(const Parameters::Solver &parameters,
                       const unsigned int        dim,
                       const unsigned int        degree,
                       const double              dofs)
    {
      double bytes = std::numeric_limits<double>::infinity();
      for (const std::string &candidate :
           preconditioner_candidates(parameters, degree))
        bytes =
          std::min(bytes,
                   predicted_memory(parameters.preconditioner_plugin(candidate),
                                    dim,
                                    degree,
                                    static_cast<types::global_dof_index>(
                                      std::min(dofs, 4294967295.)),
                                    1,
                                    0.) /
                     3);
      return bytes;
    }


    /**
     * The memory available on this host, in bytes: MemAvailable of
     * /proc/meminfo, else the available physical pages.
     */
    double
    memory_available_here()
    {
      double        available = 0;
      std::ifstream meminfo("/proc/meminfo");
      std::string   key;
      double        kb = 0;
      std::string   unit;
      while (meminfo >> key >> kb >> unit)
        if (key == "MemAvailable:")
          {
            available = kb * 1024;
            break;
          }
      if (available == 0)
        available = static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) *
                    static_cast<double>(sysconf(_SC_PAGESIZE));
      return available;
    }


    /**
     * Per host of the run (by processor name): the most memory
     * @p available that one of its processes reported, and the number of
     * the run's processes on it.
     */
    std::map<std::string, std::pair<double, unsigned int>>
    memory_per_host(const double available, const MPI_Comm comm)
    {
      char host[MPI_MAX_PROCESSOR_NAME] = {};
      int  length                       = 0;
      MPI_Get_processor_name(host, &length);
      std::map<std::string, std::pair<double, unsigned int>> hosts;
      for (const auto &[name, a] : Utilities::MPI::all_gather(
             comm, std::make_pair(std::string(host, length), available)))
        {
          auto &[most, processes] = hosts[name];
          most                    = std::max(most, a);
          ++processes;
        }
      return hosts;
    }
  } // namespace


  double
  check_resources(const RunParameters &parameters,
                  const unsigned int   dim,
                  const double         n_coarse_cells,
                  const MPI_Comm       comm)
  {
    // Estimates for the mesh after Geometry/Global refinements (an
    // adaptive mesh may grow beyond it; Mesh refinement/Cell budget bounds
    // it). DoFs as on a box; memory: a third of what the memory model
    // predicts with the preconditioner of least memory that the
    // parameters allow (a lower bound, so that no scene that fits is
    // refused: the model's GMRES basis and unitemized heap alone can be
    // half of its prediction).
    const double refinements = parameters.geometry.global_refinements;
    const double cells       = n_coarse_cells * std::pow(2., dim * refinements);
    const double p           = parameters.finite_element.degree;
    const double dofs = dim * std::pow(p * std::pow(cells, 1. / dim) + 1, dim);
    const double bytes       = least_memory_bound(parameters.solver,
                                            dim,
                                            parameters.finite_element.degree,
                                            dofs);

    // The memory available: MemAvailable of every host of the run, once.
    const auto hosts = memory_per_host(memory_available_here(), comm);
    double     total = 0, per_process = std::numeric_limits<double>::infinity();
    for (const auto &h : hosts)
      {
        total += h.second.first;
        per_process = std::min(per_process, h.second.first / h.second.second);
      }

    const auto giga = [](const double b) {
      std::ostringstream s;
      s << std::setprecision(3) << b / 1e9 << " GB";
      return s.str();
    };
    const std::string estimate =
      "about " + scientific(cells, 1) + " cells and " + scientific(dofs, 1) +
      " DoFs (Geometry: " + scientific(n_coarse_cells, 1) + " coarse cells, " +
      std::to_string(parameters.geometry.global_refinements) +
      " global refinements; Q" +
      std::to_string(parameters.finite_element.degree) + ")";
    const std::string fix =
      " Reduce Geometry/Repetitions, Geometry/Global refinements or Finite "
      "element/Polynomial degree.";
    // deal.II (this build: 32-bit indices) counts cells and DoFs in 32 bits.
    const double index_limit = 4294967295.;
    if (cells >= index_limit || dofs >= index_limit)
      throw CollectiveError("The scene is too large: " + estimate +
                            ", more than this build of deal.II can count "
                            "(4.3e+09)." +
                            fix);
    if (bytes > total)
      throw CollectiveError(
        "The scene does not fit into memory: " + estimate + " need at least " +
        giga(bytes) + " with Solver/Preconditioner = " +
        parameters.solver.preconditioner + ", and " + giga(total) +
        " are available on the " + std::to_string(hosts.size()) + " host" +
        (hosts.size() > 1 ? "s" : "") + " of this run." + fix);
    return parameters.solver.memory_per_process.value_or(per_process);
  }
} // namespace DynamicContact
