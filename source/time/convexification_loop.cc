#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/time/step_solver.h>

#include "loop_measures.h"

#include <cmath>
#include <limits>

namespace DynamicContact
{
  /**
   * The convexification loop of one step (doc/theory.md section 4): the
   * friction coefficients frozen from the previous iterate, starting from
   * w^(0) = w_{n-1}, each pass a Newton solve (ContactSolver), until the
   * stopping rule (85) holds.
   *
   * The slip-rate law inside Newton's linearization (Friction/
   * Linearization = coupled, doc/theory.md section 5.1): the first pass
   * takes mu(|w_tau|) of the iterate and its derivative, and lands on a
   * fixed point of the loop, which the frozen pass after it confirms (the
   * loop's own stopping rule decides). If it does not converge, the step
   * goes back to its start, for the frozen loop alone (a fallback,
   * counted).
   *
   * In the loop, a pass may be provisional (the condensed solver's
   * boundary iteration: the velocities at the nodes of Gamma_3 only, no
   * solve with K0): enough to decide whether the loop goes on, while the
   * loop is far from its tolerances. It is measured on Gamma_3 (xi and
   * the coefficients; the V norm needs the whole w), and only as
   * accurately as the boundary iteration's stopping point, so a pass that
   * would end the loop, reaches the cap, or whose coefficient residual no
   * longer falls (the provisional accuracy reached) is finished
   * (finalize()), the whole velocity of the pass before it computed (one
   * solve) if that one was provisional too, and the pass measured again
   * by the whole rule; the passes after it are exact. The assembled
   * solver's provisional pass writes the whole w but stops its Newton
   * iteration at that accuracy, and also within rule (85)'s tolerance of
   * the nodal velocities (the pass after it is compared with it); the
   * same rules finish it (Newton on to its tolerance, finish_inexact()).
   */
  template <int dim>
  class StepSolver<dim>::ConvexificationLoop
  {
  public:
    ConvexificationLoop(StepSolver<dim>                   &solver,
                        ContactSolver<dim>                &contact_solver,
                        const TimeScheme                  &scheme,
                        const Vector_t                    &rhs,
                        const Vector_t                    &u_old,
                        const std::vector<Tensor<1, dim>> &u_old_nodes,
                        const std::vector<Tensor<1, dim>> &w_old_nodes,
                        Vector_t                          &w,
                        Statistics                        &statistics,
                        const LoopOptions                 &options)
      : solver(solver)
      , contact_solver(contact_solver)
      , scheme(scheme)
      , rhs(rhs)
      , u_old(u_old)
      , u_old_nodes(u_old_nodes)
      , w_old_nodes(w_old_nodes)
      , w(w)
      , statistics(statistics)
      , k(scheme.time_step())
      , mu(solver.contact_state.mu)
      , lambda(solver.contact_state.lambda)
      , loop(runs_convexification_loop(solver.friction_law))
      , measures(solver.discretization,
                 solver.contact_boundary,
                 solver.foundation,
                 solver.friction_law,
                 solver.friction_parameters.slip_length,
                 solver.contact_state.coefficient_state,
                 solver.bulk,
                 scheme,
                 u_old_nodes,
                 w_old_nodes,
                 solver.friction_parameters.convexification_tolerance,
                 options.coefficient_tolerance,
                 solver.discretization.comm)
      , max_passes(loop ? options.max_passes : 1)
      , coupling(loop && options.coupled)
    {
      if (coupling)
        {
          w_start      = w;
          lambda_start = lambda;
        }
      start();
    }

    /** The passes, until the loop converges or reaches its cap. */
    void
    run(const bool accept_unconverged_loop);

    /** The loop updates the friction coefficients. */
    bool
    active() const
    {
      return loop;
    }

  private:
    using Measures = typename LoopMeasures<dim>::Measures;

    StepSolver<dim>                   &solver;
    ContactSolver<dim>                &contact_solver;
    const TimeScheme                  &scheme;
    const Vector_t                    &rhs, &u_old;
    const std::vector<Tensor<1, dim>> &u_old_nodes, &w_old_nodes;
    Vector_t                          &w;
    Statistics                        &statistics;
    const double                       k;
    std::vector<double>               &mu;
    std::vector<Tensor<1, dim>>       &lambda;
    const bool                         loop;
    LoopMeasures<dim>                  measures;
    const unsigned int                 max_passes;

    /** The coupled linearization is on (until a fallback). */
    bool                        coupling;
    FrictionCoefficients        coefficients;
    Vector_t                    w_start;
    std::vector<Tensor<1, dim>> lambda_start;

    bool                        allow_provisional = false;
    bool                        provisional       = false;
    /**
     * The last pass stopped at the provisional accuracy with w written
     * (the assembled solver's provisional passes).
     */
    bool                        inexact = false;
    double                      best_residual;
    std::vector<Tensor<1, dim>> xi_previous;
    /** The whole velocity of a provisional pass. */
    Vector_t w_previous;

    /** The loop's state at its start (again after a fallback). */
    void
    start();

    /** Measure the pass @p pass (provisional or whole). */
    Measures
    measure(const unsigned int pass);

    /**
     * Solve a pass (@p coupled: the coupled one); false if the coupled
     * pass failed, and the loop starts again from the step's start, frozen.
     */
    bool
    solve_pass(const bool coupled);

    /**
     * Finish a provisional pass (finalize()) and measure it again by the
     * whole rule.
     */
    void
    finish_provisional(const unsigned int pass,
                       const bool         after_provisional,
                       Measures          &m);

    /**
     * Finish a pass that stopped at the provisional accuracy with w
     * written: Newton on from w to its tolerance (the same coefficients),
     * and the pass measured again.
     */
    void
    finish_inexact(const unsigned int pass, Measures &m);

    /** The next frozen coefficients: the relaxed update. */
    void
    relax_coefficients(Measures &m);
  };


  template <int dim>
  void
  StepSolver<dim>::ConvexificationLoop::start()
  {
    allow_provisional = loop && solver.solvers.provisional_passes();
    provisional       = false;
    inexact           = false;
    best_residual     = std::numeric_limits<double>::max();
    if (loop)
      {
        TimerSection t(solver.timer, "Friction: convexification update");
        xi_previous = measures.start(w, lambda, mu);
      }
  }


  template <int dim>
  typename StepSolver<dim>::ConvexificationLoop::Measures
  StepSolver<dim>::ConvexificationLoop::measure(const unsigned int pass)
  {
    TimerSection t(solver.timer, "Friction: convexification update");
    // A provisional pass is measured by its velocities at the nodes, a
    // whole one by w.
    const std::vector<Tensor<1, dim>> nodal =
      provisional ? contact_solver.provisional_velocities() :
                    std::vector<Tensor<1, dim>>();
    return measures.measure(u_old,
                            k,
                            provisional ? nullptr : &w,
                            nodal,
                            lambda,
                            mu,
                            xi_previous,
                            pass,
                            solver.details);
  }


  template <int dim>
  bool
  StepSolver<dim>::ConvexificationLoop::solve_pass(const bool coupled)
  {
    // A provisional pass need not be solved further than the loop is
    // from its end: its velocities at the nodes may be off by a slip
    // rate that moves mu by at most the smallest coefficient residual
    // so far (the next pass moves the coefficients by about that much;
    // finalize() finishes a pass to the Newton tolerance before it
    // counts). A solver that writes w keeps within rule (85)'s tolerance
    // too (the next pass is compared with this one).
    const PassAccuracy provisional_accuracy{
      best_residual < std::numeric_limits<double>::max() ?
        best_residual / std::max(solver.lipschitz_constant, 1e-300) :
        0.,
      solver.friction_parameters.convexification_tolerance};
    coefficients.frozen = mu;
    coefficients.law    = coupled ? solver.friction_law : nullptr;
    if (coupled && solver.friction_parameters.slip_length.active())
      {
        coefficients.state       = solver.contact_state.coefficient_state;
        coefficients.slip_length = solver.friction_parameters.slip_length;
      }
    const ContactStep<dim> step{
      scheme, rhs, u_old_nodes, w_old_nodes, coefficients};
    try
      {
        const auto result = allow_provisional ?
                              contact_solver.solve_provisional(
                                step, lambda, w, provisional_accuracy) :
                              contact_solver.solve(step, lambda, w);
        statistics.add_newton(result);
        provisional = result.provisional;
        inexact     = result.inexact;
        return true;
      }
    catch (const StepFailure &failure)
      {
        if (!coupled)
          throw;
        // The fallback: the frozen loop from the step's start.
        solver.details << "  coupled pass failed (" << failure.what()
                       << "): the frozen-coefficient loop from the start"
                       << std::endl;
        statistics.newton_iterations += failure.newton_iterations;
        ++statistics.convexification_iterations;
        ++statistics.coupled_fallbacks;
        w        = w_start;
        lambda   = lambda_start;
        coupling = false;
        start();
        return false;
      }
  }


  template <int dim>
  void
  StepSolver<dim>::ConvexificationLoop::finish_provisional(
    const unsigned int pass,
    const bool         after_provisional,
    Measures          &m)
  {
    if (after_provisional)
      solver.discretization.reinit_owned(w_previous);
    statistics.add_newton(contact_solver.finalize(
      w, lambda, after_provisional ? &w_previous : nullptr));
    if (after_provisional)
      measures.remember(u_old, k, w_previous);
    provisional       = false;
    allow_provisional = false;
    m                 = measure(pass);
  }


  template <int dim>
  void
  StepSolver<dim>::ConvexificationLoop::finish_inexact(const unsigned int pass,
                                                       Measures          &m)
  {
    allow_provisional = false;
    solve_pass(false);
    m = measure(pass);
  }


  template <int dim>
  void
  StepSolver<dim>::ConvexificationLoop::relax_coefficients(Measures &m)
  {
    TimerSection t(solver.timer, "Friction: convexification update");
    measures.complete_coefficients(m);
    const double theta = solver.friction_parameters.relaxation;
    for (std::size_t i = 0; i < mu.size(); ++i)
      mu[i] = mu[i] + theta * (m.mu_new[i] - mu[i]);
    xi_previous = std::move(m.xi);
  }


  template <int dim>
  void
  StepSolver<dim>::ConvexificationLoop::run(const bool accept_unconverged_loop)
  {
    for (unsigned int pass = 0; pass < max_passes; ++pass)
      {
        // u^(m) of rule (85): w is whole unless the last pass was
        // provisional (then it is computed if the loop would end).
        const bool after_provisional = provisional;
        if (loop && !after_provisional)
          measures.remember(u_old, k, w);
        const bool coupled = coupling && pass == 0;
        if (!solve_pass(coupled))
          {
            pass = static_cast<unsigned int>(-1); // the loop's first pass next
            continue;
          }
        ++statistics.convexification_iterations;
        if (!loop)
          break;
        if (coupled)
          {
            // The coefficients the coupled pass ended with: the frozen ones
            // of the passes after it.
            TimerSection t(solver.timer, "Friction: convexification update");
            measures.coefficients_at(provisional ?
                                       contact_solver.provisional_velocities() :
                                       solver.contact_boundary.values(w),
                                     mu);
          }

        // A provisional pass that gains nothing beyond round-off (1e-9) on
        // the best coefficient residual so far is finished: a node that
        // changes from stick to fast slip leaves a - b in two passes, equal
        // but for round-off, and which pass was finished followed the
        // round-off of the scene's units (a fixed relative gain as the
        // rule, tried, finished passes that the rail's loop did not need:
        // more Newton iterations and solves; the commit that made this
        // rule records the counts).
        Measures m = measure(pass);
        const bool finish = m.converged || pass + 1 == max_passes ||
                            m.coefficient_residual > (1 - 1e-9) * best_residual;
        if (provisional && finish)
          finish_provisional(pass, after_provisional, m);
        if (inexact && finish)
          finish_inexact(pass, m);
        // A coupled pass's coefficient residual is 0 by construction: it
        // says nothing of how far the loop is from its end.
        if (!coupled)
          best_residual = std::min(best_residual, m.coefficient_residual);
        statistics.coefficient_residual = m.coefficient_residual;
        if (m.converged)
          break;
        // A loop that does not converge leaves mu_i != mu(|w_tau,i|): the
        // friction law would not hold. The step is retried with a smaller
        // time step instead (the fixed point contracts better with k); at
        // the smallest one it is kept and reported.
        if (pass + 1 == max_passes && accept_unconverged_loop)
          {
            statistics.convexification_converged = false;
            break;
          }
        if (pass + 1 == max_passes)
          throw StepFailure("the convexification loop did not converge in "
                            "Friction/Maximum convexification iterations = " +
                            std::to_string(max_passes) +
                            " passes (max |mu_i - mu(|w_tau,i|)| = " +
                            scientific(m.coefficient_residual) + ")");
        relax_coefficients(m);
      }
    if (provisional)
      statistics.add_newton(contact_solver.finalize(w, lambda));
  }


  template <int dim>
  typename StepSolver<dim>::Statistics
  StepSolver<dim>::solve(const TimeScheme &scheme,
                         const Vector_t   &rhs,
                         const Vector_t   &u_old,
                         const Vector_t   &w_old,
                         Vector_t         &w,
                         const bool        accept_unconverged_loop)
  {
    Assert(scheme == bulk.scheme(),
           ExcMessage("K0 is not formed for the step's time scheme."));
    Statistics          statistics;
    ContactSolver<dim> &contact_solver = solvers.solver_for(scheme);
    const auto          u_old_nodes = contact_boundary.values(u_old);
    const auto          w_old_nodes = contact_boundary.values(w_old);
    const bool          count       = friction_parameters.count_solutions &&
                       runs_convexification_loop(friction_law);
    const ContactState<dim> start_state =
      count ? contact_state : ContactState<dim>();
    const LoopArguments arguments{
      scheme, contact_solver, rhs, u_old, u_old_nodes, w_old_nodes};
    const bool loop_active =
      run_loop(arguments,
               w,
               statistics,
               LoopOptions{friction_parameters.coefficient_tolerance,
                           friction_parameters.max_convexification_iterations,
                           friction_parameters.coupled_linearization},
               accept_unconverged_loop);

    update_states(scheme, u_old_nodes, w_old_nodes, w, statistics);
    if (loop_active && (friction_parameters.uniqueness_monitor ==
                          Parameters::Friction::Monitor::always ||
                        (friction_parameters.uniqueness_monitor ==
                           Parameters::Friction::Monitor::automatic &&
                         solvers.plan().condensed)))
      uniqueness.measure(scheme, contact_solver, statistics);
    if (count)
      uniqueness.count_solutions(
        [&](Vector_t          &w_start,
            Statistics        &start_statistics,
            const double       coefficient_tolerance,
            const unsigned int max_passes,
            const bool         coupled) {
          run_loop(arguments,
                   w_start,
                   start_statistics,
                   LoopOptions{coefficient_tolerance, max_passes, coupled},
                   false);
        },
        scheme,
        w_old,
        start_state,
        statistics);
    if (loop_active && friction_parameters.slip_length.active())
      advance_coefficient_states(scheme);
    return statistics;
  }


  template <int dim>
  bool
  StepSolver<dim>::run_loop(const LoopArguments &a,
                            Vector_t            &w,
                            Statistics          &statistics,
                            const LoopOptions   &options,
                            const bool           accept_unconverged_loop)
  {
    ConvexificationLoop loop(*this,
                             a.contact_solver,
                             a.scheme,
                             a.rhs,
                             a.u_old,
                             a.u_old_nodes,
                             a.w_old_nodes,
                             w,
                             statistics,
                             options);
    loop.run(accept_unconverged_loop);
    return loop.active();
  }


  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                                \
  template typename StepSolver<dim>::Statistics StepSolver<dim>::solve( \
    const TimeScheme &,                                                 \
    const Vector_t &,                                                   \
    const Vector_t &,                                                   \
    const Vector_t &,                                                   \
    Vector_t &,                                                         \
    const bool);                                                        \
  template bool StepSolver<dim>::run_loop(const LoopArguments &,        \
                                          Vector_t &,                   \
                                          Statistics &,                 \
                                          const LoopOptions &,          \
                                          const bool);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
