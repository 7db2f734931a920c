// The time schemes of Time/Scheme (doc/theory.md section 2), registered by
// name (base/step_scheme.h): each takes a step with the primitives of the
// StepIntegrator and says what the parameters and the summary need to know
// of it.

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/plugins.h>
#include <dynamic_contact/base/step_scheme.h>
#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/time/energy_balance.h>
#include <dynamic_contact/time/step_integrator.h>
#include <dynamic_contact/time/step_record.h>

#include <cmath>

namespace DynamicContact
{
  namespace
  {
    /**
     * The overrides of both dimensions of a scheme @p Derived, from its
     * templates take_step<dim>() and error<dim>().
     */
    template <class Derived>
    class SchemeOfBothDimensions : public StepScheme
    {
    public:
      /**
       * A scheme of @p solves solves per step, an error estimate of order
       * @p error_order (0: none) and a compliance dissipation that is
       * sign-definite or not (@p signed_compliance).
       */
      SchemeOfBothDimensions(const unsigned int solves,
                             const double       error_order,
                             const bool         signed_compliance = true)
        : solves(solves)
        , error_order(error_order)
        , signed_compliance(signed_compliance)
      {}

      unsigned int
      solves_per_step() const override
      {
        return solves;
      }

      double
      local_error_order() const override
      {
        return error_order;
      }

      bool
      compliance_dissipation_is_signed() const override
      {
        return signed_compliance;
      }

      void
      step(const StepArguments<2> &arguments) const override
      {
        self().take_step(arguments);
      }
      void
      step(const StepArguments<3> &arguments) const override
      {
        self().take_step(arguments);
      }

      void
      local_error(const StepIntegrator<2>       &integrator,
                  TrilinosWrappers::MPI::Vector &e,
                  const double                   k) const override
      {
        self().error(integrator, e, k);
      }
      void
      local_error(const StepIntegrator<3>       &integrator,
                  TrilinosWrappers::MPI::Vector &e,
                  const double                   k) const override
      {
        self().error(integrator, e, k);
      }

    private:
      unsigned int solves;
      double       error_order;
      bool         signed_compliance;

      const Derived &
      self() const
      {
        return static_cast<const Derived &>(*this);
      }
    };


    /**
     * The first solve of a step: from (u_{n-1}, w_{n-1}), whose energy is
     * the record's previous energy, with @p scheme to @p t; its statistics
     * and balance terms into @p statistics and @p terms.
     */
    template <int dim>
    void
    solve_from_start(const StepArguments<dim>             &a,
                     const TimeScheme                     &scheme,
                     const double                          t,
                     typename StepSolver<dim>::Statistics &statistics,
                     EnergyBalanceTerms                   &terms)
    {
      StepIntegrator<dim> &i = a.integrator;
      i.solve_substep(scheme,
                      t,
                      i.u_old,
                      i.w_old,
                      a.record.previous_energy,
                      a.accept_unconverged_loop,
                      statistics,
                      terms);
    }


    /**
     * The second solve of a step of two: from (u_bar, w_bar), whose energy
     * is @p start, with @p scheme to @p t; the step's statistics (those of
     * the first solve, @p first_statistics, added) into the record, the
     * solve's balance terms into @p terms.
     */
    template <int dim>
    void
    solve_from_bar(const StepArguments<dim>                   &a,
                   const TimeScheme                           &scheme,
                   const double                                t,
                   const Energy                               &start,
                   const typename StepSolver<dim>::Statistics &first_statistics,
                   EnergyBalanceTerms                         &terms)
    {
      a.integrator.solve_second_substep(scheme,
                                        t,
                                        start.total(),
                                        a.accept_unconverged_loop,
                                        first_statistics,
                                        a.record,
                                        terms);
    }


    /**
     * Time/<Scheme>/Spectral radius at infinity, the parameter of the two
     * second-order schemes with a controlled high-frequency dissipation.
     */
    void
    declare_spectral_radius(ParameterHandler &prm, const std::string &what)
    {
      prm.declare_entry(
        "Spectral radius at infinity",
        "0",
        Patterns::Double(),
        "rho_inf in [0, 1]: the amplification of a mode far beyond the "
        "resolution (omega k -> infinity) in one step; 0 (default): such "
        "modes are removed in a step. " +
          what);
    }

    double
    read_spectral_radius(ParameterHandler &prm, const std::string &scheme)
    {
      const double rho = prm.get_double("Spectral radius at infinity");
      AssertThrow(rho >= 0 && rho <= 1,
                  ExcMessage("Time/" + scheme +
                             "/Spectral radius at infinity must lie in "
                             "[0, 1], got " +
                             str(rho) + "."));
      return rho;
    }


    /**
     * A one-step theta-scheme: its one solve from (u_{n-1}, w_{n-1}) is the
     * step.
     */
    class ThetaStep : public SchemeOfBothDimensions<ThetaStep>
    {
    public:
      ThetaStep(const double theta, const double error_order)
        : SchemeOfBothDimensions(1, error_order)
        , theta(theta)
      {}

      template <int dim>
      void
      take_step(const StepArguments<dim> &a) const
      {
        const TimeScheme     scheme(a.k, theta);
        StepIntegrator<dim> &i = a.integrator;
        solve_from_start(a, scheme, a.t, a.record.statistics, a.record.terms);
        i.measure_last_solve(a.record, scheme, i.u_old, i.w_old, a.t, a.k);
      }

      /**
       * Backward Euler's: e = u_n - (u_{n-1} + k (w_{n-1} + w_n)/2)
       * = (k/2) (w_n - w_{n-1}), the difference to the trapezoidal rule.
       */
      template <int dim>
      void
      error(const StepIntegrator<dim>     &integrator,
            TrilinosWrappers::MPI::Vector &e,
            const double                   k) const
      {
        e = integrator.w;
        e -= integrator.w_old;
        e *= k / 2;
      }

    private:
      double theta;
    };

    /** theta = 1, first order, with an error estimate (power 2 of k). */
    class BackwardEuler : public ThetaStep
    {
    public:
      BackwardEuler()
        : ThetaStep(1, 2)
      {}
    };

    /** theta = 1/2, without an error estimate. */
    class Trapezoidal : public ThetaStep
    {
    public:
      Trapezoidal()
        : ThetaStep(0.5, 0)
      {}
    };


    /**
     * A scheme of two solves per step whose coefficients @p Coefficients
     * (CompositeScheme, SdirkScheme) follow from the spectral radius at
     * infinity of its subsection, and whose local error is the
     * coefficients' local_error() of w_n, the velocity @p Derived::between()
     * and w_{n-1}.
     */
    template <class Derived, class Coefficients>
    class TwoSolveScheme : public SchemeOfBothDimensions<Derived>
    {
    public:
      TwoSolveScheme(const std::string &subsection,
                     const bool         signed_compliance)
        : SchemeOfBothDimensions<Derived>(2, 3, signed_compliance)
        , subsection(subsection)
      {}

      void
      parse_parameters(ParameterHandler &prm)
      {
        coefficients = Coefficients(read_spectral_radius(prm, subsection));
      }

      template <int dim>
      void
      error(const StepIntegrator<dim>     &integrator,
            TrilinosWrappers::MPI::Vector &e,
            const double                   k) const
      {
        coefficients.local_error(
          e, integrator.w, Derived::between(integrator), integrator.w_old, k);
      }

    protected:
      Coefficients coefficients;

    private:
      std::string subsection;
    };


    /**
     * The Bathe composite scheme (doc/theory.md section 2.4;
     * CompositeScheme holds its coefficients): the trapezoidal sub-step to
     * t - k/2, the second sub-step from the extrapolated state, and the
     * step's energy balance.
     */
    class Bathe : public TwoSolveScheme<Bathe, CompositeScheme>
    {
    public:
      Bathe()
        : TwoSolveScheme("Bathe", true)
      {}

      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_spectral_radius(
          prm,
          "1: no high-frequency dissipation (two trapezoidal half steps). "
          "In between, the step is a trapezoidal sub-step over k/2, the "
          "linear extrapolation of u and w to t_{n-1} + s k and a "
          "theta-step of (1 - s) k, s and theta chosen for second order and "
          "this rho_inf (doc/theory.md section 2.4).");
      }

      template <int dim>
      void
      take_step(const StepArguments<dim> &a) const;

      /**
       * The local error e = u_n - (u_{n-1} + k (w_{n-1} + 4 w_{n-1/2} +
       * w_n)/6), the difference to Simpson's rule, needs w_bar
       * (CompositeScheme::local_error(); at rho_inf = 0,
       * w_{n-1/2} = (3 w_bar + w_old)/4).
       */
      template <int dim>
      static const Vector_t &
      between(const StepIntegrator<dim> &integrator)
      {
        return integrator.w_bar;
      }
    };


    template <int dim>
    void
    Bathe::take_step(const StepArguments<dim> &a) const
    {
      StepIntegrator<dim>   &i = a.integrator;
      const double           t = a.t, k = a.k;
      const auto            &ops       = i.operators();
      const CompositeScheme &composite = coefficients;
      // Sub-step 1: the trapezoidal rule from t - k to t - k/2.
      const TimeScheme                     first = composite.first_substep(k);
      typename StepSolver<dim>::Statistics first_statistics;
      EnergyBalanceTerms                   first_terms;
      solve_from_start(a, first, t - k / 2, first_statistics, first_terms);
      // Sub-step 2: a theta-step from the extrapolated state x_bar =
      // (1 + a) x_{n-1/2} - a x_{n-1} to t (at rho_inf = 0 the three-point
      // backward difference: backward Euler over k/3 from
      // (4 x_{n-1/2} - x_{n-1})/3).
      composite.extrapolate(i.u_bar, i.u, i.u_old);
      composite.extrapolate(i.w_bar, i.w, i.w_old);
      const Energy     bar_energy = ops.energy_balance.energy(i.u_bar, i.w_bar);
      const TimeScheme last       = composite.second_substep(k);
      EnergyBalanceTerms second_terms;
      solve_from_bar(a, last, t, bar_energy, first_statistics, second_terms);
      // (f, u_bar - u_{n-1/2}) = a/(1 + a) (f, u_bar - u_{n-1}) with the
      // second sub-step's load f (f_n at rho_inf = 0).
      i.scratch = i.u_bar;
      i.scratch -= i.u_old;
      const double extrapolation_work =
        composite.extrapolation_share() * (i.load * i.scratch);
      a.record.terms = bathe_terms(first_terms,
                                   bar_energy,
                                   second_terms,
                                   extrapolation_work,
                                   a.record.previous_energy);
      i.measure_last_solve(a.record, last, i.u_bar, i.w_bar, t, k);
    }


    /**
     * The two-stage SDIRK scheme (doc/theory.md section 2.6; SdirkScheme
     * holds its coefficients): the two stages, the balances of the second,
     * the contact force sums extrapolated to t, (u, w) = y_n and the step's
     * energy balance.
     */
    class Sdirk : public TwoSolveScheme<Sdirk, SdirkScheme>
    {
    public:
      /**
       * The compliance term of the stages' dissipation is not
       * sign-definite (doc/theory.md section 6).
       */
      Sdirk()
        : TwoSolveScheme("Sdirk", false)
      {}

      /**
       * The local error, u_n - u_{n-1} = (k/2)(W1 + W2) against the
       * quadrature of the velocities exact for quadratics, needs W1
       * (SdirkScheme::local_error()), with w = W2 before the stages are
       * combined (measure_last_solve()).
       */
      template <int dim>
      static const Vector_t &
      between(const StepIntegrator<dim> &integrator)
      {
        return integrator.w_stage;
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_spectral_radius(
          prm,
          "It sets the stages' gamma (doc/theory.md section 2.6): "
          "1 - 1/sqrt(2) at 0, 1/4 at 1 (two implicit midpoint steps of "
          "k/2, no high-frequency dissipation).");
      }

      template <int dim>
      void
      take_step(const StepArguments<dim> &a) const;

    private:
      /**
       * |d|_E^2 of the stage increments' difference
       * d = (Y1 - y_{n-1}) - (Y2 - y_hat), while (u, w) = Y2.
       */
      template <int dim>
      static double
      stage_difference(StepIntegrator<dim> &i)
      {
        const auto  &ops     = i.operators();
        const double density = ops.material.density();
        i.scratch            = i.u_stage;
        i.scratch -= i.u_old;
        i.scratch -= i.u;
        i.scratch += i.u_bar;
        double d2 = ops.bulk.elastic_product(i.scratch, i.scratch);
        i.scratch = i.w_stage;
        i.scratch -= i.w_old;
        i.scratch -= i.w;
        i.scratch += i.w_bar;
        d2 += density * ops.bulk.mass_product(i.scratch, i.scratch);
        return d2;
      }
    };


    template <int dim>
    void
    Sdirk::take_step(const StepArguments<dim> &a) const
    {
      StepIntegrator<dim> &i      = a.integrator;
      StepRecord<dim>     &record = a.record;
      const double         t = a.t, k = a.k;
      const auto          &ops   = i.operators();
      const SdirkScheme   &sdirk = coefficients;
      // Stage 1: backward Euler over gamma k from y_{n-1}.
      const TimeScheme                     stage = sdirk.stage(k);
      const double                         t0    = t - k;
      typename StepSolver<dim>::Statistics first_statistics;
      EnergyBalanceTerms                   first_terms;
      const double                         old_foundation =
        ops.energy_balance.foundation_energy(i.u_old);
      solve_from_start(a,
                       stage,
                       t0 + sdirk.first_stage_time() * k,
                       first_statistics,
                       first_terms);
      i.u_stage = i.u;
      i.w_stage = i.w;
      const auto first_forces =
        ops.contact_state.force_sums(ops.contact_boundary, ops.comm);

      // Stage 2: backward Euler over gamma k from y_hat = y_{n-1} +
      // alpha (Y1 - y_{n-1}), to t_{n-1} + (1 - gamma) k.
      sdirk.second_stage_start(i.u_bar, i.u_stage, i.u_old);
      sdirk.second_stage_start(i.w_bar, i.w_stage, i.w_old);
      const Energy hat_energy = ops.energy_balance.energy(i.u_bar, i.w_bar);
      EnergyBalanceTerms second_terms;
      const double       t2 = t0 + sdirk.second_stage_time() * k;
      solve_from_bar(a, stage, t2, hat_energy, first_statistics, second_terms);

      // The error estimate (with w = W2) and the force balance of stage 2's
      // equation; the contact force sums extrapolated from the stages to
      // t_n.
      i.measure_last_solve(record, stage, i.u_bar, i.w_bar, t2, k);
      record.normal_force =
        sdirk.value_at_end(first_forces.first, record.normal_force);
      record.tangential_force =
        sdirk.value_at_end(first_forces.second, record.tangential_force);

      // The numerical dissipation from the stage increments, before u, w
      // become y_n.
      const double d2 = stage_difference(i);
      sdirk.combine(i.u, i.u_stage, i.u_bar, i.u_old);
      sdirk.combine(i.w, i.w_stage, i.w_bar, i.w_old);
      record.terms = sdirk_terms(first_terms,
                                 second_terms,
                                 record.previous_energy,
                                 old_foundation,
                                 hat_energy,
                                 ops.energy_balance.energy(i.u, i.w),
                                 sdirk.numerical_dissipation_factor() * d2,
                                 sdirk.stage_weight());
    }
  } // namespace


  void
  declare_step_schemes(ParameterHandler &prm)
  {
    PluginRegistry<StepScheme>::instance().declare_parameters(
      prm,
      "Scheme",
      "backward Euler",
      "The time scheme (doc/theory.md section 2), with the parameters in the "
      "subsection of its name where it has any:");
  }


  DYNAMIC_CONTACT_REGISTER(
    StepScheme,
    BackwardEuler,
    "backward Euler",
    "the paper's scheme (eqs. (52)-(54)), first order; with an error "
    "estimate for Time/Adaptive.");
  DYNAMIC_CONTACT_REGISTER(
    StepScheme,
    Trapezoidal,
    "trapezoidal",
    "second order, u_n = u_{n-1} + k (w_n + w_{n-1})/2, the equation of "
    "motion at the midpoint, the compliance force the discrete gradient "
    "(Pi(u_n) - Pi(u_{n-1}))/(u_n - u_{n-1}), damping and friction on "
    "(w_n + w_{n-1})/2: energy-consistent (no numerical dissipation; the "
    "balance of doc/theory.md section 6 still holds exactly, with only the "
    "physical dissipation); no error estimate (not with Time/Adaptive).");
  DYNAMIC_CONTACT_REGISTER(
    StepScheme,
    Bathe,
    "bathe",
    "the Bathe composite scheme, second order with strong high-frequency "
    "dissipation (spectral radius 0 at infinity, like backward Euler, but "
    "little dissipation of the resolved modes): a trapezoidal sub-step over "
    "k/2, then the three-point backward difference, which is a "
    "backward-Euler step of k/3 from the extrapolated state "
    "(4 x_{n-1/2} - x_{n-1})/3; two solves per step (doc/theory.md section "
    "2); its high-frequency dissipation is set by Time/Bathe/Spectral "
    "radius at infinity.");
  DYNAMIC_CONTACT_REGISTER(
    StepScheme,
    Sdirk,
    "sdirk",
    "a two-stage diagonally implicit Runge-Kutta scheme, second order, with "
    "the same control of the high-frequency dissipation (Time/Sdirk/Spectral "
    "radius at infinity) and a numerical dissipation that is >= 0 at every "
    "step whatever the load (algebraically stable): two backward-Euler "
    "stages of gamma k (gamma = 1 - 1/sqrt(2) at rho_inf = 0), the second "
    "from an extrapolated state, and the end state a combination of the "
    "stages; two solves per step, one matrix (doc/theory.md section 2.6).");
} // namespace DynamicContact
