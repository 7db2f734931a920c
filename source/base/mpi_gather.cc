#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/mpi_gather.h>

#include <climits>

namespace DynamicContact
{
  namespace
  {
    /** The gathers of both functions: to every process if @p to_all,
     *  else to @p root. */
    std::vector<std::vector<double>>
    gather_doubles(const MPI_Comm             comm,
                   const std::vector<double> &local,
                   const bool                 to_all,
                   const unsigned int         root)
    {
      const unsigned int n = dealii::Utilities::MPI::n_mpi_processes(comm);
      if (n == 1)
        return {local};
      AssertThrow(local.size() <= static_cast<std::size_t>(INT_MAX),
                  dealii::ExcMessage("Gathering more than INT_MAX values "
                                     "from one process."));
      const bool receives =
        to_all || dealii::Utilities::MPI::this_mpi_process(comm) == root;
      // MPI_Allgather(v) to every process, else MPI_Gather(v) to root:
      // the same arguments, then the root.
      const auto gather =
        [&](const auto to_every, const auto to_root, const auto... arguments) {
          return to_all ? to_every(arguments..., comm) :
                          to_root(arguments..., root, comm);
        };
      const int        size = static_cast<int>(local.size());
      std::vector<int> sizes(n);
      int              ierr = gather(
        MPI_Allgather, MPI_Gather, &size, 1, MPI_INT, sizes.data(), 1, MPI_INT);
      AssertThrowMPI(ierr);
      std::vector<int> offsets(n, 0);
      long long        total = 0;
      if (receives)
        for (unsigned int p = 0; p < n; ++p)
          {
            offsets[p] = static_cast<int>(total);
            total += sizes[p];
            AssertThrow(total <= INT_MAX,
                        dealii::ExcMessage("Gathering more than INT_MAX "
                                           "values in all."));
          }
      std::vector<double> all(static_cast<std::size_t>(total));
      ierr = gather(MPI_Allgatherv,
                    MPI_Gatherv,
                    local.data(),
                    size,
                    MPI_DOUBLE,
                    all.data(),
                    sizes.data(),
                    offsets.data(),
                    MPI_DOUBLE);
      AssertThrowMPI(ierr);
      if (!receives)
        return {};
      std::vector<std::vector<double>> parts(n);
      for (unsigned int p = 0; p < n; ++p)
        parts[p].assign(all.begin() + offsets[p],
                        all.begin() + offsets[p] + sizes[p]);
      return parts;
    }
  } // namespace


  std::vector<std::vector<double>>
  all_gather_values(const MPI_Comm comm, const std::vector<double> &local)
  {
    return gather_doubles(comm, local, true, 0);
  }


  std::vector<std::vector<double>>
  gather_values(const MPI_Comm             comm,
                const std::vector<double> &local,
                const unsigned int         root)
  {
    return gather_doubles(comm, local, false, root);
  }
} // namespace DynamicContact
