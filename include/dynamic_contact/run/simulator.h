#ifndef dynamic_contact_simulator_h
#define dynamic_contact_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/output/output.h>
#include <dynamic_contact/output/output_directory.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/run/discrete_operators.h>
#include <dynamic_contact/run/field_io.h>
#include <dynamic_contact/run/mesh_life_cycle.h>
#include <dynamic_contact/run/model_checks.h>
#include <dynamic_contact/time/step_integrator.h>
#include <dynamic_contact/time/step_record.h>

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * The discrete problem and its algorithm, step-42 style: owns the scene
   * and its laws, the Discretization (mesh, DoFs, constraints), Gamma_3
   * and its solution (ContactBoundary, ContactState), the operators and the
   * solver, the MeshLifeCycle that creates and adapts the mesh, and the
   * StepIntegrator that holds the fields u and w and does the scheme's
   * solves. It calls them in functions named after the steps: set up the
   * mesh and the initial state, adapt the mesh, do a time step
   * (do_time_step: the integrator's step, the errors of a manufactured
   * solution, the row's columns), write the fields.
   *
   * When and how often these happen, what is kept after a failure, and
   * where the results go is the TimeLoop's business (time_loop.h): it owns
   * the run state, and this class never looks at the clock, the schedule or
   * the output directory's status.
   */
  template <int dim>
  class Simulator
  {
  public:
    Simulator(const RunParameters      &parameters,
              ParameterHandler         &prm,
              const MPI_Comm            comm,
              TimerOutput              &timer,
              const ConditionalOStream &details);

    /** @name Set-up */
    /** @{ */

    /** The coarse mesh of the scene (MeshLifeCycle::create()). */
    void
    create_mesh();

    /**
     * A new run: refine the coarse mesh (Geometry/Global refinements, then
     * for the initial load if adaptive), check the input, set up DoFs and
     * operators, interpolate the initial state (throws if not finite).
     */
    void
    set_up_initial_state();

    /**
     * Before anything is written: the friction law and the functions of
     * the scene sampled on the mesh (model_checks.h), the initial
     * conditions unless @p resume.
     */
    void
    check_input(const bool resume);

    /**
     * A resumed run: the mesh and the fields (u, w, the friction forces)
     * of the checkpoint @p path, saved at time @p t; DoFs and operators set
     * up for them.
     */
    void
    load_checkpoint(const std::string &path, const double t);

    /** The time series row of step 0: the initial state's energy. */
    StepRecord<dim>
    initial_record();
    /** @} */

    /** @name The steps of the scheme */
    /** @{ */

    /**
     * Adapt the mesh for the times [t0, t1], transferring u, w and the
     * friction forces; returns the change of the energy E the transfer made.
     */
    double
    adapt_mesh(const double t0, const double t1, const double k);

    /**
     * One step from t - k to t (Time/Scheme); returns the time series row
     * (which records the energy change of a mesh transfer just before the
     * step and the cut-backs and rejected tries of the loop). With
     * @p accept_unconverged_loop (the smallest time step) a convexification
     * loop that reaches its cap is kept rather than failing. Throws
     * StepFailure (a cut-back may help) or NonFiniteValue (it may not).
     */
    StepRecord<dim>
    do_time_step(const unsigned int step,
                 const double       t,
                 const double       k,
                 const double       remesh_energy_change,
                 const unsigned int cutbacks,
                 const unsigned int rejected,
                 const bool         accept_unconverged_loop);

    /**
     * The final Newton residual of the last step solved (the larger of
     * the two sub-steps of a composite scheme).
     */
    double
    newton_residual() const
    {
      return integrator.newton_residual();
    }

    /**
     * The state a step starts from, to go back to after a failed or
     * rejected try: the fields, the Gamma_3 solution and their energy.
     */
    struct RestorePoint
    {
      Vector_t              u, w;
      ContactState<dim>     contact;
      std::optional<double> energy;
    };
    RestorePoint
    restore_point() const
    {
      return {u, w, contact_state, integrator.known_energy};
    }
    void
    restore(const RestorePoint &point);
    /** @} */

    /** @name The fields and the model */
    /** @{ */
    /**
     * The fields as they are written and read: contact CSV, VTU,
     * checkpoints, the displacement at a point (FieldIO).
     */
    FieldIO<dim> &
    fields()
    {
      return field_io;
    }
    const FieldIO<dim> &
    fields() const
    {
      return field_io;
    }

    /** The material and friction lines of the header (model_checks.h). */
    void
    print_model(const ConditionalOStream &out) const
    {
      DynamicContact::print_model(out,
                                  parameters,
                                  material,
                                  operators.step_solver.has_friction());
    }
    /** @} */

    /** @name What the time loop and the tests read */
    /** @{ */
    /** The solver of the steps, its plan for the current mesh. */
    const StepSolver<dim> &
    solver() const
    {
      return operators.step_solver;
    }

    /** What the run holds, by part (DiscreteOperators::memory_table()). */
    std::string
    memory_table() const
    {
      return operators.memory_table(integrator.memory_consumption());
    }
    /** The mesh: created, adapted, described (MeshLifeCycle). */
    const MeshLifeCycle<dim> &
    mesh() const
    {
      return mesh_cycle;
    }
    const ContactBoundary<dim> &
    contact() const
    {
      return contact_boundary;
    }
    /** The node states of the last step, aligned with contact().nodes(). */
    const std::vector<ContactNodeState<dim>> &
    node_states() const
    {
      return contact_state.nodes;
    }
    const Discretization<dim> &
    get_discretization() const
    {
      return discretization;
    }
    /** @} */

  private:
    const RunParameters &parameters;
    MPI_Comm             comm;
    TimerOutput         &timer;

    // The input is parsed (and can fail) before anything else is built.
    Scene<dim>               scene;
    KelvinVoigtMaterial<dim> material;

    Discretization<dim>    discretization;
    ContactBoundary<dim>   contact_boundary;
    ContactState<dim>      contact_state;
    DiscreteOperators<dim> operators;
    MeshLifeCycle<dim>     mesh_cycle;

    /**
     * The time step: the scheme's solves and measures, and the fields (the
     * state u, w and the vectors of a step in progress).
     */
    StepIntegrator<dim> integrator;
    /** The state, in master form (constrained entries zero): integrator's. */
    Vector_t &u, &w;
    /** The fields written and read. */
    FieldIO<dim> field_io;

    /**
     * The bytes one process may use (Solver/Memory per process, or what
     * the hosts had available at the start: check_resources()), for
     * Preconditioner = auto.
     */
    double memory_per_process = std::numeric_limits<double>::infinity();

    /** DoFs, constraints, Gamma_3 and vectors for the current mesh. */
    void
    setup_dofs();
    /** The operators for the current mesh (DiscreteOperators::setup()). */
    void
    setup_operators(const double start_time);

    /**
     * What every row records of the mesh and the scene at @p t: the DoFs
     * and cells, the errors of a manufactured solution, which optional
     * columns time_series.csv has (the uniqueness measures with a slip-rate
     * dependent law and Friction/Uniqueness monitor not never; the solution
     * count with Friction/Count solutions and such a law).
     */
    void
    record_state(StepRecord<dim> &record, const double t);
  };
} // namespace DynamicContact

#endif
