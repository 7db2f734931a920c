// The section Solver of a parameter file: declared and parsed. The other
// sections are in source/parameters/parameters.cc and
// source/parameters/run_parameters.cc.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/parameters/parameters.h>

#include "parameter_tools.h"

#include <cmath>
#include <optional>
#include <string>

namespace DynamicContact
{
  using namespace ParameterTools;

  namespace Parameters
  {
    namespace
    {
      /**
       * Solver: the choice of the contact solver and the caps of the
       * condensed one.
       */
      void
      declare_contact_solver_entries(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Contact solver",
          "auto",
          Patterns::Selection("auto|condensed|assembled"),
          "How each semismooth Newton system is solved (all give the same "
          "iterates, to the Newton tolerance). 'condensed': static "
          "condensation onto Gamma_3 - the bulk matrix K0 is factorized once "
          "per mesh and time step, the compliance of the contact nodes "
          "computed from it (from the Schur complement on Gamma_3: on one "
          "process from the Cholesky factor, on several in 3D from a MUMPS "
          "factorization where it agrees with the solves, else by dim "
          "solves per node), and each iteration is a "
          "dense solve on the active contact nodes; Gamma_3 is replicated on "
          "every process. 'assembled': the sparse Newton system of the whole "
          "body, per process only its own part (with Linear solver = "
          "iterative: GMRES preconditioned by algebraic multigrid of K0, "
          "built once per mesh and time step; with direct: the Newton matrix "
          "factorized when it changes, as in deal.II's step-42). 'auto': "
          "the one of the lower predicted cost for the steps one bulk "
          "matrix serves (the steps left, or to the next mesh adaptation; "
          "one with an adaptive time step), from a cost model of the DoFs, "
          "the contact nodes and the processes fitted to "
          "benchmarks/scaling; the condensed one only while dim times the "
          "number of contact nodes is at most Condensed limit (one process) "
          "or Condensed limit on several processes, and on meshes smaller "
          "than the model's always; the assembled one with the iterative "
          "linear solver. Decided per mesh; the log gives the predicted "
          "costs (the solver plan).");
        prm.declare_entry(
          "Condensed limit",
          "8200",
          Patterns::Integer(0),
          "Contact solver = auto on one process: the largest dim times the "
          "number of contact nodes for which the condensed solver may be "
          "chosen (its dense tables hold 8 bytes x (dim n_Gamma)^2 twice; "
          "within it the cost model chooses).");
        prm.declare_entry(
          "Condensed limit on several processes",
          "auto",
          Patterns::Anything(),
          "Contact solver = auto on more than one process where K0 is "
          "factorized by MUMPS over the processes (Direct solver package): "
          "the same cap, an integer >= 0 or 'auto'. In 2D the compliance "
          "then costs dim solves per contact node, so the condensed solver "
          "is the faster one only on small contact boundaries: 'auto' is "
          "1000. In 3D it comes from MUMPS's Schur complement: 'auto' is "
          "Condensed limit. Where every process factorizes the whole K0 "
          "(a small K0, Direct solver package = auto), Condensed limit "
          "applies as on one process. Rank 0 holds the dense tables (8 "
          "bytes x (dim n_Gamma)^2 twice).");
      }


      /** Solver: the entries of the semismooth Newton iteration. */
      void
      declare_newton_entries(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Provisional passes",
          "true",
          Patterns::Bool(),
          "Condensed solver with a convexification loop: a pass that does "
          "not end the loop takes its velocity from the stored compliance "
          "responses, without a solve with K0 (doc/algorithms.md, "
          "'Convexification loop'); false: every pass is solved in full.");
        prm.declare_entry(
          "Line search",
          "true",
          Patterns::Bool(),
          "Globalize the semismooth Newton iteration (condensed solver): "
          "when the active sets cycle (return to sets seen before) or, from "
          "the fifth iteration on, the merit function (half the squared "
          "residual) rises above that of the last five iterates, backtrack "
          "along the Newton step until it decreases (Armijo).");
        prm.declare_entry("Newton tolerance",
                          "1e-10",
                          Patterns::Double(),
                          "The semismooth Newton iteration stops when the "
                          "active sets no longer change and the residual is "
                          "below this, relative to the right-hand side.");
        prm.declare_entry("Maximum Newton iterations",
                          "50",
                          Patterns::Integer(1),
                          "Cap on the semismooth Newton iterations of one "
                          "solve; reaching it is an error.");
      }


      /** Solver: the entries of the linear solver. */
      void
      declare_linear_solver_entries(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Linear solver",
          "auto",
          Patterns::Selection("auto|direct|iterative"),
          "'direct': sparse direct factorization (package chosen below). "
          "'iterative': Krylov (CG or GMRES) preconditioned with algebraic "
          "multigrid, for problems too large for a direct solver. 'auto': "
          "direct, except where Contact solver = auto chooses the assembled "
          "solver (a large contact boundary), which then solves "
          "iteratively. The choice is printed with the solver plan "
          "(log.txt).");
        prm.declare_entry(
          "Direct solver package",
          "auto",
          Patterns::Selection("auto|Amesos_Mumps|Amesos_Klu"),
          "The sparse direct solver. 'auto': SuiteSparse CHOLMOD (sparse "
          "Cholesky) for the condensed solver on one process, and on "
          "up to 4 while K0 is small (up to 1e5 DoFs in 2D, 3e4 in 3D: "
          "every process factorizes the whole matrix), MUMPS everywhere "
          "else; 'Amesos_Mumps', 'Amesos_Klu': that Trilinos Amesos "
          "package everywhere.");
        prm.declare_entry("Linear tolerance",
                          "1e-12",
                          Patterns::Double(),
                          "Relative residual reduction of the iterative "
                          "solver.");
        prm.declare_entry("Maximum linear iterations",
                          "1000",
                          Patterns::Integer(1),
                          "Cap on the iterations of the iterative solver.");
        prm.declare_entry(
          "AMG aggregation",
          "smoothed",
          Patterns::Selection("smoothed|plain"),
          "How the algebraic multigrid of K0 (the iterative solver's "
          "preconditioner) builds its coarse levels from aggregates of "
          "nodes. 'smoothed': smoothed aggregation, the fewest Krylov "
          "iterations. 'plain': the aggregates' rigid-body modes without "
          "smoothing, a hierarchy about a third as large and quicker to "
          "build, for more Krylov iterations: for a mesh whose memory is "
          "short (the memory table at the end of log.txt shows the "
          "hierarchy's share).");
        prm.declare_entry(
          "Preconditioner",
          "auto",
          Patterns::Selection("auto|AMG|GMG|matrix-free GMG"),
          "The preconditioner of the iterative solver (the solves with K0 "
          "and the Newton systems of the assembled solver). 'AMG': "
          "algebraic multigrid of K0 (Trilinos ML; Solver/AMG "
          "aggregation). 'GMG': geometric multigrid on the mesh "
          "coarsened level by level, K0 applied cell by cell on the "
          "coarser levels, Chebyshev smoothing: no AMG hierarchy to store "
          "(elements of degree 1 and 2; on a mesh without refinement "
          "levels, Geometry/Global refinements = 0 and no adaptive "
          "refinement yet, the AMG serves). 'matrix-free GMG': the same, "
          "and K0 is not stored either but applied cell by cell on every "
          "level, for the least memory (no matrix at all but the coarsest "
          "level's) at a slower product with K0: the assembled solver "
          "with Linear solver = iterative only. 'auto': for the assembled "
          "iterative solver, the fastest of AMG, GMG and matrix-free GMG "
          "(in this order) whose peak memory, as the memory model predicts "
          "it for the mesh, fits into Solver/Memory per process (the least "
          "hungry where none does); elsewhere the AMG. The log's solver "
          "plan names the choice and the memory predicted.");
        prm.declare_entry(
          "Memory per process",
          "auto",
          Patterns::Anything(),
          "The memory, in GB, that one process may use: Preconditioner = "
          "auto chooses by it. 'auto': what each host of the run had "
          "available when the run started (MemAvailable of /proc/meminfo), "
          "shared by the run's processes on it, the least over the hosts. "
          "Set it where the run may use less than the host has (a batch "
          "system's memory limit, other jobs).");
      }
    } // namespace

    // -------------------------------------------------------------- Solver
    void
    Solver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Solver");
      {
        declare_contact_solver_entries(prm);
        prm.declare_entry(
          "Minimum DoFs per process",
          "20000",
          Patterns::Integer(0),
          "A run started on more processes than the DoFs of its initial "
          "mesh (the uniform mesh after Geometry/Global refinements) "
          "divided by this number takes part on that many processes only, "
          "the first ones (at least one); the others wait for it and end "
          "with it. Below about this many DoFs per process the work a "
          "process adds costs more than it saves (benchmarks/processes). "
          "The log names the processes that take part. 0: every process "
          "takes part.");
        declare_newton_entries(prm);
        declare_linear_solver_entries(prm);
      }
      prm.leave_subsection();
    }

    void
    Solver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Solver");
      contact_solver =
        (prm.get("Contact solver") == "assembled" ? ContactSolver::assembled :
         prm.get("Contact solver") == "condensed" ? ContactSolver::condensed :
                                                    ContactSolver::automatic);
      condensed_limit = prm.get_integer("Condensed limit");
      {
        const std::string limit =
          prm.get("Condensed limit on several processes");
        const std::optional<long> value = number_or_auto<long>(
          limit,
          [](const std::string &t, std::size_t *end) {
            return std::stol(t, end);
          },
          [](const long v) { return v >= 0; },
          "Solver/Condensed limit on several processes: '" + limit +
            "' is neither an integer >= 0 nor 'auto'.");
        condensed_limit_on_several_processes.reset();
        if (value)
          condensed_limit_on_several_processes = *value;
      }
      min_dofs_per_process  = prm.get_integer("Minimum DoFs per process");
      provisional_passes    = prm.get_bool("Provisional passes");
      line_search           = prm.get_bool("Line search");
      newton_tolerance      = prm.get_double("Newton tolerance");
      max_newton_iterations = prm.get_integer("Maximum Newton iterations");
      linear_solver =
        (prm.get("Linear solver") == "iterative" ? LinearSolver::iterative :
         prm.get("Linear solver") == "direct"    ? LinearSolver::direct :
                                                   LinearSolver::automatic);
      direct_solver_package = prm.get("Direct solver package");
      linear_tolerance      = prm.get_double("Linear tolerance");
      max_linear_iterations = prm.get_integer("Maximum linear iterations");
      smoothed_aggregation  = prm.get("AMG aggregation") == "smoothed";
      {
        const std::string name = prm.get("Preconditioner");
        preconditioner         = name == "AMG" ? Preconditioner::amg :
                                 name == "GMG" ? Preconditioner::gmg :
                                 name == "matrix-free GMG" ?
                                                 Preconditioner::matrix_free_gmg :
                                                 Preconditioner::automatic;
      }
      {
        const std::string           memory = prm.get("Memory per process");
        const std::optional<double> gb     = number_or_auto<double>(
          memory,
          [](const std::string &t, std::size_t *end) {
            return std::stod(t, end);
          },
          [](const double v) { return std::isfinite(v) && v > 0; },
          "Solver/Memory per process: '" + memory +
            "' is neither a number of GB > 0 nor 'auto'.");
        memory_per_process.reset();
        if (gb)
          memory_per_process = *gb * 1e9;
      }
      prm.leave_subsection();
      require(std::isfinite(newton_tolerance) && newton_tolerance > 0 &&
                newton_tolerance < 1,
              "Solver/Newton tolerance must lie in (0, 1), got " +
                str(newton_tolerance) + ".");
      require(std::isfinite(linear_tolerance) && linear_tolerance > 0 &&
                linear_tolerance < 1,
              "Solver/Linear tolerance must lie in (0, 1), got " +
                str(linear_tolerance) + ".");
    }
  } // namespace Parameters
} // namespace DynamicContact
