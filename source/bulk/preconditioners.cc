// The preconditioners of K0 as plugins of Solver/Preconditioner
// (base/preconditioner_plugin.h): each makes its preconditioner for a K0,
// gives its share of the memory model and declares the entries of its own
// subsection of Solver.

#include <dynamic_contact/base/plugins.h>
#include <dynamic_contact/base/preconditioner_plugin.h>
#include <dynamic_contact/bulk/bulk_multigrid.h>
#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/bulk/preconditioners.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace DynamicContact
{
  namespace
  {
    /**
     * A plugin whose preconditioner of both dimensions Derived makes with
     * its template member make<dim>().
     */
    template <class Derived>
    class OfBothDimensions : public PreconditionerPlugin
    {
    public:
      std::unique_ptr<BulkPreconditioner>
      create(const PreconditionerInput<2> &input) const override
      {
        return static_cast<const Derived &>(*this).make(input);
      }

      std::unique_ptr<BulkPreconditioner>
      create(const PreconditionerInput<3> &input) const override
      {
        return static_cast<const Derived &>(*this).make(input);
      }
    };


    /** The AMG's share: its hierarchy and its peak while built. */
    PreconditionerMemory
    algebraic_memory(const PreconditionerMemoryTerms &terms)
    {
      return {(1 + terms.amg) * terms.matrix, 0.};
    }


    /** Solver/Preconditioner = AMG, with Solver/AMG. */
    class AlgebraicMultigrid : public OfBothDimensions<AlgebraicMultigrid>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Aggregation",
          "smoothed",
          Patterns::Selection("smoothed|plain"),
          "How the algebraic multigrid of K0 builds its coarse levels from "
          "aggregates of nodes. 'smoothed': smoothed aggregation, the "
          "fewest Krylov iterations. 'plain': the aggregates' rigid-body "
          "modes without smoothing, a hierarchy about a third as large and "
          "quicker to build, for more Krylov iterations: for a mesh whose "
          "memory is short (the memory table at the end of log.txt shows "
          "the hierarchy's share).");
      }

      void
      parse_parameters(ParameterHandler &prm)
      {
        smoothed = prm.get("Aggregation") == "smoothed";
      }

      std::optional<unsigned int>
      auto_rank() const override
      {
        return 0;
      }

      PreconditionerMemory
      memory(const PreconditionerMemoryTerms &terms) const override
      {
        return algebraic_memory(terms);
      }

      std::string
      in_words() const override
      {
        return smoothed ? "algebraic multigrid" :
                          "algebraic multigrid, plain aggregation";
      }

      template <int dim>
      std::unique_ptr<BulkPreconditioner>
      make(const PreconditionerInput<dim> &input) const
      {
        AssertThrow(input.matrix != nullptr,
                    ExcMessage("The AMG is built from a stored K0."));
        auto amg = std::make_unique<BulkAMG>();
        amg->initialize(*input.matrix,
                        input.discretization,
                        /*with_rotations=*/true,
                        smoothed);
        return amg;
      }

    private:
      bool smoothed = true;
    };


    /**
     * Solver/Preconditioner = GMG (@p stored: K0 stored and used on the
     * finest level) and matrix-free GMG (K0 applied cell by cell on every
     * level): create_bulk_multigrid().
     */
    template <bool stored>
    class GeometricMultigrid
      : public OfBothDimensions<GeometricMultigrid<stored>>
    {
    public:
      bool
      stores_matrix() const override
      {
        return stored;
      }

      std::string
      in_words() const override
      {
        return stored ? "geometric multigrid" :
                        "geometric multigrid, K0 applied cell by cell";
      }

      std::optional<unsigned int>
      highest_degree() const override
      {
        return 2;
      }

      /** After the AMG: the GMG, then the matrix-free GMG. */
      std::optional<unsigned int>
      auto_rank() const override
      {
        return stored ? 1 : 2;
      }

      /**
       * Its levels and K0 where stored per DoF; its coarsest level,
       * factorized while small, else its AMG. On a mesh without levels
       * (the coarsest level is the mesh) what the AMG needs.
       */
      PreconditionerMemory
      memory(const PreconditionerMemoryTerms &terms) const override
      {
        if (terms.coarse_dofs >= terms.n_dofs)
          return algebraic_memory(terms);
        return {(stored ? terms.matrix : 0.) + terms.levels,
                terms.coarse_dofs *
                  (terms.coarse_dofs <=
                       largest_factorized_coarse_level(terms.dim) ?
                     terms.factorized_coarsest :
                     (1 + terms.amg) * terms.matrix)};
      }

      /**
       * A mesh without levels to coarsen to (Geometry/Global refinements =
       * 0) has no geometric hierarchy: nullptr, the AMG of the stored K0
       * serves there (without a stored K0 the multigrid's coarsest level
       * is the mesh).
       */
      template <int dim>
      std::unique_ptr<BulkPreconditioner>
      make(const PreconditionerInput<dim> &input) const
      {
        if (input.discretization.triangulation.n_global_levels() <= 1 &&
            input.matrix != nullptr)
          return nullptr;
        AssertThrow(input.material != nullptr && input.scheme != nullptr,
                    ExcMessage("The geometric multigrid forms K0 on its "
                               "levels from the material and the scheme."));
        return create_bulk_multigrid(input.discretization,
                                     *input.material,
                                     *input.scheme,
                                     input.matrix,
                                     input.cell_data);
      }
    };
  } // namespace


  template <int dim>
  std::unique_ptr<BulkPreconditioner>
  create_preconditioner(const Parameters::Solver       &parameters,
                        const std::string              &name,
                        const PreconditionerInput<dim> &input)
  {
    std::unique_ptr<BulkPreconditioner> made =
      parameters.preconditioner_plugin(name).create(input);
    if (!made)
      made =
        parameters.preconditioner_plugin(algebraic_multigrid).create(input);
    return made;
  }


  std::vector<std::string>
  auto_preconditioners(const Parameters::Solver &parameters,
                       const unsigned int        degree)
  {
    std::vector<std::pair<unsigned int, std::string>> ranked;
    for (const auto &[name, plugin] : parameters.preconditioners)
      if (plugin->auto_rank() &&
          (!plugin->highest_degree() || degree <= *plugin->highest_degree()))
        ranked.emplace_back(*plugin->auto_rank(), name);
    std::sort(ranked.begin(), ranked.end());
    std::vector<std::string> names;
    for (const auto &[rank, name] : ranked)
      names.push_back(name);
    return names;
  }


  void
  declare_preconditioners(ParameterHandler &prm)
  {
    PluginRegistry<PreconditionerPlugin>::instance()
      .declare_parameters_with_auto(
        prm,
        "Preconditioner",
        "The preconditioner of the iterative solver (the solves with K0 and "
        "the Newton systems of the assembled solver), with the entries of "
        "its subsection where it has any. 'auto': for the assembled "
        "iterative solver, the fastest of AMG, GMG and matrix-free GMG (in "
        "this order) whose peak memory, as the memory model predicts it for "
        "the mesh, fits into Solver/Memory per process (the least hungry "
        "where none does); elsewhere the AMG. The log's solver plan names "
        "the choice and the memory predicted.");
  }


  template std::unique_ptr<BulkPreconditioner>
  create_preconditioner(const Parameters::Solver &,
                        const std::string &,
                        const PreconditionerInput<2> &);
  template std::unique_ptr<BulkPreconditioner>
  create_preconditioner(const Parameters::Solver &,
                        const std::string &,
                        const PreconditionerInput<3> &);


  DYNAMIC_CONTACT_REGISTER(
    PreconditionerPlugin,
    AlgebraicMultigrid,
    algebraic_multigrid,
    "algebraic multigrid of K0 (Trilinos ML; Solver/AMG), built once per "
    "mesh and time step.");

  DYNAMIC_CONTACT_REGISTER(
    PreconditionerPlugin,
    GeometricMultigrid<true>,
    "GMG",
    "geometric multigrid on the mesh coarsened level by level, K0 applied "
    "cell by cell on the coarser levels, Chebyshev smoothing: no AMG "
    "hierarchy to store (elements of degree 1 and 2; on a mesh without "
    "refinement levels, Geometry/Global refinements = 0 and no adaptive "
    "refinement yet, the AMG serves).");

  DYNAMIC_CONTACT_REGISTER(
    PreconditionerPlugin,
    GeometricMultigrid<false>,
    "matrix-free GMG",
    "the same, and K0 is not stored either but applied cell by cell on "
    "every level, for the least memory (no matrix at all but the coarsest "
    "level's) at a slower product with K0: the assembled solver with "
    "Linear solver = iterative only.");
} // namespace DynamicContact
