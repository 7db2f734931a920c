#ifndef dynamic_contact_newton_driver_h
#define dynamic_contact_newton_driver_h

#include <deal.II/base/conditional_ostream.h>

#include <dynamic_contact/contact/contact_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <tuple>
#include <vector>

namespace DynamicContact
{
  /**
   * What an iterate of a semismooth Newton iteration measures of itself:
   * the relative residual (the stopping test), the merit function that the
   * line search decreases, and a fingerprint of its active sets (cycling,
   * stagnation).
   */
  struct NewtonMeasure
  {
    double        residual  = 0;
    double        merit     = 0;
    std::uint64_t signature = 0;
  };


  /**
   * How the globalization of one Newton iteration behaves (doc/algorithms.md,
   * "Globalization").
   */
  struct NewtonPolicy
  {
    /**
     * Armijo from the first iteration on (a step must lower the merit of the
     * current iterate); otherwise the first @p free_iterations steps are
     * taken in full (active-set changes may raise the merit while Newton
     * converges) and later ones must stay below the largest merit of the
     * last @p window iterates (non-monotone). A detected cycle makes the
     * rule monotone for the rest of the iteration either way.
     */
    bool         monotone        = false;
    unsigned int free_iterations = 4;
    unsigned int window          = 5;
    /**
     * Stagnation: an iterate reached by a full step, whose active sets are
     * those of the last one, whose residual fell by less than this factor,
     * and which is below sqrt(tolerance) is accepted (round-off, not a wrong
     * set; a damped step that gains little is no sign of round-off).
     */
    double stagnation_factor = 0.1;
    /** Name of the phase in the per-iteration diagnostics. */
    const char *name = "";
    /**
     * Stop below this relative residual if it is larger than
     * Solver/Newton tolerance (a provisional pass of the convexification
     * loop; the stagnation test keeps the Newton tolerance).
     */
    double tolerance = 0;
    /**
     * Newton steps taken before the stopping test may end the iteration
     * (the condensed solver's whole-system phase where its start is not
     * accurate enough for the convexification loop).
     */
    unsigned int minimum_iterations = 0;
    /**
     * An iterate reached by a full step that kept the active sets may end
     * the iteration early if this says it is accurate enough, given the
     * factor by which that step lowered the residual (a pass of the
     * convexification loop that is probably not its last; see
     * AssembledSolver::solve_provisional()). Empty: never.
     */
    std::function<bool(double)> accurate_enough;
  };


  /**
   * Whether @p current, whose active sets are those of the last iterate,
   * returns to an iterate before the last one (the past iterates' sets
   * @p history and residuals @p residuals): its sets and its residual to
   * 1e-9 (relative, so in any units the same).
   */
  inline bool
  revisits(const std::vector<std::uint64_t> &history,
           const std::vector<double>        &residuals,
           const NewtonMeasure              &current)
  {
    for (std::size_t j = 0; j + 1 < history.size(); ++j)
      if (history[j] == current.signature &&
          std::abs(residuals[j] - current.residual) <= 1e-9 * current.residual)
        return true;
    return false;
  }


  /**
   * Whether the iterate measured @p current returns to active sets seen
   * before (@p history, with other sets in between), or to an iterate seen
   * before (its sets and its residual again, to 1e-9, after another
   * iterate; @p residuals of the past iterates): globalized_newton()'s
   * cycling test.
   */
  inline bool
  is_cycling(const std::vector<std::uint64_t> &history,
             const std::vector<double>        &residuals,
             const NewtonMeasure              &current)
  {
    return history.size() >= 2 &&
           (current.signature != history.back() ?
              std::find(history.begin(),
                        history.end() - 1,
                        current.signature) != history.end() - 1 :
              revisits(history, residuals, current));
  }


  /**
   * Armijo backtracking from @p x along the full step to @p full, down to
   * 1/128 of it: @p x becomes the accepted point, whose measure is
   * returned. @p merit_now is the merit at @p x.
   */
  template <typename Problem, typename Result>
  NewtonMeasure
  backtrack_along_step(Problem                         &problem,
                       typename Problem::Iterate       &x,
                       const typename Problem::Iterate &full,
                       const double                     merit_now,
                       Result                          &result)
  {
    typename Problem::Iterate trial;
    NewtonMeasure             accepted;
    for (double alpha = 0.5;; alpha *= 0.5)
      {
        problem.combine(x, full, alpha, trial);
        accepted = problem.evaluate(trial);
        ++result.line_search_steps;
        if (problem.merit(trial, x) <= (1 - 1e-4 * alpha) * merit_now ||
            alpha < 1. / 64)
          break;
      }
    std::swap(x, trial);
    return accepted;
  }


  /**
   * One globalized semismooth Newton iteration, shared by every solver of
   * the step (the condensed solver's boundary phase, the whole-system
   * iteration with either linear back-end): stopping test, stagnation
   * acceptance, the cap (StepFailure, which the time loop answers with a
   * cut-back), active-set cycling detection, and the (non-)monotone Armijo
   * backtracking line search along the Newton step. What an iterate is, and
   * how the Newton step is computed, is the @p Problem's:
   *
   *   typename Problem::Iterate;
   *   NewtonMeasure evaluate(Iterate &x);     // linearize x, measure it
   *   double merit(const Iterate &trial, const Iterate &current);
   *   void newton_step(Iterate &x, Iterate &full); // x evaluated; full step
   *   void combine(const Iterate &x, const Iterate &full, double alpha,
   *                Iterate &trial);           // x + alpha (full - x)
   *   bool safeguarded(const Iterate &x);     // see below (collective)
   *
   * A linearization with a safeguard (the coupled friction linearization's
   * weakening limit, WeakeningLimit) is not the derivative of the merit
   * function where the safeguard acts: its step is not a descent
   * direction there, and it is meant to move a node away from a zero of
   * the merit function that the safeguard keeps the iteration from (a
   * slip rate at the onset of slip, where the law weakens faster than the
   * body resists). A line search would undo that, step after step (on
   * the 3D rail many iterations of a small fraction of a step each). So a
   * step from an iterate where the safeguard acts is taken in full unless
   * the iteration cycles.
   *
   * @p x is the starting iterate on entry and the solution on exit; @p
   * result counts iterations, cycles and line-search steps and holds the
   * last residual.
   */
  template <typename Problem, typename Result>
  void
  globalized_newton(Problem                   &problem,
                    typename Problem::Iterate &x,
                    const NewtonPolicy        &policy,
                    const Parameters::Solver  &parameters,
                    const ConditionalOStream  &details,
                    Result                    &result)
  {
    const double tol      = parameters.newton_tolerance;
    const double stop_tol = std::max(tol, policy.tolerance);

    typename Problem::Iterate  full;
    NewtonMeasure              current = problem.evaluate(x);
    std::vector<std::uint64_t> history; // active sets of the past iterates
    std::vector<double>        residuals; // and their residuals
    std::vector<double>        merits;
    bool                       monotone          = policy.monotone;
    double                     previous_residual = 0;
    bool                       last_step_full    = false;

    for (unsigned int iteration = 0;; ++iteration)
      {
        details << "    Newton " << result.iterations << " (" << policy.name
                << "): residual " << current.residual << std::endl;
        const bool stagnated =
          iteration > 0 && last_step_full &&
          current.signature == history.back() &&
          current.residual > policy.stagnation_factor * previous_residual &&
          current.residual < std::sqrt(tol);
        result.residual = current.residual;
        if ((current.residual <= stop_tol || stagnated) &&
            iteration >= policy.minimum_iterations)
          break;
        if (policy.accurate_enough && iteration > 0 && last_step_full &&
            current.signature == history.back() &&
            policy.accurate_enough(current.residual / previous_residual))
          {
            result.inexact = true;
            break;
          }
        check_newton_cap(result.iterations, current.residual, parameters);
        previous_residual = current.residual;

        // Cycling: a return to active sets seen before, with other sets in
        // between (keeping the last sets, as a damped step does, is no
        // cycle), or to an iterate seen before (its sets and its residual
        // again, to 1e-9, after another iterate: a cycle of full steps that
        // the non-monotone rule below would accept for ever, e.g. of period
        // 3 within its window of 5). The line search then damps the step
        // (the remedy) and the rule turns monotone.
        const bool cycling = is_cycling(history, residuals, current);
        result.cycles += cycling;
        if (cycling && !monotone)
          details << "    Newton " << result.iterations << " (" << policy.name
                  << "): cycle detected, damped steps from here on"
                  << std::endl;
        monotone = monotone || cycling;
        history.push_back(current.signature);
        residuals.push_back(current.residual);
        const double merit_now = current.merit;
        merits.push_back(merit_now);

        // The full semismooth Newton step, and the merit where it lands.
        problem.newton_step(x, full);
        NewtonMeasure accepted   = problem.evaluate(full);
        const double  merit_full = problem.merit(full, x);
        const double  reference =
          *std::max_element(merits.end() - std::min<std::size_t>(merits.size(),
                                                                 policy.window),
                            merits.end());
        const bool rejected =
          parameters.line_search &&
          (cycling || (monotone && merit_full > (1 - 1e-4) * merit_now) ||
           (iteration >= policy.free_iterations && merit_full > reference));
        const bool backtrack =
          rejected && (cycling || !problem.safeguarded(x));
        if (backtrack)
          {
            accepted =
              backtrack_along_step(problem, x, full, merit_now, result);
          }
        else
          std::swap(x, full);
        last_step_full = !backtrack;
        current        = accepted;
        ++result.iterations;
      }
  }


  /**
   * The smallest force a law residual can be measured against to
   * @p tolerance: 16 eps |b|_inf / tolerance, @p rhs_force = |b|_inf the
   * step's largest nodal force (inertia, elasticity, loads). The forces
   * of a step carry round-off of about eps |b|_inf; where the contact
   * forces are of that size themselves (a node that touches the
   * foundation at a penetration of round-off), a law residual relative to
   * them never falls below a tolerance (the impact stress scene written in
   * mm-tonne-s touched that way at the end of a step: 46 Newton
   * iterations with a rising residual, and a cut-back). Relative to the
   * step's own forces it is the same in any consistent units; far below
   * any contact force that carries load.
   */
  inline double
  resolvable_force(const double rhs_force, const double tolerance)
  {
    return 16 * std::numeric_limits<double>::epsilon() * rhs_force / tolerance;
  }


  /**
   * The friction law's part of a merit function: the sum of the squared law
   * residuals relative to the force scale @p f_scale (0 where there is no
   * law residual, even if no force acts yet).
   */
  inline double
  law_merit(const double law_squares, const double f_scale)
  {
    return law_squares == 0 ? 0. : law_squares / (f_scale * f_scale);
  }


  /**
   * A fingerprint of the active sets: the sum over the nodes of a hash of
   * (the node's first DoF, its set signature), so that it is the same
   * whatever the order of the nodes and the number of processes (the sum
   * over the processes is taken by the caller).
   */
  inline std::uint64_t
  node_set_hash(const std::uint64_t key, const unsigned int signature)
  {
    // SplitMix64 of the combined value.
    std::uint64_t z = key * 0x9E3779B97F4A7C15ull + signature + 1;
    z               = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z               = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }


  /**
   * What every Newton back-end needs to know about one node of Gamma_3 at
   * an iterate (w_i, lambda_i): the linearized laws, the nodal force at the
   * iterate (normal law at w plus the friction force as it stands), the
   * part of the linearized force that does not depend on the unknowns of
   * the Newton step, the residual of the friction law, and the hash of the
   * node's sets.
   */
  template <int dim>
  struct NodeEvaluation
  {
    NodeLinearization<dim> lin;
    Tensor<1, dim>         force;
    Tensor<1, dim>         base;
    /** |lambda_i - P(lambda_i + c w_e,tau)| (0 without friction). */
    double law_residual = 0;
    /**
     * |w_e,tau| at a stick node (else 0): the stick condition in velocity
     * units. In the law residual it is c m_i |w_e,tau|, a force that
     * vanishes with the time step (c = c_t k).
     */
    double        stick_rate = 0;
    std::uint64_t signature  = 0;
  };

  /**
   * The one per-node evaluation of the Newton back-ends (condensed and
   * whole-system): the laws of @p problem in the step of @p scheme at node
   * @p node with the old
   * values @p u_old, @p w_old, the iterate @p w, @p lambda and node @p i's
   * coefficient of @p mu (frozen, or mu(|w_e,tau|) of the iterate with its
   * derivative in the linearization: FrictionCoefficients).
   */
  template <int dim>
  NodeEvaluation<dim>
  evaluate_node(const ContactProblem<dim>  &problem,
                const TimeScheme           &scheme,
                const ContactNode<dim>     &node,
                const Tensor<1, dim>       &u_old,
                const Tensor<1, dim>       &w_old,
                const Tensor<1, dim>       &w,
                const Tensor<1, dim>       &lambda,
                const FrictionCoefficients &mu,
                const unsigned int          i)
  {
    const double c    = problem.c_t * scheme.time_step();
    double       mu_i = 0, dmu_ds = 0;
    if (problem.friction && mu.coupled())
      {
        const double s = node.tangential(scheme.weighted(w, w_old)).norm();
        std::tie(mu_i, dmu_ds) = mu.coupled_coefficient(i, s, scheme);
      }
    else if (problem.friction && !mu.frozen.empty())
      mu_i = mu.frozen[i];
    NodeEvaluation<dim> e;
    e.lin = linearize_node(problem.foundation,
                           node,
                           u_old,
                           w_old,
                           w,
                           scheme,
                           problem.friction,
                           lambda,
                           mu_i,
                           c,
                           dmu_ds,
                           mu.coupled() && !mu.weakening_limit.empty() ?
                             mu.weakening_limit[i] :
                             std::numeric_limits<double>::infinity());
    const Tensor<1, dim> normal_force =
      e.lin.normal.pressure * node.weight * node.normal;
    e.force = normal_force + lambda;
    e.base  = normal_force;
    if (e.lin.friction.state == FrictionState::slip)
      e.base += e.lin.friction.value;
    if (problem.friction)
      e.law_residual =
        (lambda - projected_friction_force(node,
                                           e.lin.friction.threshold,
                                           scheme.weighted(w, w_old),
                                           lambda,
                                           c))
          .norm();
    if (e.lin.friction.state == FrictionState::stick)
      e.stick_rate = node.tangential(scheme.weighted(w, w_old)).norm();
    e.signature =
      node_set_hash(node.dofs[0],
                    e.lin.normal.set_signature() +
                      16 * static_cast<unsigned int>(e.lin.friction.state));
    return e;
  }
} // namespace DynamicContact

#endif
