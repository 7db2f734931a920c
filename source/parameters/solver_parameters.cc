// The section Solver of a parameter file: declared and parsed. The other
// sections are in source/parameters/parameters.cc and
// source/parameters/run_parameters.cc.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/plugins.h>
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
       * Every registered implementation of @p Interface with the entries of
       * its subsection (of the current subsection of @p prm), by name.
       */
      template <class Interface>
      std::map<std::string, std::shared_ptr<const Interface>>
      create_every_plugin(ParameterHandler &prm)
      {
        const auto &registry = PluginRegistry<Interface>::instance();
        std::map<std::string, std::shared_ptr<const Interface>> plugins;
        for (const std::string &name : registry.registered())
          plugins.emplace(name, registry.create(name, prm));
        return plugins;
      }

      /** The entry @p name of @p plugins (a @p kind, for the error). */
      template <class Interface>
      const Interface &
      registered_plugin(
        const std::map<std::string, std::shared_ptr<const Interface>> &plugins,
        const std::string                                             &name,
        const std::string                                             &kind)
      {
        const auto found = plugins.find(name);
        AssertThrow(found != plugins.end() && found->second,
                    ExcMessage("No " + kind + " '" + name +
                               "' is registered."));
        return *found->second;
      }

      /** Solver: the entries of the semismooth Newton iteration. */
      void
      declare_newton_entries(ParameterHandler &prm)
      {
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
        declare_preconditioners(prm);
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
        declare_contact_solvers(prm);
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
      contact_solver = prm.get("Contact solver");
      contact_solvers       = create_every_plugin<ContactSolverPlugin>(prm);
      min_dofs_per_process  = prm.get_integer("Minimum DoFs per process");
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
      preconditioner        = prm.get("Preconditioner");
      preconditioners       = create_every_plugin<PreconditionerPlugin>(prm);
      {
        const std::string           memory = prm.get("Memory per process");
        const std::optional<double> gb =
          positive_or_auto(memory,
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

    const ContactSolverPlugin &
    Solver::contact_solver_plugin(const std::string &name) const
    {
      return registered_plugin(contact_solvers, name, "contact solver");
    }

    const PreconditionerPlugin &
    Solver::preconditioner_plugin(const std::string &name) const
    {
      return registered_plugin(preconditioners, name, "preconditioner");
    }
  } // namespace Parameters
} // namespace DynamicContact
