#ifndef dynamic_contact_step_integrator_h
#define dynamic_contact_step_integrator_h

#include <deal.II/base/timer.h>

#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/time/energy_balance.h>
#include <dynamic_contact/time/force_balance.h>
#include <dynamic_contact/time/step_record.h>
#include <dynamic_contact/time/step_solver.h>

#include <array>
#include <optional>
#include <stdexcept>

namespace DynamicContact
{
  /**
   * A value that is not finite where a step needs it (collective): not a
   * failure of the solver (no cut-back); the run stops with the last good
   * state.
   */
  class NonFiniteValue : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };


  /**
   * What a step works with, owned by the Simulator (it must outlive the
   * StepIntegrator): the scene and the material, the discretization and
   * Gamma_3 of the current mesh, the Gamma_3 solution, the operators, the
   * step's contact solver and the balances.
   */
  template <int dim>
  struct StepOperators
  {
    const Parameters::Time           &time;
    MPI_Comm                          comm;
    TimerOutput                      &timer;
    const Scene<dim>                 &scene;
    const KelvinVoigtMaterial<dim>   &material;
    const Discretization<dim>        &discretization;
    const ContactBoundary<dim>       &contact_boundary;
    const ContactState<dim>          &contact_state;
    BulkOperator<dim>                &bulk;
    StepSolver<dim>                  &step_solver;
    const EnergyBalance<dim>         &energy_balance;
    const ForceBalanceEvaluator<dim> &force_balance;
  };


  /**
   * One time step of Time/Scheme (doc/theory.md section 2) and the fields
   * it works on: the state (u, w) and the vectors of a step in progress.
   * The scheme (a StepScheme plugin, source/time/step_schemes.cc) takes
   * the step with the primitives below: a step of a one-step theta-scheme
   * (backward Euler, trapezoidal) is one solve (solve_substep()); the
   * Bathe scheme's and the SDIRK scheme's are two, from a start computed
   * between them. Each assembles its right-hand side, solves for w with the
   * step's contact solver, sets u, and books the energy balance; after the
   * last solve the step measures the contact force sums, the force balance
   * and (Time/Adaptive) its local error.
   *
   * The Simulator owns this object and calls step(); what happens around a
   * step (the mesh, the errors of a manufactured solution, the columns of
   * the time series) is the Simulator's.
   */
  template <int dim>
  class StepIntegrator
  {
  public:
    explicit StepIntegrator(const StepOperators<dim> &operators);

    /** The fields for the DoFs of the current mesh (zero). */
    void
    reinit();

    /**
     * One step from (u, w) at t - k to t, whose energy is
     * @p record.previous_energy: (u, w) become the step's solution, the
     * solver's statistics, the balances and the measures go into
     * @p record. Throws StepFailure (a cut-back may help) or
     * NonFiniteValue (it may not); (u, w) are then undefined (the
     * Simulator restores them).
     */
    void
    step(StepRecord<dim> &record,
         const double     t,
         const double     k,
         const bool       accept_unconverged_loop);

    /**
     * Where the scene has an exact (manufactured) solution: its errors at
     * @p t against (u, w) as they stand, into @p record.
     */
    void
    record_errors(StepRecord<dim> &record, const double t) const;

    /**
     * The final Newton residual of the last step solved (the larger of
     * the two solves of a two-solve scheme).
     */
    double
    newton_residual() const
    {
      return last_newton_residual;
    }

    /** Bytes of the fields and work vectors on this process. */
    double
    memory_consumption() const;

    /** The state: displacement and velocity, in master form. */
    Vector_t u, w;

    /**
     * The total energy E of (u, w) as they stand, computed once: E_{n-1}
     * of a step is E_n of the step before.
     */
    double
    energy();
    /** E of (u, w) where it is known; reinit() forgets it. */
    std::optional<double> known_energy;

    // For the schemes (step_schemes.cc): the fields of a step in progress
    // and the primitives a step is made of.

    // u_old, w_old: the state at the start of the step; u_bar, w_bar: the
    // start of a second sub-step or stage; u_stage, w_stage: a first stage
    // kept while the second is solved; load: f_theta of the last solve;
    // scratch: a work vector.
    Vector_t u_old, w_old, u_bar, w_bar, u_stage, w_stage, load, scratch;

    /** What a step works with. */
    const StepOperators<dim> &
    operators() const
    {
      return ops;
    }

    /**
     * One (sub-)step of the theta-scheme @p scheme that ends at @p t, from
     * (@p u_start, @p w_start) whose energy is @p start_energy: assemble the
     * right-hand side, solve for w, set u; the solver's statistics and the
     * energy balance terms of the (sub-)step.
     */
    void
    solve_substep(const TimeScheme                     &scheme,
                  const double                          t,
                  const Vector_t                       &u_start,
                  const Vector_t                       &w_start,
                  const double                          start_energy,
                  const bool                            accept_unconverged_loop,
                  typename StepSolver<dim>::Statistics &statistics,
                  EnergyBalanceTerms                   &terms);
    /**
     * The second (sub-)step of a two-solve scheme (bathe, sdirk): from
     * (u_bar, w_bar), whose energy is @p start_energy, to @p t; the step's
     * statistics (the first (sub-)step's @p first_statistics added) into
     * @p record, the (sub-)step's balance terms into @p terms.
     */
    void
    solve_second_substep(
      const TimeScheme                           &scheme,
      const double                                t,
      const double                                start_energy,
      const bool                                  accept_unconverged_loop,
      const typename StepSolver<dim>::Statistics &first_statistics,
      StepRecord<dim>                            &record,
      EnergyBalanceTerms                         &terms);
    /**
     * After the last solve of a step, while (u, w) are its solution, into
     * @p record: the local error estimate (Time/Adaptive), the contact force
     * sums and the force balance of that (sub-)step @p last from
     * (@p u_start, @p w_start) to @p t_last.
     */
    void
    measure_last_solve(StepRecord<dim>  &record,
                       const TimeScheme &last,
                       const Vector_t   &u_start,
                       const Vector_t   &w_start,
                       const double      t_last,
                       const double      k);

  private:
    const StepOperators<dim> ops;

    // rhs: the right-hand side of the solve in progress.
    Vector_t rhs;
    /** Pointers to all the fields (of a const integrator: const pointers). */
    template <typename Self>
    static auto
    fields(Self &self)
    {
      return std::array<decltype(&self.u), 11>{{&self.u,
                                                &self.w,
                                                &self.u_old,
                                                &self.w_old,
                                                &self.u_bar,
                                                &self.w_bar,
                                                &self.u_stage,
                                                &self.w_stage,
                                                &self.load,
                                                &self.rhs,
                                                &self.scratch}};
    }

    double last_newton_residual = 0;

    /**
     * b = (rho/k) M w_start - (1 - theta) A w_start
     *     - B (u_start + theta (1 - theta) k w_start) + f_theta
     * of the (sub-)step @p scheme ending at @p t, into rhs (and f_theta
     * into load).
     */
    void
    assemble_rhs(const TimeScheme &scheme,
                 const double      t,
                 const Vector_t   &u_start,
                 const Vector_t   &w_start);
    /**
     * The displacement's local error estimate of the step just solved,
     * relative to the energy of the state (doc/theory.md 2.5).
     */
    double
    time_error_estimate(const double k) const;
  };
} // namespace DynamicContact

#endif
