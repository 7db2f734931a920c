#include <deal.II/base/mpi.h>

#include <dynamic_contact/bulk/preconditioners.h>
#include <dynamic_contact/contact/solver_plan.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

namespace DynamicContact
{
  using namespace dealii;

  namespace
  {
    /**
     * Contact solver = auto within the condensed solver's limit: the
     * solver of the lower cost predicted for plan.steps_per_matrix steps;
     * the condensed one on meshes smaller than the model's, or where it
     * has no terms. @p one_factor: K0 factorized by CHOLMOD.
     */
    void
    choose_by_cost(SolverPlan                   &plan,
                   std::ostringstream           &reason,
                   const unsigned int            dim,
                   const types::global_dof_index n_dofs,
                   const unsigned int            size,
                   const unsigned int            limit,
                   const bool                    one_factor,
                   const MPI_Comm                comm)
    {
      const unsigned int processes = Utilities::MPI::n_mpi_processes(comm);
      const CostedSolver condensed =
        processes == 1 ? CostedSolver::condensed :
        one_factor     ? CostedSolver::condensed_on_every_process :
                         CostedSolver::condensed_distributed;
      plan.condensed_cost =
        predicted_cost(condensed, dim, n_dofs, size, processes);
      plan.assembled_cost =
        predicted_cost(CostedSolver::assembled, dim, n_dofs, size, processes);
      const unsigned int steps    = plan.steps_per_matrix;
      const double       below    = smallest_costed_mesh(dim);
      const double       measured = largest_costed_mesh(dim, condensed);
      const std::string  within   = "dim x contact nodes = " +
                                 std::to_string(size) +
                                 " <= " + std::to_string(limit);
      if (condensed == CostedSolver::condensed_distributed &&
          plan.condensed_cost.calibrated && n_dofs > measured)
        {
          // MUMPS's Schur complement must agree with its solves, and on
          // larger meshes it may not: C then costs dim solves per node,
          // a cost the model does not know.
          plan.condensed = false;
          reason << "larger than the meshes the condensed solver with MUMPS "
                 << "was measured on (" << measured << " DoFs); " << within;
          return;
        }
      if (size > 0 && n_dofs >= below && plan.condensed_cost.calibrated &&
          plan.assembled_cost.calibrated)
        {
          const double c = plan.condensed_cost.total(steps),
                       a = plan.assembled_cost.total(steps);
          plan.condensed = c <= a;
          reason << "predicted for " << steps << " step"
                 << (steps == 1 ? "" : "s")
                 << " per bulk matrix: condensed " << cost_string(c)
                 << ", assembled " << cost_string(a) << "; " << within;
          return;
        }
      plan.condensed = true;
      reason << within;
      if (size > 0 && n_dofs < below)
        reason << ", smaller than the meshes of the cost model (" << below
               << " DoFs)";
      else if (size > 0)
        reason << ", no cost model for it";
    }
  } // namespace


  std::string
  choose_preconditioner(const Parameters::Solver     &parameters,
                        const unsigned int            dim,
                        const types::global_dof_index n_dofs,
                        const unsigned int            n_processes,
                        const MemoryBudget           &memory,
                        std::string                  &reason)
  {
    std::ostringstream s;
    s << "peak predicted per process:";
    std::optional<std::string> chosen;
    std::string                least = algebraic_multigrid;
    double least_need                = std::numeric_limits<double>::infinity();
    bool   first                     = true;
    for (const std::string &p : auto_preconditioners(parameters, memory.degree))
      {
        const double need =
          predicted_memory(parameters.preconditioner_plugin(p),
                           dim,
                           memory.degree,
                           n_dofs,
                           n_processes,
                           memory.coarse_dofs);
        s << (first ? " " : ", ") << p << " " << memory_string(need);
        first = false;
        if (!chosen && need <= memory.bytes_per_process)
          chosen = p;
        if (need < least_need)
          {
            least      = p;
            least_need = need;
          }
      }
    if (std::isfinite(memory.bytes_per_process))
      s << "; " << memory_string(memory.bytes_per_process)
        << " per process available";
    else
      s << "; no memory limit known";
    if (!chosen)
      s << ": none fits, the least";
    reason = s.str();
    return chosen.value_or(least);
  }


  namespace
  {
    /**
     * The preconditioner of @p plan: as set, or for Preconditioner = auto
     * the fastest that fits where the assembled iterative solver runs (the
     * condensed solver's iterative solves with K0 take the AMG).
     */
    void
    plan_preconditioner(SolverPlan                   &plan,
                        const Parameters::Solver     &parameters,
                        const unsigned int            dim,
                        const types::global_dof_index n_dofs,
                        const unsigned int            n_processes,
                        const MemoryBudget           &memory)
    {
      plan.preconditioner = parameters.preconditioner;
      if (plan.preconditioner == "auto")
        plan.preconditioner =
          !plan.condensed && plan.linear_solver ==
                               Parameters::Solver::LinearSolver::iterative ?
            choose_preconditioner(parameters,
                                  dim,
                                  n_dofs,
                                  n_processes,
                                  memory,
                                  plan.preconditioner_reason) :
            algebraic_multigrid;
      plan.preconditioner_plugin =
        parameters.preconditioners.at(plan.preconditioner);
    }
  } // namespace


  SolverPlan
  plan_solver(const Parameters::Solver     &parameters,
              const unsigned int            dim,
              const types::global_dof_index n_dofs,
              const unsigned int            n_contact_nodes,
              const unsigned int            steps_per_matrix,
              const MPI_Comm                comm,
              const MemoryBudget           &memory)
  {
    using LS = Parameters::Solver::LinearSolver;
    SolverPlan         plan;
    std::ostringstream reason;
    const unsigned int n_processes = Utilities::MPI::n_mpi_processes(comm);
    const bool         one_factor =
      factorized_by_cholmod(parameters, dim, n_dofs, n_processes);

    // The condensed solver's dense tables are bounded by its limit
    // (doc/algorithms.md, "Choosing"; Solver/Condensed). With a CHOLMOD
    // factor several processes are one as the condensed solver sees it
    // (the compliance from the factor's trailing block); with MUMPS over
    // the processes its limit on several processes applies.
    const bool         automatic = parameters.contact_solver == "auto";
    const unsigned int limit =
      parameters.contact_solver_plugin("condensed")
        .boundary_limit(dim, n_processes > 1 && !one_factor)
        .value_or(std::numeric_limits<unsigned int>::max());
    const unsigned int size = dim * n_contact_nodes;
    plan.steps_per_matrix   = std::max(steps_per_matrix, 1u);
    if (!automatic)
      {
        plan.condensed = parameters.contact_solver == "condensed";
        reason << "as set";
      }
    else if (size > limit)
      {
        plan.condensed = false;
        reason << "dim x contact nodes = " << size << " > " << limit;
      }
    else
      choose_by_cost(
        plan, reason, dim, n_dofs, size, limit, one_factor, comm);

    plan.contact_solver = automatic ?
                            (plan.condensed ? "condensed" : "assembled") :
                            parameters.contact_solver;

    // The linear solver: auto is direct, except for the assembled solver
    // chosen by Contact solver = auto (a large contact boundary or a
    // large mesh), which solves by GMRES with algebraic multigrid.
    plan.linear_solver = parameters.linear_solver;
    if (parameters.linear_solver == LS::automatic)
      plan.linear_solver =
        (!plan.condensed && automatic) ? LS::iterative : LS::direct;
    // The condensed solver factorizes K0 (BulkSolver), the assembled one
    // its Newton matrix by Amesos.
    if (plan.condensed)
      plan.factorization = bulk_factorization(
        plan.solver_parameters(parameters), dim, n_dofs, comm);
    else
      plan.factorization = plan.linear_solver == LS::iterative ?
                             SolverPlan::Factorization::none :
                             SolverPlan::Factorization::amesos;
    plan_preconditioner(plan, parameters, dim, n_dofs, n_processes, memory);
    reason << "; " << n_dofs << " DoFs on " << n_processes << " process"
           << (n_processes == 1 ? "" : "es");
    plan.reason = reason.str();
    return plan;
  }


  Parameters::Solver
  SolverPlan::solver_parameters(const Parameters::Solver &given) const
  {
    Parameters::Solver resolved = given;
    resolved.linear_solver      = linear_solver;
    resolved.preconditioner     = preconditioner;
    return resolved;
  }


  std::string
  SolverPlan::contact_solver_name() const
  {
    if (contact_solver != "assembled")
      return contact_solver;
    return linear_solver == Parameters::Solver::LinearSolver::iterative ?
             "assembled (iterative)" :
             "assembled (direct)";
  }


  namespace
  {
    /** The factorization of @p plan in words (description()). */
    std::string
    factorization_text(const SolverPlan &plan)
    {
      using F = SolverPlan::Factorization;
      switch (plan.factorization)
        {
          case F::cholmod:
            return "CHOLMOD";
          case F::cholmod_on_every_process:
            return "CHOLMOD on every process";
          case F::amesos:
            return "Amesos, distributed";
          case F::none:
            break;
        }
      return "none (Krylov with " + plan.preconditioner_plugin->in_words() +
             ")";
    }
  } // namespace


  std::string
  SolverPlan::choices() const
  {
    return contact_solver_name() +
           ", factorization: " + factorization_text(*this) +
           (preconditioner_reason.empty() ?
              std::string() :
              "; preconditioner " + preconditioner);
  }


  std::string
  SolverPlan::description() const
  {
    return contact_solver_name() +
           ", factorization: " + factorization_text(*this) + " (" + reason +
           ")" +
           (preconditioner_reason.empty() ?
              std::string() :
              "; preconditioner " + preconditioner + " (" +
                preconditioner_reason + ")");
  }
} // namespace DynamicContact
