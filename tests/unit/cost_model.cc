// The solver plan's cost model (cost_model.h) and the choice it makes for
// Solver/Contact solver = auto (plan_solver):
//  - the table is what benchmarks/cost-model fits to the committed
//    benchmark results (the script's --check), and every term is finite;
//  - the predicted costs grow with the mesh (the rail's family of meshes,
//    n = 8 ... 32 cells across, in 3D; the paper's domain in 2D), and
//    beyond 2 processes a term shrinks by at most half per doubling and
//    never grows, but for the condensed solver's dense work on Gamma_3,
//    which every process repeats: it grows by 1.3 per doubling, so that
//    on 16 processes the condensed rail 80 x 8 x 8 costs more per step
//    than on 2 (measured on a 16-core machine);
//  - the plan takes the solver of the lower predicted cost for the steps
//    one bulk matrix serves, says both costs, and takes the condensed
//    solver only within Solver/Condensed/Limit and, with MUMPS, on the
//    meshes measured; 'as set' is kept;
//  - K0 is factorized by CHOLMOD on every process only on up to 4;
//  - the memory model (predicted_memory) predicts the peaks that
//    benchmarks/memory measured (benchmarks/results/memory.csv and
//    memory_2d.csv) within 12 %, and Preconditioner = auto takes the AMG
//    while it fits into the memory per process, then the GMG, then the
//    matrix-free GMG (also where none fits), the AMG for degree 3, and in
//    the plan only for the assembled iterative solver.
// Plans on 1 and 2 processes are made for MPI_COMM_SELF and for a
// communicator of 2 (the test runs on 2 processes); nothing printed
// depends on the calibration's numbers.

#include <deal.II/base/mpi.h>

#include <dynamic_contact/contact/cost_model.h>
#include <dynamic_contact/contact/solver_plan.h>

#include "program_tools.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using namespace DynamicContact;
using namespace program_tools;

namespace
{
  /**
   * The section Solver as a parameter file with @p entries ("Entry=value",
   * relative to Solver) gives it: Contact solver = auto and the other
   * defaults.
   */
  Parameters::Solver
  automatic(const std::vector<std::string> &entries = {})
  {
    ParameterHandler prm;
    Parameters::Solver::declare_parameters(prm);
    for (const std::string &entry : entries)
      apply_override(prm, "Solver/" + entry);
    Parameters::Solver p;
    p.parse_parameters(prm);
    return p;
  }

  /** The rail n*10 x n x n: (DoFs, contact nodes). */
  std::pair<unsigned int, unsigned int>
  rail(const unsigned int n)
  {
    return {3 * (10 * n + 1) * (n + 1) * (n + 1), (10 * n - 1) * (n + 1)};
  }

  /** The paper's domain m x 16: (DoFs, contact nodes). */
  std::pair<unsigned int, unsigned int>
  paper(const unsigned int m)
  {
    return {2 * (m + 1) * 17, m - 1};
  }

  using CSolver = CostedSolver;

  bool
  is_root()
  {
    return Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  }

  /** The table is the fit of the committed results; every term finite. */
  void
  check_table(Checks &checks)
  {
    if (is_root())
      {
        const Outcome o =
          run_benchmark_script("cost-model", {"--check"}, "cost-model");
        checks.add(o.succeeded(),
                   "cost_model_table.cc is benchmarks/cost-model's fit of "
                   "benchmarks/results/scaling*.csv");
      }
    bool finite = !cost_model_terms.empty();
    for (const auto &t : cost_model_terms)
      finite = finite && std::isfinite(t.coefficient) && t.coefficient > 0 &&
               std::isfinite(t.exponent) &&
               (t.processes == 1 || t.processes == 2);
    checks.add(finite,
               "every term: a finite positive coefficient, 1 or 2 "
               "processes");
  }

  /** Growth with the mesh. */
  void
  check_growth(Checks &checks)
  {
    bool grows = true, calibrated = true;
    for (const CSolver s : {CSolver::condensed, CSolver::assembled})
      for (const unsigned int processes : {1u, 2u, 16u})
        for (const unsigned int dim : {2u, 3u})
          {
            SolverCost last;
            for (const unsigned int size : {0u, 1u, 2u, 3u, 4u})
              {
                const auto [dofs, nodes] =
                  dim == 3 ? rail(std::vector{8u, 11u, 16u, 22u, 32u}[size]) :
                             paper(128u << size);
                const CSolver way =
                  s != CSolver::condensed || processes == 1 ? s :
                  dim == 3 ? CSolver::condensed_distributed :
                             CSolver::condensed_on_every_process;
                const auto c =
                  predicted_cost(way, dim, dofs, dim * nodes, processes);
                calibrated = calibrated && c.calibrated;
                grows      = grows && c.total(10) > last.total(10);
                last       = c;
              }
          }
    checks.add(calibrated,
               "both solvers calibrated in 2D and 3D on 1, 2 and 16 processes "
               "(on several, the condensed one with the whole factor on every "
               "process in 2D, with MUMPS in 3D)");
    checks.add(grows,
               "a larger mesh costs more (rail and paper domain, both "
               "solvers, 1, 2 and 16 processes)");
  }

  /** Beyond two processes. */
  void
  check_beyond_two_processes(Checks &checks)
  {
    bool bounded = true;
    for (const CSolver s : {CSolver::assembled,
                            CSolver::condensed_on_every_process,
                            CSolver::condensed_distributed})
      {
        const double most        = s == CSolver::assembled ? 1 : 1.3;
        const auto [dofs, nodes] = rail(16);
        auto last                = predicted_cost(s, 3, dofs, 3 * nodes, 2);
        for (const unsigned int p : {4u, 8u, 16u})
          {
            const auto c = predicted_cost(s, 3, dofs, 3 * nodes, p);
            bounded      = bounded &&
                      c.per_step <= last.per_step * most * (1 + 1e-12) &&
                      c.per_step >= last.per_step / 2 * (1 - 1e-12) &&
                      c.once <= last.once * most * (1 + 1e-12) &&
                      c.once >= last.once / 2 * (1 - 1e-12);
            last = c;
          }
      }
    checks.add(bounded,
               "each doubling beyond 2 processes divides a cost by "
               "at most 2 and keeps it (assembled) or multiplies it "
               "by at most 1.3 (condensed)");
    const auto [dofs, nodes] = rail(8);
    const auto two =
      predicted_cost(CSolver::condensed_distributed, 3, dofs, 3 * nodes, 2);
    const auto sixteen =
      predicted_cost(CSolver::condensed_distributed, 3, dofs, 3 * nodes, 16);
    checks.add(sixteen.per_step > two.per_step,
               "the condensed rail 80 x 8 x 8 costs more per step on 16 "
               "processes than on 2 (its dense work on Gamma_3 is repeated "
               "by every process)");
  }

  /** What the plans of check_lower_cost found. */
  struct PlanFindings
  {
    bool lower = true, said = true, said_beyond = true, some_condensed = false,
         some_assembled = false;
  };

  /** The plan of one mesh, number of steps and communicator. */
  void
  check_plan(PlanFindings      &f,
             const MPI_Comm     comm,
             const unsigned int dim,
             const unsigned int size,
             const unsigned int steps)
  {
    const auto [dofs, nodes] = dim == 3 ? rail(size) : paper(size);
    const SolverPlan plan =
      plan_solver(automatic(), dim, dofs, nodes, steps, comm);
    // With MUMPS (3D, several processes, a K0 too large for the
    // whole factor on each) only on the meshes measured.
    const bool beyond_mumps =
      comm == MPI_COMM_WORLD && dim == 3 && dofs > 3e4 &&
      dofs > largest_costed_mesh(3, CSolver::condensed_distributed);
    if (dim * nodes > 8200 || beyond_mumps)
      {
        f.lower = f.lower && !plan.condensed;
        if (beyond_mumps && dim * nodes <= 8200)
          f.said_beyond =
            f.said_beyond &&
            plan.reason.find("larger than the meshes") != std::string::npos;
        return;
      }
    const bool cheaper =
      plan.condensed_cost.total(steps) <= plan.assembled_cost.total(steps);
    f.lower =
      f.lower && plan.condensed == cheaper && plan.steps_per_matrix == steps;
    f.said = f.said &&
             plan.reason.find("condensed " +
                              cost_string(plan.condensed_cost.total(steps))) !=
               std::string::npos &&
             plan.reason.find("assembled " +
                              cost_string(plan.assembled_cost.total(steps))) !=
               std::string::npos;
    f.some_condensed = f.some_condensed || plan.condensed;
    f.some_assembled = f.some_assembled || !plan.condensed;
  }

  /** The plan takes the lower predicted cost, and says both. */
  void
  check_lower_cost(Checks &checks)
  {
    PlanFindings f;
    for (const MPI_Comm comm : {MPI_COMM_SELF, MPI_COMM_WORLD})
      for (const unsigned int dim : {2u, 3u})
        for (const unsigned int size : {8u, 16u, 22u, 32u, 128u, 512u, 2048u})
          for (const unsigned int steps : {1u, 8u, 128u})
            if ((dim == 3) == (size < 100))
              check_plan(f, comm, dim, size, steps);
    checks.add(f.lower,
               "auto takes the solver of the lower predicted cost "
               "within the condensed limit, the assembled one beyond");
    checks.add(f.said, "the plan's reason gives both predicted costs");
    checks.add(f.said_beyond,
               "with MUMPS on a mesh larger than those measured: assembled, "
               "and the plan says why");
    checks.add(f.some_condensed && f.some_assembled,
               "both solvers are chosen somewhere on these meshes");
  }

  /** Steps per matrix, the limit, 'as set' and K0's factorization. */
  void
  check_plan_options(Checks &checks)
  {
    const auto self = MPI_COMM_SELF;
    {
      // Few steps per bulk matrix favour the solver with the cheaper set-up.
      const auto [dofs, nodes] = rail(8);
      const auto one  = plan_solver(automatic(), 3, dofs, nodes, 1, self);
      const auto many = plan_solver(automatic(), 3, dofs, nodes, 1000, self);
      checks.add(one.condensed_cost.once > one.assembled_cost.once &&
                   (many.condensed || !one.condensed),
                 "the condensed solver's set-up (factorization, compliance) "
                 "costs more than the AMG's; if it is chosen for 1 step, it "
                 "is for 1000");
    }
    {
      // The limit and 'as set'.
      auto p                   = automatic({"Condensed/Limit=0"});
      const auto [dofs, nodes] = rail(8);
      const auto capped        = plan_solver(p, 3, dofs, nodes, 1000, self);
      checks.add(!capped.condensed && !capped.condensed_cost.calibrated &&
                   capped.reason.find("> 0") != std::string::npos,
                 "Condensed/Limit = 0: assembled, no costs predicted");
      p.contact_solver = "condensed";
      const auto set   = plan_solver(p, 3, dofs, nodes, 1, self);
      checks.add(set.condensed && set.reason.rfind("as set", 0) == 0,
                 "Contact solver = condensed: kept as set");
    }
    // The whole CHOLMOD factor on every process: small K0, at most 4
    // processes; else MUMPS over the processes.
    using F                  = SolverPlan::Factorization;
    const auto [dofs, nodes] = paper(1024);
    bool as_measured         = true;
    for (const unsigned int n : {1u, 2u, 4u, 5u, 16u})
      as_measured = as_measured &&
                    bulk_factorization(automatic(), 2, dofs, n) ==
                      (n == 1 ? F::cholmod :
                       n <= 4 ? F::cholmod_on_every_process :
                                F::amesos) &&
                    bulk_factorization(automatic(), 2, 2e5, n) ==
                      (n == 1 ? F::cholmod : F::amesos);
    checks.add(as_measured,
               "K0 factorized by CHOLMOD on one process, on every process of "
               "up to 4 while small, else by MUMPS");
  }

  /** The fields of a CSV line (commas within quotes kept). */
  std::vector<std::string>
  csv_fields(const std::string &line)
  {
    std::vector<std::string> f;
    std::string              field;
    bool                     quoted = false;
    for (const char c : line)
      if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        f.push_back(std::exchange(field, ""));
      else
        field += c;
    f.push_back(field);
    return f;
  }

  /**
   * One line of a memory measurement: whether it is a peak of a
   * preconditioner auto chooses from (then ++rows) and within 12 % of the
   * memory model.
   */
  bool
  memory_row_close(const std::string &file,
                   const unsigned int dim,
                   const std::string &line,
                   std::size_t       &rows)
  {
    // ranks,preconditioner,dofs,wall_time,item,mb_all,mb_largest,...
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() < 7 || f[4] != "peak resident")
      return true;
    const auto &registered = automatic().preconditioners;
    if (registered.find(f[1]) == registered.end())
      return true; // AMG plain: not a choice of auto
    // The coarse meshes: the rail's 10 x 1 x 1 cells, the paper's 128 x
    // 128.
    const double coarse_dofs = dim == 3 ? 3. * 11 * 2 * 2 : 2. * 129 * 129;
    const double predicted   = predicted_memory(*registered.at(f[1]),
                                              dim,
                                              1,
                                              std::stoul(f[2]),
                                              std::stoul(f[0]),
                                              coarse_dofs) /
                             1e6;
    const double measured = std::stod(f[6]);
    if (is_root() && std::abs(predicted / measured - 1) > 0.12)
      std::cout << "  " << file << ", " << f[0] << " process(es), " << f[1]
                << ": predicted " << predicted << " MB, measured " << measured
                << " MB" << std::endl;
    ++rows;
    return std::abs(predicted / measured - 1) <= 0.12;
  }

  /**
   * The memory model against what benchmarks/memory measured: the peak of
   * the largest process, within 12 %, for every preconditioner, on 1
   * process (3D and 2D) and on 16 (3D).
   */
  void
  check_memory_model(Checks &checks)
  {
    bool        close = true;
    std::size_t rows  = 0;
    for (const auto &[file, dim] :
         std::vector<std::pair<std::string, unsigned int>>{
           {"memory.csv", 3}, {"memory_2d.csv", 2}})
      {
        std::ifstream in(std::string(REPOSITORY_DIR) + "/benchmarks/results/" +
                         file);
        std::string   line;
        while (std::getline(in, line))
          close = memory_row_close(file, dim, line, rows) && close;
      }
    checks.add(close && rows == 8,
               "the memory model predicts the peak of the largest process "
               "within 12 % (benchmarks/results/memory.csv, 3D, 1 and 16 "
               "processes, and memory_2d.csv; AMG, GMG, matrix-free GMG)");
  }

  /** The preconditioner @p name with its default parameters. */
  const PreconditionerPlugin &
  plugin(const std::string &name)
  {
    static const Parameters::Solver defaults = automatic();
    return defaults.preconditioner_plugin(name);
  }

  /** The memory the rail 320 x 32 x 32 needs on 1 process. */
  double
  need(const std::string &name, const unsigned int degree)
  {
    return predicted_memory(plugin(name), 3, degree, rail(32).first, 1, 132);
  }

  /** Preconditioner = auto: the fastest that fits. */
  void
  check_preconditioner_choice(Checks &checks)
  {
    const auto dofs = rail(32).first;
    checks.add(preconditioner_candidates(automatic(), 1) ==
                   std::vector<std::string>{"AMG", "GMG", "matrix-free GMG"} &&
                 preconditioner_candidates(automatic(), 3) ==
                   std::vector<std::string>{"AMG"} &&
                 preconditioner_candidates(
                   automatic({"Preconditioner=matrix-free GMG"}), 1) ==
                   std::vector<std::string>{"matrix-free GMG"},
               "auto tries the preconditioners by their rank (AMG, GMG, "
               "matrix-free GMG), the geometric ones for degree 1 and 2 "
               "only; one set is the only candidate");
    checks.add(need("AMG", 1) > need("GMG", 1) &&
                 need("GMG", 1) > need("matrix-free GMG", 1),
               "the rail 320 x 32 x 32 needs the most with the AMG, the "
               "least with the matrix-free GMG");
    checks.add(
      predicted_memory(plugin("matrix-free GMG"), 3, 1, dofs, 1, dofs) ==
        need("AMG", 1),
      "on a mesh without levels the GMGs need what the AMG needs");
    bool        as_budgeted = true;
    std::string reason;
    for (const auto &[bytes, expected] :
         std::vector<std::pair<double, std::string>>{
           {std::numeric_limits<double>::infinity(), "AMG"},
           {1.01 * need("AMG", 1), "AMG"},
           {0.99 * need("AMG", 1), "GMG"},
           {0.99 * need("GMG", 1), "matrix-free GMG"},
           {0.5 * need("matrix-free GMG", 1), "matrix-free GMG"}})
      {
        MemoryBudget budget;
        budget.bytes_per_process = bytes;
        as_budgeted =
          as_budgeted &&
          choose_preconditioner(automatic(), 3, dofs, 1, budget, reason) ==
            expected;
      }
    checks.add(as_budgeted,
               "auto: the AMG while it fits, then the GMG, then the "
               "matrix-free GMG, which also serves where none fits");
    checks.add(reason.find("none fits") != std::string::npos &&
                 reason.find("matrix-free GMG") != std::string::npos,
               "the reason names the memory of each and says none fits");
    MemoryBudget small;
    small.bytes_per_process = 1e6;
    small.degree            = 3;
    checks.add(choose_preconditioner(automatic(), 3, dofs, 1, small, reason) ==
                 "AMG",
               "elements of degree 3: the AMG (the GMG is for degree 1 and "
               "2)");
  }

  /** In the plan: the assembled iterative solver only. */
  void
  check_preconditioner_in_plan(Checks &checks)
  {
    const auto self          = MPI_COMM_SELF;
    const auto [dofs, nodes] = rail(32);
    MemoryBudget small;
    small.bytes_per_process = 1e6;
    small.degree            = 1;
    auto p                  = automatic();
    p.preconditioner        = "auto";
    p.contact_solver        = "assembled";
    p.linear_solver         = Parameters::Solver::LinearSolver::iterative;
    const auto assembled    = plan_solver(p, 3, dofs, nodes, 1, self, small);
    p.contact_solver        = "condensed";
    const auto condensed    = plan_solver(p, 3, dofs, nodes, 1, self, small);
    p.preconditioner        = "GMG";
    p.contact_solver        = "assembled";
    const auto set          = plan_solver(p, 3, dofs, nodes, 1, self, small);
    checks.add(assembled.preconditioner == "matrix-free GMG" &&
                 assembled.matrix_free_bulk() &&
                 assembled.description().find("preconditioner "
                                              "matrix-free GMG") !=
                   std::string::npos &&
                 assembled.solver_parameters(p).preconditioner ==
                   "matrix-free GMG",
               "plan, assembled iterative, 1 MB per process: the "
               "matrix-free GMG, in the plan's description and in the "
               "solver's parameters");
    checks.add(condensed.preconditioner == "AMG" &&
                 set.preconditioner == "GMG" &&
                 condensed.preconditioner_reason.empty() &&
                 set.preconditioner_reason.empty(),
               "plan: the condensed solver takes the AMG; a preconditioner "
               "set is kept");
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checks                           checks;
  check_table(checks);
  check_growth(checks);
  check_beyond_two_processes(checks);
  check_lower_cost(checks);
  check_plan_options(checks);
  check_memory_model(checks);
  check_preconditioner_choice(checks);
  check_preconditioner_in_plan(checks);
  checks.assert_all();
}
