#ifndef dynamic_contact_solver_plan_h
#define dynamic_contact_solver_plan_h

#include <deal.II/base/types.h>

#include <dynamic_contact/bulk/bulk_factorization.h>
#include <dynamic_contact/contact/cost_model.h>
#include <dynamic_contact/parameters/parameters.h>

#include <mpi.h>

#include <limits>
#include <memory>
#include <string>

namespace DynamicContact
{
  /**
   * How a step is solved, chosen in one place from the parameters and the
   * problem (made by plan_solver() whenever the mesh or Gamma_3 changes):
   * which contact solver (condensed or assembled), how its linear systems
   * are solved (sparse direct or Krylov with algebraic multigrid), which
   * direct solver factorizes, and why. The parameters given are kept as
   * they are; 'auto' values are resolved here.
   */
  struct SolverPlan
  {
    /** How K0 is factorized (bulk_factorization()). */
    using Factorization = BulkFactorization;

    /**
     * The registered contact solver that runs (Solver/Contact solver, or
     * the choice of auto; Parameters::Solver::contact_solvers).
     */
    std::string contact_solver = "condensed";
    /**
     * It is the condensed solver (K0 factorized by BulkSolver); else K0 is
     * factorized, if at all, as the assembled solver does.
     */
    bool condensed = true;
    /** Direct or iterative (Solver/Linear solver with auto resolved). */
    Parameters::Solver::LinearSolver linear_solver =
      Parameters::Solver::LinearSolver::direct;
    Factorization factorization = Factorization::cholmod;
    /**
     * Without one: the preconditioner (Solver/Preconditioner, auto
     * resolved: choose_preconditioner()), with its parameters.
     */
    std::string                                 preconditioner = "AMG";
    std::shared_ptr<const PreconditionerPlugin> preconditioner_plugin;
    /** Why the contact solver and the factorization were chosen. */
    std::string reason;
    /** Preconditioner = auto: why this one (empty otherwise). */
    std::string preconditioner_reason;
    /**
     * Contact solver = auto: the predicted costs of both solvers (not
     * calibrated where the model has no terms, or the boundary exceeds the
     * condensed limit) and the steps one K0 is expected to serve.
     */
    SolverCost   condensed_cost, assembled_cost;
    unsigned int steps_per_matrix = 1;

    /**
     * K0 is applied cell by cell, not stored: the matrix-free GMG for the
     * assembled iterative solver (the condensed solver and the direct one
     * need K0 stored, whatever the preconditioner).
     */
    bool
    matrix_free_bulk() const
    {
      return preconditioner_plugin && !preconditioner_plugin->stores_matrix() &&
             !condensed &&
             linear_solver == Parameters::Solver::LinearSolver::iterative;
    }

    /** The solver parameters the chosen solver works with. */
    Parameters::Solver
    solver_parameters(const Parameters::Solver &given) const;

    /**
     * contact_solver, for the assembled one with its linear solver:
     * "assembled (direct|iterative)".
     */
    std::string
    contact_solver_name() const;

    /**
     * The choices alone: the contact solver, the factorization and, where
     * it was chosen, the preconditioner, without the reasons and the
     * predicted costs (which change with every mesh). Two plans that
     * solve alike give the same text.
     */
    std::string
    choices() const;

    /** One line: the choices and why. */
    std::string
    description() const;
  };

  /**
   * What Solver/Preconditioner = auto weighs besides the size of the mesh:
   * the memory one process may use (Solver/Memory per process, or what
   * the hosts had available at the start: check_resources()), the
   * elements' degree, and the DoFs of the mesh's coarsest level (the
   * geometric multigrid's coarsest level).
   */
  struct MemoryBudget
  {
    /** Bytes per process; infinite: no limit known (the AMG). */
    double       bytes_per_process = std::numeric_limits<double>::infinity();
    unsigned int degree            = 1;
    /** The DoFs of the coarsest level; the mesh's DoFs: no levels. */
    double coarse_dofs = 0;
  };

  /**
   * The preconditioner of the assembled iterative solver for
   * Solver/Preconditioner = auto: the first of preconditioner_candidates()
   * (AMG, GMG and matrix-free GMG, fastest first:
   * benchmarks/results/scaling_preconditioners.csv) whose peak memory
   * predicted on the largest process (predicted_memory()) fits into the
   * budget; the one of least memory where none fits. @p reason: the memory
   * each needs and the budget, for the log.
   */
  std::string
  choose_preconditioner(const Parameters::Solver             &parameters,
                        const unsigned int                    dim,
                        const dealii::types::global_dof_index n_dofs,
                        const unsigned int                    n_processes,
                        const MemoryBudget                   &memory,
                        std::string                          &reason);

  /**
   * The plan for a problem of @p n_dofs bulk DoFs and @p n_contact_nodes
   * nodes on Gamma_3 on the processes of @p comm (every process decides
   * alike), whose bulk matrix K0 is expected to serve @p steps_per_matrix
   * steps (the steps left, or fewer where the mesh or the time step
   * changes): Contact solver = auto takes the solver of the lower cost
   * predicted for them (cost_model.h), the condensed one only while
   * dim x contact nodes is within its limit. Preconditioner = auto:
   * choose_preconditioner() within @p memory for the assembled iterative
   * solver, the AMG elsewhere.
   */
  SolverPlan
  plan_solver(const Parameters::Solver             &parameters,
              const unsigned int                    dim,
              const dealii::types::global_dof_index n_dofs,
              const unsigned int                    n_contact_nodes,
              const unsigned int                    steps_per_matrix,
              const MPI_Comm                        comm,
              const MemoryBudget                   &memory = MemoryBudget());
} // namespace DynamicContact

#endif
