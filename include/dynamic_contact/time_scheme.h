#ifndef dynamic_contact_time_scheme_h
#define dynamic_contact_time_scheme_h

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
} // namespace DynamicContact

#endif
