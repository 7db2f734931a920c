#ifndef dynamic_contact_bulk_factorization_h
#define dynamic_contact_bulk_factorization_h

#include <deal.II/base/types.h>

#include <dynamic_contact/parameters/parameters.h>

#include <mpi.h>

namespace DynamicContact
{
  /** How the bulk matrix K0 is factorized for a direct solve, or not. */
  enum class BulkFactorization
  {
    /** SuiteSparse CHOLMOD, one process. */
    cholmod,
    /** CHOLMOD on every process, each with the whole matrix. */
    cholmod_on_every_process,
    /** Trilinos Amesos (MUMPS or KLU), distributed. */
    amesos,
    /** No factorization: CG or GMRES with algebraic multigrid. */
    none
  };

  /**
   * A direct solve with K0 under these parameters factorizes by CHOLMOD:
   * with Direct solver package = auto, on one process, and on several
   * while K0 is small enough that the whole factor on every process is
   * faster than MUMPS over them (the limits are the crossovers measured
   * on two processes: benchmarks/results/replicated_factorization.txt;
   * 2D factors are much sparser).
   */
  bool
  factorized_by_cholmod(const Parameters::Solver             &parameters,
                        const unsigned int                    dim,
                        const dealii::types::global_dof_index n_dofs,
                        const unsigned int                    n_processes);

  /**
   * How a bulk matrix of @p n_dofs rows is factorized with these
   * parameters on the processes of @p comm (Solver/Direct solver package
   * = auto: CHOLMOD on one process; on up to 4, CHOLMOD on every process
   * while the matrix is small, see the definition for the measured
   * limits, else MUMPS over the processes). Linear solver = iterative:
   * none.
   */
  BulkFactorization
  bulk_factorization(const Parameters::Solver             &parameters,
                     const unsigned int                    dim,
                     const dealii::types::global_dof_index n_dofs,
                     const MPI_Comm                        comm);

  /** The same on @p n_processes processes. */
  BulkFactorization
  bulk_factorization(const Parameters::Solver             &parameters,
                     const unsigned int                    dim,
                     const dealii::types::global_dof_index n_dofs,
                     const unsigned int                    n_processes);
} // namespace DynamicContact

#endif
