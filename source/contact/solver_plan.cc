#include <deal.II/base/mpi.h>

#include <dynamic_contact/contact/solver_plan.h>

#include <sstream>

namespace DynamicContact
{
  using namespace dealii;

  SolverPlan::Factorization
  bulk_factorization(const Parameters::Solver     &parameters,
                     const unsigned int            dim,
                     const types::global_dof_index n_dofs,
                     const MPI_Comm                comm)
  {
    using F = SolverPlan::Factorization;
    if (parameters.linear_solver == Parameters::Solver::LinearSolver::iterative)
      return F::none;
    if (parameters.direct_solver_package != "auto")
      return F::amesos;
    if (Utilities::MPI::n_mpi_processes(comm) == 1)
      return F::cholmod;
    // Several processes. Measured on 2 (benchmarks/results/
    // replicated_factorization.txt), CHOLMOD on each process against MUMPS
    // over both: the paper's scene (2D, 33 282 DoFs) and the rail
    // 80 x 8 x 8 (3D, 19 683 DoFs) run about as fast as on one process
    // with CHOLMOD on each, 1.3 to 1.7 times slower with MUMPS; at 47 952
    // DoFs in 3D (rail 110 x 11 x 11) a MUMPS solve is already faster than
    // CHOLMOD's, which a run of more than a few dozen steps repays. 2D
    // factors are much sparser. Each process holds the whole factor.
    const double limit = dim == 2 ? 1e5 : 3e4;
    return n_dofs <= limit ? F::cholmod_on_every_process : F::amesos;
  }


  SolverPlan
  plan_solver(const Parameters::Solver     &parameters,
              const unsigned int            dim,
              const types::global_dof_index n_dofs,
              const unsigned int            n_contact_nodes,
              const MPI_Comm                comm)
  {
    using CS = Parameters::Solver::ContactSolver;
    using LS = Parameters::Solver::LinearSolver;
    SolverPlan         plan;
    std::ostringstream reason;
    const bool one_process = Utilities::MPI::n_mpi_processes(comm) == 1;

    // The contact solver: the condensed one while dim n_Gamma is below the
    // measured crossover (doc/algorithms.md, "Choosing"). Where the bulk
    // matrix is factorized whole on each process, several processes are
    // one process as the condensed solver sees it (the compliance from
    // the factor's trailing block); else in 3D the compliance comes from
    // MUMPS's Schur complement (the same limit), in 2D from dim solves per
    // node (1000).
    Parameters::Solver direct = parameters;
    direct.linear_solver      = LS::direct;
    const bool whole_factor_everywhere =
      bulk_factorization(direct, dim, n_dofs, comm) != SolverPlan::Factorization::amesos;
    const unsigned int limit =
      one_process || whole_factor_everywhere ?
        parameters.condensed_limit :
        parameters.condensed_limit_on_several_processes.value_or(
          dim == 3 ? parameters.condensed_limit : 1000);
    const unsigned int size = dim * n_contact_nodes;
    if (parameters.contact_solver == CS::automatic)
      {
        plan.condensed = size <= limit;
        reason << "dim x contact nodes = " << size
               << (plan.condensed ? " <= " : " > ") << limit;
      }
    else
      {
        plan.condensed = parameters.contact_solver == CS::condensed;
        reason << "as set";
      }

    // The linear solver: auto is direct, except for the assembled solver
    // chosen by Contact solver = auto (a large contact boundary, so a
    // large problem), which solves by GMRES with algebraic multigrid.
    plan.linear_solver = parameters.linear_solver;
    if (parameters.linear_solver == LS::automatic)
      plan.linear_solver =
        (!plan.condensed && parameters.contact_solver == CS::automatic) ?
          LS::iterative :
          LS::direct;
    plan.factorization =
      bulk_factorization(plan.solver_parameters(parameters), dim, n_dofs, comm);
    if (!plan.condensed &&
        plan.factorization != SolverPlan::Factorization::none)
      // The assembled solver factorizes its Newton matrix by Amesos.
      plan.factorization = SolverPlan::Factorization::amesos;
    reason << "; " << n_dofs << " DoFs on "
           << Utilities::MPI::n_mpi_processes(comm) << " process"
           << (one_process ? "" : "es");
    plan.reason = reason.str();
    return plan;
  }


  Parameters::Solver
  SolverPlan::solver_parameters(const Parameters::Solver &given) const
  {
    Parameters::Solver resolved = given;
    resolved.linear_solver      = linear_solver;
    return resolved;
  }


  std::string
  SolverPlan::contact_solver_name() const
  {
    if (condensed)
      return "condensed";
    return linear_solver == Parameters::Solver::LinearSolver::iterative ?
             "assembled (iterative)" :
             "assembled (direct)";
  }


  std::string
  SolverPlan::description() const
  {
    std::string factor;
    switch (factorization)
      {
        case Factorization::cholmod:
          factor = "CHOLMOD";
          break;
        case Factorization::cholmod_on_every_process:
          factor = "CHOLMOD on every process";
          break;
        case Factorization::amesos:
          factor = "Amesos, distributed";
          break;
        case Factorization::none:
          factor = "none (Krylov with algebraic multigrid)";
          break;
      }
    return contact_solver_name() + ", factorization: " + factor + " (" +
           reason + ")";
  }
} // namespace DynamicContact
