#ifndef dynamic_contact_linear_algebra_h
#define dynamic_contact_linear_algebra_h

#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <vector>

namespace DynamicContact
{
  /**
   * The distributed linear algebra of the program, in one place: Trilinos
   * (Epetra) vectors and sparse matrices, as in deal.II's step-40 and
   * step-42.
   */
  using Vector_t = dealii::TrilinosWrappers::MPI::Vector;
  using Matrix_t = dealii::TrilinosWrappers::SparseMatrix;

  /**
   * Every process's @p local numbers, concatenated in the order of the
   * ranks, on every process: one MPI_Allgatherv, and nothing on one
   * process. (dealii::Utilities::MPI::all_gather serializes and compresses
   * its objects, even on one process: on the paper domain 256 x 16 that
   * cost 16 % of the run, in the gathers of Gamma_3 data each Newton
   * iteration.)
   */
  inline std::vector<double>
  all_gather_numbers(const MPI_Comm comm, const std::vector<double> &local)
  {
    const unsigned int n = dealii::Utilities::MPI::n_mpi_processes(comm);
    if (n == 1)
      return local;
    const int        size = static_cast<int>(local.size());
    std::vector<int> sizes(n), offsets(n + 1, 0);
    int ierr = MPI_Allgather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, comm);
    AssertThrowMPI(ierr);
    for (unsigned int p = 0; p < n; ++p)
      offsets[p + 1] = offsets[p] + sizes[p];
    std::vector<double> all(offsets[n]);
    ierr = MPI_Allgatherv(local.data(),
                          size,
                          MPI_DOUBLE,
                          all.data(),
                          sizes.data(),
                          offsets.data(),
                          MPI_DOUBLE,
                          comm);
    AssertThrowMPI(ierr);
    return all;
  }
} // namespace DynamicContact

#endif
