#ifndef dynamic_contact_solution_uniqueness_h
#define dynamic_contact_solution_uniqueness_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/time/step_statistics.h>

#include <functional>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * Whether the solution of a step with a slip-rate dependent friction law
   * is unique, as the StepSolver records it into StepStatistics: the
   * uniqueness measures of the solved step (Friction/Uniqueness monitor,
   * doc/theory.md section 5.2) and the count of the solutions that the
   * step's convexification loop reaches from several starts
   * (Friction/Count solutions, section 5.3; solution_count.cc).
   */
  template <int dim>
  class SolutionUniqueness
  {
  public:
    /**
     * A convexification loop of the step from the initial guess @p w (its
     * solution on return) to the coefficient residual
     * @p coefficient_tolerance in at most @p max_passes passes, the first
     * with the coupled linearization if @p coupled; throws StepFailure
     * where it reaches no solution.
     */
    using Loop = std::function<void(Vector_t          &w,
                                    StepStatistics    &statistics,
                                    const double       coefficient_tolerance,
                                    const unsigned int max_passes,
                                    const bool         coupled)>;

    /**
     * @p friction_parameters and @p lipschitz_constant: StepSolver's (the
     * parameters must outlive this), the L of the bound.
     */
    SolutionUniqueness(const Discretization<dim>  &discretization,
                       const ContactBoundary<dim> &contact_boundary,
                       ContactState<dim>          &contact_state,
                       const Foundation           &foundation,
                       const FrictionLaw          *friction_law,
                       const Parameters::Friction &friction_parameters,
                       const double                lipschitz_constant,
                       TimerOutput                &timer,
                       const ConditionalOStream   &details)
      : discretization(discretization)
      , contact_boundary(contact_boundary)
      , contact_state(contact_state)
      , foundation(foundation)
      , friction_law(friction_law)
      , friction_parameters(friction_parameters)
      , lipschitz_constant(lipschitz_constant)
      , timer(timer)
      , details(details)
    {}

    /**
     * The uniqueness measures of the solved step of @p scheme (solved by
     * @p solver) into @p statistics (StepStatistics::uniqueness_bound,
     * uniqueness_certificate, contraction_factor; collective).
     */
    void
    measure(const TimeScheme   &scheme,
            ContactSolver<dim> &solver,
            StepStatistics     &statistics);

    /**
     * Friction/Count solutions (doc/theory.md section 5.3): the step of
     * @p scheme solved again by @p loop from several starts to a
     * coefficient residual of 1/100 of Friction/Coefficient tolerance, and
     * the distinct solutions counted into @p statistics. @p start_state is
     * the contact state at the step's start; the contact state and the
     * step's solution are left as they were (collective).
     */
    void
    count_solutions(const Loop              &loop,
                    const TimeScheme        &scheme,
                    const Vector_t          &w_old,
                    const ContactState<dim> &start_state,
                    StepStatistics          &statistics);

  private:
    const Discretization<dim>  &discretization;
    const ContactBoundary<dim> &contact_boundary;
    ContactState<dim>          &contact_state;
    const Foundation           &foundation;
    const FrictionLaw          *friction_law;
    const Parameters::Friction &friction_parameters;
    const double                lipschitz_constant;
    TimerOutput                &timer;
    const ConditionalOStream   &details;
  };
} // namespace DynamicContact

#endif
