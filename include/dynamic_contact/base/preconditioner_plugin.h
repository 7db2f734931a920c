#ifndef dynamic_contact_preconditioner_plugin_h
#define dynamic_contact_preconditioner_plugin_h

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <optional>
#include <string>

namespace DynamicContact
{
  class BulkPreconditioner;
  template <int dim>
  struct PreconditionerInput;

  /**
   * What the memory model (predicted_memory()) knows of a run when it asks
   * a preconditioner for its share: the mesh and the coefficients fitted to
   * benchmarks/memory, in bytes.
   */
  struct PreconditionerMemoryTerms
  {
    unsigned int dim = 3;
    /** The bulk DoFs of the mesh and of its coarsest level. */
    double n_dofs = 0, coarse_dofs = 0;
    /** Bytes per DoF of K0 and its sparsity pattern. */
    double matrix = 0;
    /** The AMG's hierarchy and its peak while built, per byte of K0. */
    double amg = 0;
    /** Bytes per DoF of a geometric multigrid's coarser levels. */
    double levels = 0;
    /** Bytes per DoF of a coarsest level factorized (KLU). */
    double factorized_coarsest = 0;
  };

  /** A preconditioner's share of the memory of a run. */
  struct PreconditionerMemory
  {
    /** Bytes per DoF of the process (K0 where stored, the hierarchy). */
    double per_dof = 0;
    /** Bytes per process whatever its share of the DoFs. */
    double fixed = 0;
  };

  /**
   * The interface of Solver/Preconditioner (a plugin in the way of the laws,
   * doc/extending.md): the preconditioner of the iterative solves with the
   * bulk matrix K0 and of the assembled solver's Newton systems, with the
   * entries of its own subsection of Solver (named after it: 'AMG' ->
   * Solver/AMG). An implementation registers with
   * DYNAMIC_CONTACT_REGISTER(PreconditionerPlugin, Class, "name",
   * "description") in source/bulk/preconditioners.cc (which
   * declare_preconditioners() links into the program). Preconditioner =
   * auto tries those with an auto_rank(), in its order, and takes the first
   * whose memory, as the memory model predicts it, fits (SolverPlan).
   *
   * The object is the parsed parameters, not state of a run: it makes a
   * preconditioner for each K0 (create()).
   */
  class PreconditionerPlugin
  {
  public:
    virtual ~PreconditionerPlugin() = default;

    /**
     * The preconditioner for @p input (a mesh and its K0); nullptr where it
     * cannot serve on this mesh (a geometric multigrid on a mesh without
     * levels to coarsen to, K0 stored): then the AMG serves
     * (create_preconditioner()).
     */
    virtual std::unique_ptr<BulkPreconditioner>
    create(const PreconditionerInput<2> &input) const = 0;
    virtual std::unique_ptr<BulkPreconditioner>
    create(const PreconditionerInput<3> &input) const = 0;

    /**
     * Whether K0 is stored for it; false: K0 is applied cell by cell,
     * which only the assembled iterative solver can do.
     */
    virtual bool
    stores_matrix() const
    {
      return true;
    }

    /** The highest degree of the elements it is made for (none: any). */
    virtual std::optional<unsigned int>
    highest_degree() const
    {
      return std::nullopt;
    }

    /**
     * Preconditioner = auto: its place among those tried (0 first: the
     * fastest); none: auto never chooses it.
     */
    virtual std::optional<unsigned int>
    auto_rank() const
    {
      return std::nullopt;
    }

    /** Its share of the memory model (predicted_memory()). */
    virtual PreconditionerMemory
    memory(const PreconditionerMemoryTerms &terms) const = 0;

    /**
     * What the Krylov solver is preconditioned with, for the solver plan in
     * the log: "algebraic multigrid", ...
     */
    virtual std::string
    in_words() const = 0;
  };

  /**
   * Declare, in the current subsection of @p prm (Solver), the entry
   * 'Preconditioner' (auto or one of the registered preconditioners) and
   * the subsection of every preconditioner that has entries. Defined in
   * source/bulk/preconditioners.cc, beside the registrations, so that they
   * are part of the program.
   */
  void
  declare_preconditioners(dealii::ParameterHandler &prm);
} // namespace DynamicContact

#endif
