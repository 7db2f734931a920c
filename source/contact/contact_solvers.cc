// The contact solvers as plugins of Solver/Contact solver
// (base/contact_solver_plugin.h): each makes its solver for a mesh and
// declares the entries of its own subsection of Solver.

#include <dynamic_contact/base/contact_solver_plugin.h>
#include <dynamic_contact/base/number_or_auto.h>
#include <dynamic_contact/base/plugins.h>
#include <dynamic_contact/contact/assembled_solver.h>
#include <dynamic_contact/contact/condensed_solver.h>

#include <optional>
#include <string>

namespace DynamicContact
{
  namespace
  {
    /** A plugin that makes the solver Solver<dim> of both dimensions. */
    template <template <int> class Solver>
    class SolverOfBothDimensions : public ContactSolverPlugin
    {
    public:
      std::unique_ptr<ContactSolver<2>>
      create(const ContactProblem<2> &problem) const override
      {
        return std::make_unique<Solver<2>>(problem);
      }

      std::unique_ptr<ContactSolver<3>>
      create(const ContactProblem<3> &problem) const override
      {
        return std::make_unique<Solver<3>>(problem);
      }
    };


    /**
     * The same, for a solver that may solve the passes of a convexification
     * loop provisionally: its entry Provisional passes (default true), whose
     * text says what such a pass does (@p what_a_pass_does).
     */
    template <template <int> class Solver>
    class SolverWithProvisionalPasses : public SolverOfBothDimensions<Solver>
    {
    public:
      bool
      provisional_passes() const override
      {
        return provisional;
      }

    protected:
      static void
      declare_provisional_passes(ParameterHandler  &prm,
                                 const std::string &what_a_pass_does)
      {
        prm.declare_entry("Provisional passes",
                          "true",
                          Patterns::Bool(),
                          "With a convexification loop: a pass that does not "
                          "end the loop " +
                            what_a_pass_does +
                            " (doc/algorithms.md, 'Convexification loop'); "
                            "false: every pass is solved in full.");
      }

      void
      parse_provisional_passes(ParameterHandler &prm)
      {
        provisional = prm.get_bool("Provisional passes");
      }

    private:
      bool provisional = true;
    };


    /** Solver/Contact solver = condensed, with Solver/Condensed. */
    class Condensed : public SolverWithProvisionalPasses<CondensedSolver>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_provisional_passes(
          prm,
          "takes its velocity from the stored compliance responses, without "
          "a solve with K0");
        prm.declare_entry(
          "Limit",
          "8200",
          Patterns::Integer(0),
          "Contact solver = auto on one process: the largest dim times the "
          "number of contact nodes for which the condensed solver may be "
          "chosen (its dense tables hold 8 bytes x (dim n_Gamma)^2 twice; "
          "within it the cost model chooses).");
        prm.declare_entry(
          "Limit on several processes",
          "auto",
          Patterns::Anything(),
          "Contact solver = auto on more than one process where K0 is "
          "factorized by MUMPS over the processes (Direct solver package): "
          "the same cap, an integer >= 0 or 'auto'. In 2D the compliance "
          "then costs dim solves per contact node, so the condensed solver "
          "is the faster one only on small contact boundaries: 'auto' is "
          "1000. In 3D it comes from MUMPS's Schur complement: 'auto' is "
          "Limit. Where every process factorizes the whole K0 (a small K0, "
          "Direct solver package = auto), Limit applies as on one process. "
          "Rank 0 holds the dense tables (8 bytes x (dim n_Gamma)^2 "
          "twice).");
      }

      void
      parse_parameters(ParameterHandler &prm)
      {
        parse_provisional_passes(prm);
        limit                     = prm.get_integer("Limit");
        const std::string several = prm.get("Limit on several processes");
        limit_on_several_processes =
          count_or_auto(several,
                        "Solver/Condensed/Limit on several processes: '" +
                          several + "' is neither an integer >= 0 nor 'auto'.");
      }

      /**
       * Limit; with K0 factorized by MUMPS over the processes, Limit on
       * several processes (auto: Limit in 3D, where the compliance comes
       * from MUMPS's Schur complement; 1000 in 2D, where it costs dim
       * solves per contact node).
       */
      std::optional<unsigned int>
      boundary_limit(const unsigned int dim,
                     const bool         distributed) const override
      {
        if (!distributed)
          return limit;
        return limit_on_several_processes.value_or(dim == 3 ? limit : 1000);
      }

    private:
      unsigned int                limit = 8200;
      std::optional<unsigned int> limit_on_several_processes;
    };


    /** Solver/Contact solver = assembled, with Solver/Assembled. */
    class Assembled : public SolverWithProvisionalPasses<AssembledSolver>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_provisional_passes(
          prm,
          "stops its Newton iteration once its velocities are as accurate "
          "as the loop's next coefficients and its stopping rule need, and "
          "the pass that ends the loop is finished to the Newton "
          "tolerance");
      }

      void
      parse_parameters(ParameterHandler &prm)
      {
        parse_provisional_passes(prm);
      }
    };
  } // namespace


  void
  declare_contact_solvers(ParameterHandler &prm)
  {
    PluginRegistry<ContactSolverPlugin>::instance()
      .declare_parameters_with_auto(
        prm,
        "Contact solver",
        "How each semismooth Newton system is solved (all give the same "
        "iterates, to the Newton tolerance), with the entries of the solver's "
        "subsection where it has any. 'auto': the one of the lower predicted "
        "cost, condensed or assembled, for the steps one bulk matrix serves "
        "(the steps left, or to the next mesh adaptation; one with an "
        "adaptive time step), from a cost model of the DoFs, the contact "
        "nodes and the processes fitted to benchmarks/scaling; the condensed "
        "one only while dim times the number of contact nodes is at most "
        "Condensed/Limit (one process) or Condensed/Limit on several "
        "processes, and on meshes smaller than the model's always; the "
        "assembled one with the iterative linear solver. Decided per mesh; "
        "the log gives the predicted costs (the solver plan).");
  }


  DYNAMIC_CONTACT_REGISTER(
    ContactSolverPlugin,
    Condensed,
    "condensed",
    "static condensation onto Gamma_3 - the bulk matrix K0 is factorized "
    "once per mesh and time step, the compliance of the contact nodes "
    "computed from it (from the Schur complement on Gamma_3: on one process "
    "from the Cholesky factor, on several in 3D from a MUMPS factorization "
    "where it agrees with the solves, else by dim solves per node), and "
    "each iteration is a dense solve on the active contact nodes; Gamma_3 "
    "is replicated on every process.");

  DYNAMIC_CONTACT_REGISTER(
    ContactSolverPlugin,
    Assembled,
    "assembled",
    "the sparse Newton system of the whole body, per process only its own "
    "part (with Linear solver = iterative: GMRES preconditioned by "
    "multigrid of K0, built once per mesh and time step; with direct: the "
    "Newton matrix factorized when it changes, as in deal.II's step-42).");
} // namespace DynamicContact
