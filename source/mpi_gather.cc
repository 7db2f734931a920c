#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <dynamic_contact/mpi_gather.h>

#include <climits>

namespace DynamicContact
{
  std::vector<std::vector<double>>
  all_gather_values(const MPI_Comm comm, const std::vector<double> &local)
  {
    const unsigned int n = dealii::Utilities::MPI::n_mpi_processes(comm);
    if (n == 1)
      return {local};
    AssertThrow(local.size() <= static_cast<std::size_t>(INT_MAX),
                dealii::ExcMessage("all_gather_values: more than INT_MAX "
                                   "values on one process."));
    const int        size = static_cast<int>(local.size());
    std::vector<int> sizes(n);
    int              ierr =
      MPI_Allgather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, comm);
    AssertThrowMPI(ierr);
    std::vector<int> offsets(n, 0);
    long long        total = 0;
    for (unsigned int p = 0; p < n; ++p)
      {
        offsets[p] = static_cast<int>(total);
        total += sizes[p];
        AssertThrow(total <= INT_MAX,
                    dealii::ExcMessage("all_gather_values: more than "
                                       "INT_MAX values in all."));
      }
    std::vector<double> all(static_cast<std::size_t>(total));
    ierr = MPI_Allgatherv(local.data(),
                          size,
                          MPI_DOUBLE,
                          all.data(),
                          sizes.data(),
                          offsets.data(),
                          MPI_DOUBLE,
                          comm);
    AssertThrowMPI(ierr);
    std::vector<std::vector<double>> parts(n);
    for (unsigned int p = 0; p < n; ++p)
      parts[p].assign(all.begin() + offsets[p],
                      all.begin() + offsets[p] + sizes[p]);
    return parts;
  }
} // namespace DynamicContact
