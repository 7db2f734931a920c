#ifndef dynamic_contact_foundation_h
#define dynamic_contact_foundation_h

#include <deal.II/base/parameter_handler.h>

#include <dynamic_contact/base/plugins.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace DynamicContact
{
  /**
   * A capped ramp r -> min(slope r_+, cap): the shape of both the normal
   * compliance p and the normal damped response q, eq. (88). Value,
   * a generalized derivative (the one semismooth Newton uses: the slope on
   * the open interval where the ramp rises, zero elsewhere) and the
   * primitive Pi(r) = int_0^r.
   */
  class CappedRamp
  {
  public:
    CappedRamp(const double slope, const double cap)
      : slope(slope)
      , cap(cap)
      , kink(slope > 0 ? cap / slope : 0.)
    {}

    double
    value(const double r) const
    {
      return std::min(slope * std::max(r, 0.), cap);
    }

    /** The slope where 0 < r < cap/slope, zero elsewhere. */
    double
    derivative(const double r) const
    {
      return (slope > 0 && r > 0 && r < kink) ? slope : 0.;
    }

    /** True where the ramp is active (r > 0): the set this law adds to. */
    bool
    active(const double r) const
    {
      return slope > 0 && r > 0;
    }

    /** True where the cap is reached (r >= cap/slope). */
    bool
    saturated(const double r) const
    {
      return slope > 0 && r >= kink;
    }

    /** Pi(r) = int_0^r value(s) ds. */
    double
    primitive(const double r) const
    {
      if (r <= 0 || slope == 0)
        return 0.;
      if (r <= kink)
        return 0.5 * slope * r * r;
      return 0.5 * cap * kink + cap * (r - kink);
    }

    /**
     * The dissipation of a step from a to b of the compliance,
     *   p(b)(b - a) - (Pi(b) - Pi(a)) = int_min(a,b)^max(a,b) |p(s) - p(b)| ds,
     * which is >= 0 because p is nondecreasing. Evaluated on the linear
     * pieces of p, without the cancellation of the left-hand form.
     */
    double
    dissipation(const double a, const double b) const
    {
      if (slope == 0 || a == b)
        return 0.;
      const double lo = std::min(a, b), hi = std::max(a, b);
      const double pieces[4] = {lo,
                                std::clamp(0., lo, hi),
                                std::clamp(kink, lo, hi),
                                hi};
      double       sum       = 0;
      for (unsigned int i = 0; i < 3; ++i)
        {
          const double s0 = pieces[i], s1 = pieces[i + 1];
          if (s1 <= s0)
            continue;
          // |p(mid) - p(b)| on a piece where p is linear; where b lies in the
          // same piece use the slope (no cancellation).
          const double mid      = 0.5 * (s0 + s1);
          const bool   same     = (b >= s0 && b <= s1);
          const double gradient = (mid > 0 && mid < kink) ? slope : 0.;
          const double jump     = same ? gradient * std::abs(b - mid) :
                                         std::abs(value(b) - value(mid));
          sum += (s1 - s0) * jump;
        }
      return sum;
    }

    /**
     * The discrete gradient (Pi(b) - Pi(a))/(b - a): the compliance force of
     * the energy-consistent trapezoidal scheme, with which the work of the
     * force over a step is exactly the change of Pi (p((a+b)/2) as b -> a).
     * Exact on the linear pieces of p: p((a+b)/2) where a and b lie on one,
     * else the integral piece by piece (no difference of two values of Pi,
     * and no threshold on b - a, which would be a length).
     */
    double
    discrete_gradient(const double a, const double b) const
    {
      if (a == b || on_one_piece(a, b))
        return value(0.5 * (a + b));
      const double lo = std::min(a, b), hi = std::max(a, b);
      const double pieces[4] = {lo,
                                std::clamp(0., lo, hi),
                                std::clamp(kink, lo, hi),
                                hi};
      double       integral  = 0;
      for (unsigned int i = 0; i < 3; ++i)
        if (pieces[i + 1] > pieces[i])
          integral += (pieces[i + 1] - pieces[i]) *
                      value(0.5 * (pieces[i] + pieces[i + 1]));
      return integral / (hi - lo);
    }

    /**
     * d/db of the discrete gradient: (p(b)(b - a) - (Pi(b) - Pi(a)))/(b - a)^2
     * = dissipation(a, b)/(b - a)^2; p'/2 where a and b lie on one linear
     * piece of p.
     */
    double
    discrete_gradient_derivative(const double a, const double b) const
    {
      if (a == b || on_one_piece(a, b))
        return 0.5 * derivative(0.5 * (a + b));
      return dissipation(a, b) / ((b - a) * (b - a));
    }

    /** Whether a and b lie on one linear piece of the ramp. */
    bool
    on_one_piece(const double a, const double b) const
    {
      return (a > 0 && b > 0 && a < kink && b < kink) || (a <= 0 && b <= 0) ||
             (a >= kink && b >= kink);
    }

    double
    get_slope() const
    {
      return slope;
    }

    double
    get_cap() const
    {
      return cap;
    }

  private:
    double slope;
    double cap;
    double kink;
  };


  /**
   * A law of the foundation's normal response r -> f(r) (doc/theory.md
   * section 2): nondecreasing, f(r) = 0 for r <= 0; the normal compliance p
   * of the penetration and the normal damped response q of the normal
   * velocity are such laws (NormalLaw and DampingLaw, chosen by
   * Foundation/Normal compliance/Law and Foundation/Normal damping/Law).
   * What the solver and the energy balance use: value, a generalized
   * derivative, the primitive, and for the trapezoidal scheme the discrete
   * gradient and the dissipation of a step (with generic forms from the
   * primitive that an implementation may replace by exact ones).
   */
  class ResponseLaw
  {
  public:
    virtual ~ResponseLaw() = default;

    virtual double
    value(const double r) const = 0;
    /** A generalized derivative (the one semismooth Newton uses). */
    virtual double
    derivative(const double r) const = 0;
    /** int_0^r value(s) ds. */
    virtual double
    primitive(const double r) const = 0;
    /** Whether f vanishes everywhere (the law switched off). */
    virtual bool
    is_zero() const = 0;
    /**
     * The largest slope of f, sup |f(b) - f(a)|/|b - a| (a force per area
     * per unit of r); +infinity where a law does not know it. The
     * uniqueness bound (doc/theory.md section 5.2) needs it.
     */
    virtual double
    lipschitz_constant() const
    {
      return std::numeric_limits<double>::infinity();
    }

    /**
     * The least upper bound of f, the cap c3 or c4 of the paper's H(p)(b),
     * H(q)(b) (eqs. (33), (34)); infinite (the default) for a law that
     * gives no bound. The well-posedness report (doc/theory.md section
     * 1.5) takes the largest normal stress from it.
     */
    virtual double
    supremum() const
    {
      return std::numeric_limits<double>::infinity();
    }
    /** Where the law acts (r > 0): a set of the active-set Newton. */
    virtual bool
    active(const double r) const
    {
      return !is_zero() && r > 0;
    }
    /** Where f stops growing (a set of the active-set Newton). */
    virtual bool
    saturated(const double) const
    {
      return false;
    }
    /** f(b)(b - a) - (Pi(b) - Pi(a)) >= 0: the dissipation of a step. */
    virtual double
    dissipation(const double a, const double b) const
    {
      return std::max(0., value(b) * (b - a) - (primitive(b) - primitive(a)));
    }
    /**
     * (Pi(b) - Pi(a))/(b - a), f((a+b)/2) as b -> a: where b - a is below
     * close() of a and b, whose difference of Pi would cancel most digits.
     */
    virtual double
    discrete_gradient(const double a, const double b) const
    {
      if (close(a, b))
        return value(0.5 * (a + b));
      return (primitive(b) - primitive(a)) / (b - a);
    }
    /** d/db of the discrete gradient. */
    virtual double
    discrete_gradient_derivative(const double a, const double b) const
    {
      if (close(a, b))
        return 0.5 * derivative(0.5 * (a + b));
      return dissipation(a, b) / ((b - a) * (b - a));
    }
    /**
     * |b - a| at most 1e-8 (about the square root of the round-off) of
     * max(|a|, |b|): relative, so that the same scene in other units takes
     * the same branch. Then f((a+b)/2) errs by O((b - a)^2) where the
     * quotient would lose 8 of its digits.
     */
    static bool
    close(const double a, const double b)
    {
      return std::abs(b - a) <= 1e-8 * std::max(std::abs(a), std::abs(b));
    }

    /** Parse the law's own subsection (called inside it). */
    virtual void
    parse_parameters(ParameterHandler &prm) = 0;
  };

  /** The normal compliance p(u_nu) (eq. (17)); see ResponseLaw. */
  class NormalLaw : public ResponseLaw
  {};

  /** The normal damped response q(u'_nu) (eq. (17)); see ResponseLaw. */
  class DampingLaw : public ResponseLaw
  {};


  /**
   * The paper's capped ramp (eq. (88)) as a law of the foundation: the
   * implementation 'capped ramp' of both NormalLaw (entries Stiffness c_nu
   * and Cap c3) and DampingLaw (entries Coefficient d_nu and Cap c4).
   */
  template <class Interface>
  class CappedRampLaw : public Interface
  {
  public:
    CappedRampLaw() = default;
    explicit CappedRampLaw(const CappedRamp &ramp)
      : ramp(ramp)
    {}

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm) override;

    double
    value(const double r) const override
    {
      return ramp.value(r);
    }
    double
    derivative(const double r) const override
    {
      return ramp.derivative(r);
    }
    double
    primitive(const double r) const override
    {
      return ramp.primitive(r);
    }
    bool
    is_zero() const override
    {
      return ramp.get_slope() == 0;
    }
    double
    lipschitz_constant() const override
    {
      return ramp.get_slope();
    }
    /** c3 or c4 (0 where the law is switched off). */
    double
    supremum() const override
    {
      return is_zero() ? 0. : ramp.get_cap();
    }
    bool
    active(const double r) const override
    {
      return ramp.active(r);
    }
    bool
    saturated(const double r) const override
    {
      return ramp.saturated(r);
    }
    double
    dissipation(const double a, const double b) const override
    {
      return ramp.dissipation(a, b);
    }
    double
    discrete_gradient(const double a, const double b) const override
    {
      return ramp.discrete_gradient(a, b);
    }
    double
    discrete_gradient_derivative(const double a, const double b) const override
    {
      return ramp.discrete_gradient_derivative(a, b);
    }

  private:
    CappedRamp ramp{0., 1.};
  };


  // The entries of the two capped ramps, declare_parameters() and
  // parse_parameters() of CappedRampLaw<NormalLaw> and
  // CappedRampLaw<DampingLaw>: source/laws/foundation.cc.


  /**
   * The deformable foundation of eq. (17): -sigma_nu = p(u_nu) + q(u'_nu),
   * p the normal compliance, q the normal damped response.
   */
  class Foundation
  {
  public:
    Foundation(std::shared_ptr<const NormalLaw>  compliance,
               std::shared_ptr<const DampingLaw> damping,
               const bool                        damping_only_in_contact)
      : p(std::move(compliance))
      , q(std::move(damping))
      , damping_only_in_contact(damping_only_in_contact)
    {}

    /** The paper's foundation: capped ramps p = (c_nu, c3), q = (d_nu, c4). */
    Foundation(const CappedRamp &compliance,
               const CappedRamp &damping,
               const bool        damping_only_in_contact)
      : Foundation(std::make_shared<CappedRampLaw<NormalLaw>>(compliance),
                   std::make_shared<CappedRampLaw<DampingLaw>>(damping),
                   damping_only_in_contact)
    {}

    /**
     * Declare, inside subsection Foundation, the subsections Normal
     * compliance and Normal damping: each with the entry Law (the
     * registered laws) and a subsection per law.
     */
    static void
    declare_parameters(ParameterHandler &prm);

    /** The foundation the entries name (called inside Foundation). */
    static Foundation
    create(ParameterHandler &prm);

    /** Normal compliance p(r), e.g. min(c_nu r_+, c3). */
    const ResponseLaw &
    compliance() const
    {
      return *p;
    }

    /** Normal damped response q(r), e.g. min(d_nu r_+, c4). */
    const ResponseLaw &
    damping() const
    {
      return *q;
    }

    bool
    has_damping() const
    {
      return !q->is_zero();
    }

    /** Whether q acts at a node with penetration @p u_nu. */
    bool
    damping_acts(const double u_nu) const
    {
      return !damping_only_in_contact || u_nu > 0;
    }

    /**
     * The largest slope of the pressure p(u_nu) + q(w_nu) as a function
     * of the step's unknown normal velocity, where u_nu grows with it at
     * @p du_dw and w_nu at @p dw_dw (TimeScheme::displacement_derivative()
     * and effective_derivative()): du_dw Lip(p) + dw_dw Lip(q). The
     * discrete gradient of the trapezoidal scheme is no steeper than p.
     * +infinity where a law does not know its slope, or where q acts only
     * in contact (the pressure then jumps where the contact begins).
     */
    double
    pressure_lipschitz_constant(const double du_dw, const double dw_dw) const
    {
      if (damping_only_in_contact && has_damping())
        return std::numeric_limits<double>::infinity();
      return du_dw * p->lipschitz_constant() +
             (has_damping() ? dw_dw * q->lipschitz_constant() : 0.);
    }

    /**
     * The largest normal pressure p + q the laws allow, c3 + c4 (infinite
     * where a law gives no bound).
     */
    double
    pressure_bound() const
    {
      return p->supremum() + (has_damping() ? q->supremum() : 0.);
    }

    /** The normal pressure p(u_nu) + q(w_nu) (a force per unit area). */
    double
    pressure(const double u_nu, const double w_nu) const
    {
      return p->value(u_nu) + (damping_acts(u_nu) ? q->value(w_nu) : 0.);
    }

  private:
    std::shared_ptr<const NormalLaw>  p;
    std::shared_ptr<const DampingLaw> q;
    bool                              damping_only_in_contact;
  };
} // namespace DynamicContact

#endif
