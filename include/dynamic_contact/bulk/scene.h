#ifndef dynamic_contact_scene_h
#define dynamic_contact_scene_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/distributed/tria.h>

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/parameters/parameters.h>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * Advice for a rectangle whose coarse mesh (@p repetitions cells) is
   * large, on @p n_processes > 1: every process of a
   * parallel::distributed::Triangulation holds the whole coarse mesh, so
   * the same mesh made of fewer repetitions and more global refinements
   * (each repetition halved as long as all are even) holds only each
   * process's part (the refinements at most 20; with an @p adaptive mesh
   * the refinement levels, counted from the coarse mesh, rise by as
   * much). Empty where there is nothing to gain (one process, fewer than
   * 10^5 coarse cells).
   */
  std::string
  coarse_mesh_note(const std::vector<unsigned int> &repetitions,
                   const unsigned int               global_refinements,
                   const unsigned int               n_processes,
                   const bool                       adaptive);


  /**
   * What a parameter file says about the world: the body's geometry, which
   * boundary does what, the loads, the initial state and the foundation's
   * initial gap. Everything here is data (function expressions, a mesh
   * file); a new scene needs no recompilation.
   */
  template <int dim>
  class Scene
  {
  public:
    /**
     * Parse the function-valued entries from @p prm (which must hold the
     * values read for @p parameters); an expression that does not parse is
     * an error naming its subsection.
     */
    Scene(const RunParameters &parameters, ParameterHandler &prm);

    /**
     * Create the coarse mesh (rectangle or Gmsh file), check that every
     * boundary id of the mesh is assigned exactly one condition and that
     * every id the parameter file names exists, then refine globally.
     */
    void
    create_mesh(parallel::distributed::Triangulation<dim> &tria,
                const bool refine_globally = true) const;

    /** Traction f_2(x, t) on the Traction ids. Call set_time() first. */
    Function<dim> &
    traction() const
    {
      return *traction_function;
    }

    /** Body force f_0(x, t). */
    Function<dim> &
    body_force() const
    {
      return *body_force_function;
    }

    Function<dim> &
    initial_displacement() const
    {
      return *initial_displacement_function;
    }

    Function<dim> &
    initial_velocity() const
    {
      return *initial_velocity_function;
    }

    /**
     * Whether there is an additional traction s(x, t) on Gamma_3
     * (manufactured solutions; face_load() gives it).
     */
    bool
    has_contact_source() const
    {
      return contact_source_nonzero;
    }

    /** An exact solution is known (a manufactured solution). */
    bool
    has_exact_solution() const
    {
      return exact_displacement_function != nullptr;
    }

    /** The exact displacement and velocity (has_exact_solution()). */
    Function<dim> &
    exact_displacement() const
    {
      return *exact_displacement_function;
    }
    Function<dim> &
    exact_velocity() const
    {
      return *exact_velocity_function;
    }

    /** Initial gap g0(x) >= 0 of Gamma_3 to the foundation. */
    Function<dim> &
    initial_gap() const
    {
      return *initial_gap_function;
    }

    /** False if the traction expression is identically zero (skip it). */
    bool
    has_traction() const
    {
      return traction_nonzero;
    }

    /** False if the body force expression is identically zero. */
    bool
    has_body_force() const
    {
      return body_force_nonzero;
    }

    /**
     * The first value of a function of the scene that is not finite, as a
     * message naming the function, the point and the time ("" if none):
     * the traction on the Traction faces, the contact source and the
     * initial gap on the Contact faces, the body force and the exact
     * solution in the body, at the vertices of the locally owned cells and
     * at @p times; with @p initial also the initial conditions (at t = 0).
     * Local: each process samples its own cells.
     */
    std::string
    non_finite_value(const Triangulation<dim>  &tria,
                     const std::vector<double> &times,
                     const bool                 initial) const;

    /** Set the time of the time-dependent functions (loads, source). */
    void
    set_time(const double t) const;

    /**
     * The load on face @p f of @p cell: the traction on a face of
     * Boundary conditions/Traction, the contact source on a face of
     * Contact (each only if its expression is not zero), nullptr
     * elsewhere. The one place that says which face carries which load,
     * for the load vector, the force balance and load following.
     */
    Function<dim> *
    face_load(const typename Triangulation<dim>::cell_iterator &cell,
              const unsigned int                                f) const;

    /** Whether @p cell carries a load: a body force or a loaded face. */
    bool
    carries_load(const typename Triangulation<dim>::cell_iterator &cell) const;

    /**
     * The load @p f at @p p in the equation of a step of @p scheme ending
     * at @p t: f(t) for backward Euler, theta f(t) + (1 - theta) f(t - k)
     * for the theta-scheme (@p old_value: room for f(t - k), sized like
     * @p value, so that quadrature loops allocate nothing). Sets the time of
     * the scene's functions.
     */
    void
    step_load(Function<dim>    &f,
              const Point<dim> &p,
              const double      t,
              const TimeScheme &scheme,
              Vector<double>   &value,
              Vector<double>   &old_value) const;

    const Parameters::BoundaryConditions &
    boundary_conditions() const
    {
      return boundaries;
    }

  private:
    Parameters::Geometry           geometry;
    Parameters::BoundaryConditions boundaries;

    std::unique_ptr<Functions::ParsedFunction<dim>> traction_function;
    std::unique_ptr<Functions::ParsedFunction<dim>> body_force_function;
    std::unique_ptr<Functions::ParsedFunction<dim>>
      initial_displacement_function;
    std::unique_ptr<Functions::ParsedFunction<dim>> initial_velocity_function;
    std::unique_ptr<Functions::ParsedFunction<dim>> initial_gap_function;
    std::unique_ptr<Functions::ParsedFunction<dim>> contact_source_function;
    std::unique_ptr<Functions::ParsedFunction<dim>> exact_displacement_function;
    std::unique_ptr<Functions::ParsedFunction<dim>> exact_velocity_function;
    /** The expressions, for messages. */
    std::map<const Function<dim> *, std::pair<std::string, std::string>>
         expressions;
    bool traction_nonzero;
    bool body_force_nonzero;
    bool contact_source_nonzero;
    /** The boundary ids of Traction and Contact (face_load). */
    std::set<types::boundary_id> traction_ids;
    std::set<types::boundary_id> contact_ids;

    void
    check_boundary_ids(const Triangulation<dim> &tria) const;
  };
} // namespace DynamicContact

#endif
