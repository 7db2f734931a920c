#ifndef dynamic_contact_mesh_adaptation_h
#define dynamic_contact_mesh_adaptation_h

#include <deal.II/base/point.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/mesh/refinement_strategy.h>
#include <dynamic_contact/bulk/scene.h>

#include <functional>
#include <vector>

namespace DynamicContact
{
  /**
   * Where the mesh should be fine (the paper's scene, doc/theory.md
   * section 8: a Gaussian load of width ~1/sqrt(psi) travelling along the
   * rail). Each RefinementStrategy of Mesh refinement/Strategy (load
   * following, contact following, error indicator, or one of your own)
   * asks for a level per cell; each cell is flagged towards the largest level
   * asked for (the minimum level if none asks), within the cell budget. One
   * call flags one cycle (a cell changes by at most one level); the caller
   * repeats until nothing is flagged, transferring the fields each time.
   */
  template <int dim>
  class MeshAdaptation
  {
  public:
    /** The strategies are created from @p prm (Mesh refinement/Strategy). */
    MeshAdaptation(const Parameters::MeshRefinement &parameters,
                   const Scene<dim>                 &scene,
                   Discretization<dim>              &discretization,
                   ParameterHandler                 &prm);

    bool
    enabled() const
    {
      return parameters.enabled();
    }

    /** Adapt before step @p step (1-based): every 'Refine every' steps. */
    bool
    due(const unsigned int step) const
    {
      return enabled() && step > 1 && (step - 1) % parameters.refine_every == 0;
    }

    /**
     * The number of steps ahead the strategies look (the largest they ask
     * for; 'Refine every' if none asks).
     */
    unsigned int
    lookahead_steps() const;

    /** Whether flag_cells() needs the penetrating nodes of Gamma_3. */
    bool
    needs_contact_points() const;

    /**
     * Set refinement and coarsening flags for the times [t0, t1] (sampled
     * every k) from the penetrating nodes @p contact_points and the ghosted,
     * expanded fields @p u and @p w (for the error indicator). Returns true
     * if any cell of any process is flagged.
     */
    bool
    flag_cells(const double                   t0,
               const double                   t1,
               const double                   k,
               const std::vector<Point<dim>> &contact_points,
               const Vector_t                &u,
               const Vector_t                &w);

    /**
     * The most refinement cycles one adaptation needs: a cell changes by one
     * level per cycle.
     */
    unsigned int
    max_cycles() const
    {
      return parameters.maximum_level - parameters.minimum_level + 1;
    }

    /**
     * A fingerprint of the mesh (number of active cells and the sum of their
     * levels over all processes): a cycle that leaves it unchanged changed
     * nothing (p4est drops coarsening flags of incomplete families).
     */
    std::pair<types::global_cell_index, double>
    fingerprint() const;


  private:
    const Parameters::MeshRefinement parameters;
    const Scene<dim>                &scene;
    Discretization<dim>             &discretization;
    const std::vector<std::unique_ptr<const RefinementStrategy<dim>>>
      strategies;
  };


  /**
   * Execute the refinement and coarsening flagged on the mesh of
   * @p discretization and carry @p fields (vectors in master form) over to
   * the new mesh: expanded (hanging nodes filled in), transferred with
   * parallel::distributed::SolutionTransfer (p4est repartitions the mesh),
   * and brought back to master form. @p after_refinement must set up the
   * new DoFs and constraints (Discretization::setup_dofs, and what depends
   * on them). Interpolation onto children and back to the parent is exact:
   * refining and coarsening back returns the fields unchanged.
   */
  template <int dim>
  void
  refine_and_transfer(Discretization<dim>           &discretization,
                      const std::vector<Vector_t *> &fields,
                      const std::function<void()>   &after_refinement);
} // namespace DynamicContact

#endif
