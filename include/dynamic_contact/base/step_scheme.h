#ifndef dynamic_contact_step_scheme_h
#define dynamic_contact_step_scheme_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/base/plugins.h>

#include <string>

namespace DynamicContact
{
  using namespace dealii;

  // The time family's step (time/step_integrator.h, time/step_record.h):
  // a scheme takes its steps with the integrator's primitives.
  template <int dim>
  class StepIntegrator;
  template <int dim>
  struct StepRecord;

  /** What a step of a scheme gets (StepScheme::step()). */
  template <int dim>
  struct StepArguments
  {
    StepIntegrator<dim> &integrator;
    StepRecord<dim>     &record;
    const double         t;
    const double         k;
    const bool           accept_unconverged_loop;
  };

  /**
   * A time scheme of Time/Scheme (doc/theory.md section 2), chosen by name
   * like the laws (doc/extending.md): each implementation registers itself
   * with DYNAMIC_CONTACT_REGISTER(StepScheme, Class, "name", "description")
   * and declares and parses the entries of its own subsection of Time
   * (Time/Bathe, Time/Sdirk; a scheme without parameters declares none).
   *
   * The interface lives below the families that ask about a scheme (the
   * parameters check a scene against its properties, the run's summary
   * words its energy balance after it); the implementations are in
   * source/time/step_schemes.cc, where a step is a sequence of the
   * StepIntegrator's solves and measures. A scheme is a value: it holds its
   * coefficients, not the state of a run, and a step gets everything else
   * as arguments.
   */
  class StepScheme
  {
  public:
    virtual ~StepScheme() = default;

    /**
     * Solves per step: 1 for a theta-step (the solve is the step), 2 for a
     * scheme of two sub-steps or stages.
     */
    virtual unsigned int
    solves_per_step() const = 0;

    /**
     * The power of k in the local error estimate of a step (Time/Adaptive,
     * doc/theory.md section 2.5); 0 for a scheme without an estimate.
     */
    virtual double
    local_error_order() const = 0;

    /**
     * Whether the compliance term of the step's numerical dissipation is
     * >= 0 by construction (doc/theory.md section 6); the run's summary
     * leaves it out of its check where it is not.
     */
    virtual bool
    compliance_dissipation_is_signed() const
    {
      return true;
    }

    /**
     * One step of length k to t with the primitives of the integrator
     * (StepIntegrator::step() describes the contract), all in @p arguments.
     */
    virtual void
    step(const StepArguments<2> &arguments) const = 0;
    virtual void
    step(const StepArguments<3> &arguments) const = 0;

    /**
     * @p e = the displacement's local error of the step of length @p k
     * that @p integrator has just taken (called only where
     * local_error_order() > 0; @p e has the fields' layout).
     */
    virtual void
    local_error(const StepIntegrator<2>       &integrator,
                TrilinosWrappers::MPI::Vector &e,
                const double                   k) const = 0;
    virtual void
    local_error(const StepIntegrator<3>       &integrator,
                TrilinosWrappers::MPI::Vector &e,
                const double                   k) const = 0;
  };


  /**
   * Declare Time/Scheme (default 'backward Euler') and the subsection of
   * every registered scheme, in the current subsection (Time). Defined
   * with the schemes (source/time/step_schemes.cc), which it links into
   * every program that reads parameters (the library is static).
   */
  void
  declare_step_schemes(ParameterHandler &prm);
} // namespace DynamicContact

#endif
