#ifndef dynamic_contact_refinement_strategy_h
#define dynamic_contact_refinement_strategy_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <dynamic_contact/base/plugins.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/bulk/scene.h>

#include <functional>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /** What a refinement strategy may look at when the mesh adapts. */
  template <int dim>
  struct AdaptationContext
  {
    const Scene<dim> &scene;
    /** Non-const: a strategy may use (and must clear) refinement flags. */
    Discretization<dim> &discretization;
    /** The times [t0, t1] until the next adaptation, sampled every k. */
    double t0, t1, k;
    /** The nodes of Gamma_3 that penetrate the foundation (every process;
     *  empty unless a strategy needs_contact_points()). */
    const std::vector<Point<dim>> &contact_points;
    /** Displacement and velocity, ghosted and expanded. */
    const Vector_t &u;
    const Vector_t &w;
  };


  /**
   * One way of saying where the mesh should be fine, chosen by name in the
   * list Mesh refinement/Strategy (doc/extending.md): for each locally
   * owned cell, the level it asks for. MeshAdaptation gives every cell the
   * largest level any strategy asks for (the minimum level if none asks),
   * within the levels and the cell budget.
   *
   * An implementation declares and parses the entries of its subsection
   * Mesh refinement/<Name> (static declare_parameters, parse_parameters)
   * and is registered for both dimensions with
   * DYNAMIC_CONTACT_REGISTER_STRATEGY(Class, "name", "description").
   */
  template <int dim>
  class RefinementStrategy
  {
  public:
    using Cell = typename Triangulation<dim>::active_cell_iterator;
    /**
     * The level a cell asks for (at most @p max_level, the finest level of
     * this adaptation), or -1 for no request.
     */
    using Levels = std::function<int(const Cell &, unsigned int max_level)>;

    virtual ~RefinementStrategy() = default;

    virtual void
    parse_parameters(ParameterHandler &prm) = 0;

    /**
     * Collective: look at the state (and the load ahead) once per
     * refinement cycle and return the levels the cells ask for.
     */
    virtual Levels
    levels(const AdaptationContext<dim> &context) const = 0;

    /** Whether levels() needs AdaptationContext::contact_points. */
    virtual bool
    needs_contact_points() const
    {
      return false;
    }

    /**
     * How many steps ahead the strategy looks (t1 - t0 = this times k);
     * 0: until the next adaptation.
     */
    virtual unsigned int
    lookahead_steps() const
    {
      return 0;
    }

    /**
     * The strategies @p names (Parameters::MeshRefinement::strategies, the
     * list Mesh refinement/Strategy without 'none'), each with the
     * parameters of its subsection (called at the top level of @p prm).
     */
    static std::vector<std::unique_ptr<const RefinementStrategy<dim>>>
    create(ParameterHandler &prm, const std::vector<std::string> &names);
  };


  /**
   * Whether a cell lies within @p window of one of @p points (its centre
   * closer than window plus half its diameter).
   */
  template <int dim>
  bool
  cell_near(const typename Triangulation<dim>::active_cell_iterator &cell,
            const std::vector<Point<dim>>                           &points,
            const double                                             window);
} // namespace DynamicContact

/** Register @p classname<2> and @p classname<3> as refinement strategy @p name.
 */
#define DYNAMIC_CONTACT_REGISTER_STRATEGY(classname, name, description) \
  DYNAMIC_CONTACT_REGISTER(::DynamicContact::RefinementStrategy<2>,     \
                           classname<2>,                                \
                           name,                                        \
                           description);                                \
  DYNAMIC_CONTACT_REGISTER(::DynamicContact::RefinementStrategy<3>,     \
                           classname<3>,                                \
                           name,                                        \
                           description)

#endif
