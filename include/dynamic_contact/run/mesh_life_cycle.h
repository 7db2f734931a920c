#ifndef dynamic_contact_mesh_life_cycle_h
#define dynamic_contact_mesh_life_cycle_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/mesh/mesh_adaptation.h>
#include <dynamic_contact/parameters/parameters.h>

#include <functional>
#include <string>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * What a change of the mesh and a checkpoint carry of a run's state, as
   * finite element fields: u and w, the friction forces of the
   * ContactState (ContactState::friction_field()) and, with a slip length,
   * the coefficient states (ContactState::state_field()). take() makes the
   * fields of the state before the mesh changes (or is saved), give_back()
   * puts the friction forces and states on the nodes of the new mesh (or
   * of the loaded one).
   */
  template <int dim>
  class CarriedFields
  {
  public:
    /**
     * @p per_weight: the friction forces as a traction (the form that
     * survives interpolation to a new mesh), else as the nodal forces (a
     * checkpoint stores them exactly with the mesh); @p with_states: the
     * coefficient states too (Friction/Slip length active).
     */
    CarriedFields(Vector_t  &u,
                  Vector_t  &w,
                  const bool per_weight,
                  const bool with_states);

    void
    take(const ContactState<dim>    &state,
         const Discretization<dim>  &discretization,
         const ContactBoundary<dim> &boundary);
    void
    give_back(ContactState<dim>          &state,
              const ContactBoundary<dim> &boundary) const;

    /** u, w, the friction forces and (with states) the states. */
    const std::vector<Vector_t *> &
    vectors() const
    {
      return fields;
    }

  private:
    const bool              per_weight, with_states;
    Vector_t                friction, states;
    std::vector<Vector_t *> fields;
  };


  /**
   * The mesh of a run from its creation to each adaptation, the part of
   * the Simulator that changes the mesh: the coarse mesh of the scene,
   * checked against the resources before it is allocated; the refinement
   * for the initial load; the adaptation before a step, which carries the
   * fields and the friction forces over to the new mesh (CarriedFields).
   * Where cells are refined is MeshAdaptation's business (the strategies of
   * Mesh refinement); what depends on the DoFs is set up by the caller's
   * @p setup_dofs after each change.
   */
  template <int dim>
  class MeshLifeCycle
  {
  public:
    MeshLifeCycle(const RunParameters        &parameters,
                  ParameterHandler           &prm,
                  const Scene<dim>           &scene,
                  Discretization<dim>        &discretization,
                  const ContactBoundary<dim> &contact_boundary,
                  const MPI_Comm              comm);

    /**
     * Create the coarse mesh of the scene, refusing a scene that cannot fit
     * (check_resources()) before anything is allocated: a rectangle before
     * its cells are made, a mesh file once its coarse cells are counted.
     * Returns the bytes one process may use (check_resources()).
     */
    double
    create(TimerOutput &timer);

    /**
     * After create(): how many processes of this run should
     * take part (Solver/Minimum DoFs per process) for the DoFs of the
     * initial mesh: the first M of them, at least one. Where M is less than
     * all, @p note is what the run prints about it.
     */
    unsigned int
    processes_taking_part(std::string &note) const;

    /** "2D, Q1 elements, N cells, M DoFs, K contact nodes". */
    std::string
    summary() const;

    /**
     * Before the first step of an adaptive run: refine towards the load of
     * the first steps, with the initial conditions (@p
     * set_initial_conditions) interpolated anew into @p u and @p w on each
     * mesh (nothing is transferred).
     */
    void
    refine_for_initial_load(const Vector_t              &u,
                            const Vector_t              &w,
                            const std::function<void()> &set_initial_conditions,
                            const std::function<void()> &setup_dofs);

    /**
     * Adapt the mesh for the times [t0, t1] (sampled every k), carrying u,
     * w and the friction forces of @p contact_state over in each cycle.
     * Returns whether the mesh changed.
     */
    bool
    adapt(const double                 t0,
          const double                 t1,
          const double                 k,
          Vector_t                    &u,
          Vector_t                    &w,
          ContactState<dim>           &contact_state,
          const std::function<void()> &setup_dofs);

    /** When the mesh is adapted, and how far ahead it looks. */
    const MeshAdaptation<dim> &
    adaptation() const
    {
      return mesh_adaptation;
    }

  private:
    const RunParameters        &parameters;
    const Scene<dim>           &scene;
    Discretization<dim>        &discretization;
    const ContactBoundary<dim> &contact_boundary;
    MPI_Comm                    comm;
    MeshAdaptation<dim>         mesh_adaptation;

    /**
     * After create(): the DoFs of the uniform mesh after Geometry/Global
     * refinements (exact for a rectangle; dim degree^dim per cell of a mesh
     * file), before any adaptive refinement.
     */
    double
    initial_dofs_estimate() const;

    /**
     * One cycle's flags for [t0, t1] from the fields @p u and @p w (master
     * form); whether any cell is flagged.
     */
    bool
    flag_cells(const double    t0,
               const double    t1,
               const double    k,
               const Vector_t &u,
               const Vector_t &w);

    /** Positions of the nodes that penetrate the foundation (all processes). */
    std::vector<Point<dim>>
    penetrating_nodes(const Vector_t &u) const;
  };
} // namespace DynamicContact

#endif
