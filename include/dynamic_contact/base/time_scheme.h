#ifndef dynamic_contact_time_scheme_h
#define dynamic_contact_time_scheme_h

#include <cmath>

namespace DynamicContact
{
  /**
   * One step of the velocity-based theta-scheme (doc/theory.md section 2):
   * from (u_{n-1}, w_{n-1}) at t - k to (u_n, w_n) at t,
   *   (rho/k) M (w_n - w_{n-1}) + A w_e + B u_theta + contact(u_n, w_e)
   *     = f_theta,
   * with the effective velocity w_e = theta w_n + (1 - theta) w_{n-1}, the
   * displacement u_n = u_{n-1} + k w_e, u_theta = theta u_n + (1 - theta)
   * u_{n-1} and f_theta = theta f(t) + (1 - theta) f(t - k). theta = 1 is
   * backward Euler (the paper's scheme), theta = 1/2 the trapezoidal rule.
   * A sub-step of a composite scheme (Time/Scheme = bathe) is one such step
   * too, with its own k and theta.
   *
   * This value type is the one place that writes these combinations; the
   * code never spells out "(1 - theta)" by hand. Every formula keeps the
   * floating-point operations of the hand-written code it replaced.
   */
  class TimeScheme
  {
  public:
    TimeScheme(const double time_step = 0, const double theta = 1)
      : k(time_step)
      , th(theta)
    {}

    /** The step (or sub-step) length k. */
    double
    time_step() const
    {
      return k;
    }

    double
    theta() const
    {
      return th;
    }

    /** theta = 1: the laws act on u_n and w_n, f on t only. */
    bool
    is_backward_euler() const
    {
      return th == 1;
    }

    bool
    operator==(const TimeScheme &other) const
    {
      return k == other.k && th == other.th;
    }
    bool
    operator!=(const TimeScheme &other) const
    {
      return !(*this == other);
    }

    /** theta x + (1 - theta) x_old for numbers and tensors (w_e, f_theta). */
    template <typename T>
    T
    weighted(const T &x, const T &x_old) const
    {
      return th * x + (1 - th) * x_old;
    }

    /**
     * The same in place for vectors: x <- theta x + (1 - theta) x_old.
     * (Unconditional; callers that skip the old values for theta = 1 test
     * is_backward_euler() themselves.)
     */
    template <typename VectorType>
    void
    weigh(VectorType &x, const VectorType &x_old) const
    {
      x *= th;
      x.add(1 - th, x_old);
    }

    /** u_n = u_{n-1} + k (theta w_n + (1 - theta) w_{n-1}). */
    template <typename VectorType>
    void
    advance_displacement(VectorType       &u,
                         const VectorType &u_old,
                         const VectorType &w,
                         const VectorType &w_old) const
    {
      u = u_old;
      u.add(k * th, w);
      if (th < 1)
        u.add(k * (1 - th), w_old);
    }

    /** u_n = u_{n-1} + k w_e at a node (tensors). */
    template <typename T>
    T
    displacement(const T &u_old, const T &w_effective) const
    {
      return u_old + k * w_effective;
    }

    /** d w_e / d w_n. */
    double
    effective_derivative() const
    {
      return th;
    }

    /** d u_n / d w_n = theta k. */
    double
    displacement_derivative() const
    {
      return th * k;
    }

    /**
     * The coefficients of K0 = (rho/k) M + theta A + theta^2 k B, the
     * matrix of w_n: mass (times rho), viscosity, elasticity.
     */
    double
    mass_coefficient(const double density) const
    {
      return density / k;
    }
    double
    viscosity_coefficient() const
    {
      return th;
    }
    double
    elasticity_coefficient() const
    {
      return th * th * k;
    }

    /**
     * The right-hand side's old parts: B acts on
     * u_{n-1} + theta (1 - theta) k w_{n-1} (returned: the factor of
     * w_{n-1}), A on -(1 - theta) w_{n-1} (viscosity_old_factor()).
     */
    double
    elastic_old_velocity_factor() const
    {
      return th * (1 - th) * k;
    }
    double
    viscosity_old_factor() const
    {
      return 1 - th;
    }

    /**
     * The compliance force of a step with theta < 1 from p(u_n) and the
     * discrete gradient DG = (Pi(u_n) - Pi(u_{n-1}))/(u_n - u_{n-1}) (or
     * from their derivatives):
     *   P_n = (2 theta - 1) p(u_n) + 2 (1 - theta) DG,
     * exactly DG for theta = 1/2 (energy-consistent) and p(u_n) for
     * theta = 1. It equals p(u_theta) to O(k^2), as the composite scheme's
     * second order needs for theta in (1/2, 1), and its dissipation
     * P_n (u_n - u_{n-1}) - (Pi(u_n) - Pi(u_{n-1}))
     *   = (2 theta - 1) [p(u_n)(u_n - u_{n-1}) - (Pi(u_n) - Pi(u_{n-1}))]
     * is >= 0 for a nondecreasing p.
     */
    double
    compliance_force(const double end_value,
                     const double discrete_gradient) const
    {
      if (th == 0.5)
        return discrete_gradient;
      return (2 * th - 1) * end_value + 2 * (1 - th) * discrete_gradient;
    }

    /**
     * The scheme's numerical dissipation factor (theta - 1/2) of
     * rho |w_n - w_{n-1}|^2 and a_E(u_n - u_{n-1}, u_n - u_{n-1}).
     */
    double
    numerical_dissipation_factor() const
    {
      return th - 0.5;
    }

  private:
    double k;
    double th;
  };

  /**
   * The composite scheme of Time/Scheme = bathe (doc/theory.md section
   * 2.4) with a prescribed spectral radius at infinity rho_inf in [0, 1].
   * A step of length k from (u_{n-1}, w_{n-1}):
   *   1. the trapezoidal rule over k/2 to (u_{n-1/2}, w_{n-1/2});
   *   2. the linear extrapolation to t_{n-1} + s k of both fields,
   *        x_bar = (1 + a) x_{n-1/2} - a x_{n-1},   a = 2 s - 1;
   *   3. one theta-step (TimeScheme) of length (1 - s) k from x_bar to t_n.
   * Second order for every rho_inf; s and theta solve
   *   (theta - 1) s^2 + (5/4 - 2 theta) s + (theta - 1/2) = 0,
   *   rho_inf = (1 + 2 a) (1 - theta)/theta,
   * whose solution in closed form is
   *   s = ((5 rho + 11) + sqrt((1 - rho)(7 rho + 25)))/(8 rho + 24),
   *   theta = (s^2 - 5 s/4 + 1/2)/(1 - s)^2.
   * rho_inf = 0 is the Bathe scheme (s = 2/3, theta = 1: backward Euler
   * over k/3 from (4 x_{n-1/2} - x_{n-1})/3), with exactly the constants
   * of the hand-written code it replaced; rho_inf = 1 is two trapezoidal
   * half steps (s = 1/2, theta = 1/2).
   *
   * This value type is the one place that holds these coefficients.
   */
  class CompositeScheme
  {
  public:
    explicit CompositeScheme(const double spectral_radius_at_infinity = 0)
      : rho(spectral_radius_at_infinity)
    {
      if (rho == 0)
        return; // the defaults below: s = 2/3, theta = 1
      const double s =
        ((5 * rho + 11) + std::sqrt((1 - rho) * (7 * rho + 25))) /
        (8 * rho + 24);
      th             = (s * s - 1.25 * s + 0.5) / ((1 - s) * (1 - s));
      half_weight    = 2 * s;
      old_weight     = 1 - 2 * s;
      second_divisor = 1 / (1 - s);
      work_share     = (2 * s - 1) / (2 * s);
      error_bar      = -1 / s;
      error_old      = (1 - s) / s;
      error_divisor  = 1 / ((1 - s) * th - 1. / 6);
    }

    double
    spectral_radius_at_infinity() const
    {
      return rho;
    }

    /** The theta of the second sub-step. */
    double
    theta() const
    {
      return th;
    }

    /** Sub-step 1 of a step of length k: the trapezoidal rule over k/2. */
    TimeScheme
    first_substep(const double k) const
    {
      return TimeScheme(k / 2, 0.5);
    }

    /** Sub-step 3: the theta-step of length (1 - s) k that ends at t_n. */
    TimeScheme
    second_substep(const double k) const
    {
      return TimeScheme(k / second_divisor, th);
    }

    /** x_bar = (1 + a) x_{n-1/2} - a x_{n-1}. */
    template <typename VectorType>
    void
    extrapolate(VectorType       &x_bar,
                const VectorType &x_half,
                const VectorType &x_old) const
    {
      x_bar = x_half;
      x_bar *= half_weight;
      x_bar.add(old_weight, x_old);
    }

    /**
     * The share a/(1 + a) of u_bar - u_{n-1} that is the extrapolation's
     * displacement u_bar - u_{n-1/2}.
     */
    double
    extrapolation_share() const
    {
      return work_share;
    }

    /**
     * The local error estimate of the displacement (doc/theory.md section
     * 2.5): the scheme's u_n - u_{n-1} is a quadrature of the velocities,
     *   k ((1 + a)/4 - (1 - s)(1 - theta) a) w_{n-1}
     *   + k (1 + a)((1/4) + (1 - s)(1 - theta)) w_{n-1/2}
     *   + k (1 - s) theta w_n,
     * exact for linear velocities; its difference to Simpson's rule is
     *   e = k ((1 - s) theta - 1/6) (w_{n-1} - 2 w_{n-1/2} + w_n),
     * written with w_{n-1/2} = (w_bar + a w_{n-1})/(1 + a).
     */
    template <typename VectorType>
    void
    local_error(VectorType       &e,
                const VectorType &w,
                const VectorType &w_bar,
                const VectorType &w_old,
                const double      k) const
    {
      e = w;
      e.add(error_bar, w_bar);
      e.add(error_old, w_old);
      e *= k / error_divisor;
    }

  private:
    double rho;
    // rho_inf = 0, in the constants of the Bathe scheme.
    double th             = 1;
    double half_weight    = 4. / 3;
    double old_weight     = -1. / 3;
    double second_divisor = 3;
    double work_share     = 0.25;
    double error_bar      = -1.5;
    double error_old      = 0.5;
    double error_divisor  = 6;
  };
  /**
   * The two-stage singly diagonally implicit Runge-Kutta scheme of
   * Time/Scheme = sdirk (doc/theory.md section 2.6) with a prescribed
   * spectral radius at infinity rho_inf in [0, 1]: the Butcher tableau
   *   c = (gamma, 1 - gamma),  A = [[gamma, 0], [1 - 2 gamma, gamma]],
   *   b = (1/2, 1/2),
   * on the first-order system y = (u, w), y' = (w, M^-1 (f - ...)).
   * A step of length k from y_{n-1}:
   *   1. a backward-Euler step of gamma k from y_{n-1} to Y1 at
   *      t_{n-1} + gamma k;
   *   2. the extrapolation y_hat = y_{n-1} + alpha (Y1 - y_{n-1}),
   *      alpha = (1 - 2 gamma)/gamma;
   *   3. a backward-Euler step of gamma k from y_hat to Y2 at
   *      t_{n-1} + (1 - gamma) k;
   *   4. y_n = y_{n-1} + beta ((Y1 - y_{n-1}) + (Y2 - y_hat)),
   *      beta = 1/(2 gamma), i.e. y_n = rho_inf y_{n-1}
   *      + beta (1 - alpha) Y1 + beta Y2.
   * Second order for every gamma; R(infinity) = 1 - (4 gamma - 1)/(2 gamma^2)
   * = rho_inf gives gamma = (2 - sqrt(2 + 2 rho))/(2 (1 - rho)), from
   * 1 - 1/sqrt(2) (rho_inf = 0, L-stable) to 1/4 (rho_inf = 1: two implicit
   * midpoint steps of k/2). Its algebraic-stability matrix
   * diag(b) A + A^T diag(b) - b b^T = (gamma - 1/4) [[1, -1], [-1, 1]] is
   * positive semidefinite, so that the energy of the quadratic part changes
   * by the stages' work minus
   *   D_num = (gamma - 1/4)/(2 gamma^2) |(Y1 - y_{n-1}) - (Y2 - y_hat)|_E^2
   * >= 0, for any load, damping and contact forces (doc/theory.md
   * section 6). This value type is the one place that holds these
   * coefficients.
   */
  class SdirkScheme
  {
  public:
    explicit SdirkScheme(const double rho = 0)
      : g(rho >= 1 ? 0.25 : (2 - std::sqrt(2 + 2 * rho)) / (2 * (1 - rho)))
    {}

    /** Both stages: backward Euler over gamma k. */
    TimeScheme
    stage(const double k) const
    {
      return TimeScheme(g * k, 1);
    }

    /** The stages' times after t_{n-1}, as fractions of k. */
    double
    first_stage_time() const
    {
      return g;
    }
    double
    second_stage_time() const
    {
      return 1 - g;
    }

    /** y_hat = y_{n-1} + alpha (Y1 - y_{n-1}). */
    template <typename VectorType>
    void
    second_stage_start(VectorType       &y_hat,
                       const VectorType &y1,
                       const VectorType &y_old) const
    {
      const double alpha = (1 - 2 * g) / g;
      y_hat              = y1;
      y_hat *= alpha;
      y_hat.add(1 - alpha, y_old);
    }

    /** y_n = y_{n-1} + beta ((Y1 - y_{n-1}) + (Y2 - y_hat)), in place of Y2. */
    template <typename VectorType>
    void
    combine(VectorType       &y2_to_yn,
            const VectorType &y1,
            const VectorType &y_hat,
            const VectorType &y_old) const
    {
      y2_to_yn.add(-1., y_hat);
      y2_to_yn.add(1., y1);
      y2_to_yn.add(-1., y_old);
      y2_to_yn *= stage_weight(); // beta
      y2_to_yn += y_old;
    }

    /**
     * beta = b_i/gamma = 1/(2 gamma): the weight of a stage's increment in
     * y_n (combine()) and of its work and dissipation (each stage books
     * them over gamma k) in the step's balance.
     */
    double
    stage_weight() const
    {
      return 1 / (2 * g);
    }

    /** (gamma - 1/4)/(2 gamma^2), the factor of D_num. */
    double
    numerical_dissipation_factor() const
    {
      return (g - 0.25) / (2 * g * g);
    }

    /**
     * A quantity known at the two stages (a contact force sum) at t_n, by
     * linear extrapolation in time.
     */
    double
    value_at_end(const double first, const double second) const
    {
      return ((1 - g) * second - g * first) / (1 - 2 * g);
    }

    /**
     * The local error estimate of the displacement (doc/theory.md section
     * 2.5): u_n - u_{n-1} = (k/2)(W1 + W2) against the quadrature of the
     * velocities w_{n-1}, W1, W2 at 0, gamma, 1 - gamma that is exact for
     * quadratics; the difference is
     *   e = k C (w_{n-1}/(gamma (1 - gamma)) + W1/(gamma (2 gamma - 1))
     *            + W2/((1 - gamma)(1 - 2 gamma))),
     *   C = 1/3 - (gamma^2 + (1 - gamma)^2)/2,
     * O(k^3) for smooth velocities.
     */
    template <typename VectorType>
    void
    local_error(VectorType       &e,
                const VectorType &w2,
                const VectorType &w1,
                const VectorType &w_old,
                const double      k) const
    {
      const double C = 1. / 3 - (g * g + (1 - g) * (1 - g)) / 2;
      e              = w2;
      e *= k * C / ((1 - g) * (1 - 2 * g));
      e.add(k * C / (g * (2 * g - 1)), w1);
      e.add(k * C / (g * (1 - g)), w_old);
    }

  private:
    double g; // gamma
  };
} // namespace DynamicContact

#endif
