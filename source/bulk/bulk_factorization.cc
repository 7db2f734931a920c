#include <deal.II/base/mpi.h>

#include <dynamic_contact/bulk/bulk_factorization.h>

namespace DynamicContact
{
  using namespace dealii;

  bool
  factorized_by_cholmod(const Parameters::Solver     &parameters,
                        const unsigned int            dim,
                        const types::global_dof_index n_dofs,
                        const unsigned int            n)
  {
    if (parameters.direct_solver_package != "auto")
      return false;
    // The whole factor on every process: while K0 is small, and on at
    // most 4 processes (on 8 and 16 processes of a 16-core machine every
    // process's factorization took many times as long as on one:
    // benchmarks/results/replicated_factorization_16cores.txt).
    const double limit = dim == 2 ? 1e5 : 3e4;
    return n == 1 || (n_dofs <= limit && n <= 4);
  }


  BulkFactorization
  bulk_factorization(const Parameters::Solver     &parameters,
                     const unsigned int            dim,
                     const types::global_dof_index n_dofs,
                     const unsigned int            n_processes)
  {
    using F = BulkFactorization;
    if (parameters.linear_solver == Parameters::Solver::LinearSolver::iterative)
      return F::none;
    if (!factorized_by_cholmod(parameters, dim, n_dofs, n_processes))
      return F::amesos;
    return n_processes == 1 ? F::cholmod : F::cholmod_on_every_process;
  }


  BulkFactorization
  bulk_factorization(const Parameters::Solver     &parameters,
                     const unsigned int            dim,
                     const types::global_dof_index n_dofs,
                     const MPI_Comm                comm)
  {
    return bulk_factorization(parameters,
                              dim,
                              n_dofs,
                              Utilities::MPI::n_mpi_processes(comm));
  }
} // namespace DynamicContact
