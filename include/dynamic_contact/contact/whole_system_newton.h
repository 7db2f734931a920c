#ifndef dynamic_contact_whole_system_newton_h
#define dynamic_contact_whole_system_newton_h

#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/newton_driver.h>

#include <vector>

namespace DynamicContact
{
  /**
   * An iterate of the semismooth Newton iteration on the whole system
   * (doc/theory.md section 5)
   *   R(w, lambda) = K0 w - b + sum_i P_i^T (N_i(w) nu_i + lambda_i) = 0,
   *   lambda_i = P_B(0, mu_i N_i)(lambda_i + c m_i w_tau,i),
   * and what evaluating it computes. Everything per node is about the nodes
   * this process owns (ContactBoundary::nodes()): nothing is replicated.
   */
  template <int dim>
  struct WholeSystemIterate
  {
    /** The velocity w_n, master form. */
    Vector_t w;
    /** Friction forces lambda_i of the owned nodes. */
    std::vector<Tensor<1, dim>> lambda;

    // Filled by WholeSystemNewton::evaluate():
    /** The linearization of each owned node at (w, lambda). */
    std::vector<NodeLinearization<dim>> lin;
    /** f_i = N_i nu_i + lambda_i at the iterate. */
    std::vector<Tensor<1, dim>> forces;
    /**
     * The part of the linearized force that does not depend on the Newton
     * step's unknowns: N_i nu_i, plus the slip value at slip nodes.
     */
    std::vector<Tensor<1, dim>> base;
    /** R(w, lambda). */
    Vector_t residual;
    /**
     * Largest |lambda_i - P_B(...)| (all ranks), and the force it is
     * measured against: the largest nodal force, at least
     * WholeSystemNewton::force_scale.
     */
    double law_residual = 0;
    double law_squares  = 0; // sum of the squared law residuals
    /**
     * Sum of the squared slip rates of the stick nodes relative to
     * WholeSystemNewton::velocity_scale (0 where that is not set).
     */
    double stick_squares = 0;
    double f_scale       = 1e-300;
    /** max(|b|, |K0 w|): the scale of the equilibrium residual. */
    double scale = 1e-300;
    /** |R|. */
    double residual_norm = 0;
    /**
     * max(|R|/scale, law_residual/f_scale), and if
     * WholeSystemNewton::velocity_scale is set the largest slip rate |w_e,tau|
     * of a stick node (all ranks) relative to it: the stopping test's
     * measure.
     */
    double relative_residual = 0;
  };


  template <int dim>
  class WholeSystemNewton;

  /**
   * How a Newton step of the whole system is solved: the linear algebra
   * only. The globalization (line search, cycling, stagnation, the cap) is
   * globalized_newton()'s, the same for every back-end.
   */
  template <int dim>
  class LinearBackend
  {
  public:
    virtual ~LinearBackend() = default;

    /**
     * The full Newton step from the evaluated iterate @p x: @p full.w and
     * @p full.lambda (the friction forces the linearized laws give at the
     * new velocity; at stick nodes, the multiplier of w_tau = 0).
     */
    virtual void
    newton_step(const WholeSystemNewton<dim>  &system,
                const WholeSystemIterate<dim> &x,
                WholeSystemIterate<dim>       &full,
                ContactSolveResult            &result) = 0;
  };


  /**
   * The whole-system Newton iteration as globalized_newton() sees it:
   * evaluate an iterate (linearize the owned nodes, the residual with one
   * product with K0), its merit (the relative residual), the Newton step (by
   * the back-end) and the points on the step. O(N) per evaluation, with a
   * few global reductions.
   */
  template <int dim>
  class WholeSystemNewton
  {
  public:
    using Iterate = WholeSystemIterate<dim>;

    /** The iteration on @p step (what it refers to must outlive this). */
    WholeSystemNewton(const ContactProblem<dim> &problem,
                      const ContactStep<dim>    &step,
                      LinearBackend<dim>        &backend,
                      ContactSolveResult        &result);

    NewtonMeasure
    evaluate(Iterate &x) const;

    /**
     * Half the sum of the squared equilibrium and law residuals, each
     * relative to its scale (that of the current iterate): smooth where the
     * active sets do not change, so that the Newton step is a descent
     * direction of it.
     */
    double
    merit(const Iterate &trial, const Iterate &current) const
    {
      const double r = trial.residual_norm / current.scale;
      return 0.5 * (r * r + law_merit(trial.law_squares, current.f_scale) +
                    trial.stick_squares);
    }

    void
    newton_step(Iterate &x, Iterate &full)
    {
      backend.newton_step(*this, x, full, result);
    }

    void
    combine(const Iterate &x,
            const Iterate &full,
            const double   alpha,
            Iterate       &trial) const;

    /** Drop the coupled linearization's weakening limits (newton_driver.h). */
    /**
     * The coupled linearization's weakening limit acted at a node of
     * @p x (newton_driver.h; collective).
     */
    bool
    safeguarded(const Iterate &x) const;

    /**
     * residual = K0 w - b + sum_i P_i^T f_i for forces @p owned_forces of
     * the owned nodes; returns the residual's l2 norm.
     */
    double
    residual_of(const Vector_t                    &w,
                const std::vector<Tensor<1, dim>> &owned_forces,
                Vector_t                          &residual) const;

    /** w_e = theta w + (1 - theta) w_{n-1} at owned node i. */
    Tensor<1, dim>
    effective_velocity(const unsigned int i, const Tensor<1, dim> &w_i) const
    {
      return scheme.weighted(w_i, w_old[i]);
    }

    const ContactProblem<dim> &problem;
    /** The step's (k, theta); K0 is formed for it. */
    const TimeScheme                  &scheme;
    const Vector_t                    &rhs;
    const std::vector<Tensor<1, dim>> &u_old;
    const std::vector<Tensor<1, dim>> &w_old;
    const FrictionCoefficients        &mu;

    /**
     * If positive, the stopping test also measures the stick condition in
     * velocity units, the largest |w_e,tau| of a stick node relative to
     * this velocity. The law residual weighs it with c m_i = c_t k m_i,
     * which vanishes with the time step: at k = 5e-7 a stick node of the
     * critical-speed stress scene kept |w_tau| = 1.4e-10 of the largest
     * velocity while the law residual was far below its tolerance. The
     * scale must not vanish where the body comes to rest (the round-off of
     * w does not): the condensed solver gives max(|w|, 1e-6 |w_free|),
     * w_free = K0^{-1} b. Where it is set, a stick node's law residual (c
     * m_i |w_e,tau| exactly) is left to this measure (evaluate()).
     */
    double velocity_scale = 0;

    /**
     * The floor of the law residual's force scale: resolvable_force() of
     * the step's |b|_inf.
     */
    const double force_scale;

  private:
    LinearBackend<dim> &backend;
    ContactSolveResult &result;
  };
} // namespace DynamicContact

#endif
