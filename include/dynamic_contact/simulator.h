#ifndef dynamic_contact_simulator_h
#define dynamic_contact_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk_operator.h>
#include <dynamic_contact/contact_boundary.h>
#include <dynamic_contact/discretization.h>
#include <dynamic_contact/energy_balance.h>
#include <dynamic_contact/force_balance.h>
#include <dynamic_contact/foundation.h>
#include <dynamic_contact/friction_law.h>
#include <dynamic_contact/material.h>
#include <dynamic_contact/output.h>
#include <dynamic_contact/parameters.h>
#include <dynamic_contact/scene.h>
#include <dynamic_contact/step_solver.h>

#include <memory>
#include <vector>

namespace DynamicContact
{
  /**
   * Owns the mesh, the DoFs and the fields, and runs the time loop: for each
   * step, form K0 for k, assemble the load, solve the step (convexification
   * loop around the active-set Newton), check the energy balance, write the
   * outputs.
   */
  template <int dim>
  class Simulator
  {
  public:
    Simulator(const RunParameters &parameters,
              ParameterHandler &   prm,
              const MPI_Comm       comm);
    ~Simulator();

    /** Run the whole simulation. */
    void
    run();

    /**
     * After a failure of run(): mark the output as failed and silence the
     * timer summary (the processes may no longer be in step).
     */
    void
    abandon(const std::string &reason);

    /** The rows written to time_series.csv so far (for tests). */
    const std::vector<TimeSeriesRow> &
    time_series() const
    {
      return rows;
    }

    /** The contact boundary and node states of the last step (for tests). */
    const ContactBoundary<dim> &
    contact() const
    {
      return contact_boundary;
    }
    const std::vector<ContactNodeState<dim>> &
    node_states() const
    {
      return step_solver.node_states();
    }

    /**
     * The displacement at a point of the body (collective; for tests and
     * probes). Throws if no process owns a cell containing the point.
     */
    Tensor<1, dim>
    point_displacement(const Point<dim> &point) const;

    /** The displacement (master form) and the discretization (for tests). */
    const Vector_t &
    displacement() const
    {
      return u;
    }
    const Discretization<dim> &
    get_discretization() const
    {
      return discretization;
    }

  private:
    const RunParameters parameters;
    MPI_Comm            comm;
    ConditionalOStream  pcout;
    ConditionalOStream  details;

    // The input is parsed (and can fail) before anything else is built.
    Scene<dim>                   scene;
    KelvinVoigtMaterial<dim>     material;
    Foundation                   foundation;
    std::unique_ptr<FrictionLaw> friction_law;

    TimerOutput timer;

    Discretization<dim>  discretization;
    ContactBoundary<dim> contact_boundary;
    BulkOperator<dim>    bulk;
    StepSolver<dim>      step_solver;
    EnergyBalance<dim>   energy_balance;
    ForceBalanceEvaluator<dim> force_balance;

    // Fields in master form (constrained entries zero).
    Vector_t u, w, u_old, w_old, load, rhs;

    std::unique_ptr<TimeSeriesWriter> time_series_writer;
    std::unique_ptr<VtuWriter<dim>>   vtu_writer;
    std::vector<TimeSeriesRow>        rows;

    void
    setup_system();
    void
    set_initial_conditions();
    void
    prepare_output_directory();
    void
    print_header() const;
    /** One step from t - k to t; returns the time series row. */
    TimeSeriesRow
    do_time_step(const unsigned int step, const double t, const double k);
    /** Write the contact CSV and/or the VTU fields of the current step. */
    void
    output_results(const unsigned int step,
                   const double       t,
                   const bool         contact_csv,
                   const bool         vtu);
    void
    write_status(const std::string &status) const;
  };


  /**
   * Read the parameters and run the simulation in the dimension they name.
   * Errors propagate as exceptions (main turns them into a message and a
   * non-zero exit).
   */
  void
  run_simulation(const std::string &             parameter_file,
                 const std::vector<std::string> &overrides,
                 const MPI_Comm                  comm);
} // namespace DynamicContact

#endif
