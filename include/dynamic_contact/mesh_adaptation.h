#ifndef dynamic_contact_mesh_adaptation_h
#define dynamic_contact_mesh_adaptation_h

#include <deal.II/base/point.h>

#include <dynamic_contact/linear_algebra.h>
#include <dynamic_contact/discretization.h>
#include <dynamic_contact/parameters.h>
#include <dynamic_contact/scene.h>

#include <functional>
#include <vector>

namespace DynamicContact
{
  /**
   * Where the mesh should be fine (the paper's scene, doc/theory.md
   * section 8: a Gaussian load of width ~1/sqrt(psi) travelling along the
   * rail). Each strategy of
   * Mesh refinement/Strategy asks for a level per cell:
   *   load following:    the maximum level within 'Load window' of a point
   *                      where the traction (or body force) is large at some
   *                      time until the next adaptation, from the expressions;
   *   contact following: the maximum level within 'Contact window' of a node
   *                      that penetrates the foundation;
   *   error indicator:   one level up or down by Kelly's indicator on u and w;
   * each cell is flagged towards the largest level asked for (the minimum
   * level if none asks), within the cell budget. One call flags one cycle
   * (a cell changes by at most one level); the caller repeats until nothing
   * is flagged, transferring the fields each time.
   */
  template <int dim>
  class MeshAdaptation
  {
  public:
    MeshAdaptation(const Parameters::MeshRefinement &parameters,
                   const Scene<dim> &                 scene,
                   Discretization<dim> &              discretization);

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

    /** The number of steps ahead that load following samples the load. */
    unsigned int
    lookahead_steps() const
    {
      return parameters.lookahead_steps > 0 ? parameters.lookahead_steps :
                                              parameters.refine_every;
    }

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
               const Vector_t &               u,
               const Vector_t &               w);

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

    /** The points where the load is large in [t0, t1] (every process). */
    std::vector<Point<dim>>
    large_load_points(const double t0, const double t1, const double k) const;

  private:
    const Parameters::MeshRefinement parameters;
    const Scene<dim> &               scene;
    Discretization<dim> &            discretization;
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
  refine_and_transfer(Discretization<dim> &          discretization,
                      const std::vector<Vector_t *> &fields,
                      const std::function<void()> &  after_refinement);
} // namespace DynamicContact

#endif
