#ifndef dynamic_contact_friction_law_h
#define dynamic_contact_friction_law_h

#include <deal.II/base/function_parser.h>

#include <deal.II/base/parameter_handler.h>

#include <dynamic_contact/base/plugins.h>
#include <dynamic_contact/laws/slip_length.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * The friction coefficient mu(s) of the slip rate s = |u'_tau| (eq. (18)):
   * an interface with the implementations 'constant', the paper's
   * slip-weakening 'exponential' (eq. (90)) and 'expression' (a function of
   * s), chosen by Friction/Law. A new law is a class derived from this one
   * with declare_parameters/parse_parameters for its own subsection
   * Friction/<Name>, registered with DYNAMIC_CONTACT_REGISTER(FrictionLaw,
   * Class, "name", "description") (doc/extending.md).
   */
  class FrictionLaw
  {
  public:
    virtual ~FrictionLaw() = default;

    /** mu(s), s >= 0. */
    virtual double
    value(const double s) const = 0;

    /** mu'(s) (one-sided at kinks). */
    virtual double
    derivative(const double s) const = 0;

    /** True if mu does not depend on s: one convexification pass suffices. */
    virtual bool
    is_constant() const = 0;

    /** A short description for logs, e.g. "mu(s) = 0.5 exp(-2000 s) + 0.5". */
    virtual std::string
    description() const = 0;

    /**
     * The one-sided Lipschitz constant lambda of H(mu)(c): the smallest
     * lambda >= 0 with mu(s1) - mu(s2) >= -lambda (s1 - s2) for
     * s1 > s2 >= 0 in [0, s_max], i.e. max(0, -min mu'). Sampled densely on
     * [0, s_max] (exact for the built-in laws).
     */
    virtual double
    one_sided_lipschitz_constant(const double s_max) const;

    /**
     * The largest coefficient on [0, s_max]: sampled (sample_points()),
     * exact for the built-in laws. The uniqueness bound's coupling through
     * the normal forces (doc/theory.md section 5.2) needs it.
     */
    virtual double
    largest_value(const double s_max) const;

    /**
     * Throws an ExcMessage naming the parameter if mu is negative or not
     * finite somewhere on [0, s_max] (sampled).
     */
    void
    check_nonnegative(const double s_max) const;

    /**
     * Where the laws are checked on [0, s_max]: 0, a geometric sequence
     * from 1e-11 s_max (dense near 0, where laws change fastest) and 1000
     * equal steps, sorted. Relative to s_max, so that a scene in other
     * units is sampled at the same slip rates.
     */
    static std::vector<double>
    sample_points(const double s_max);

    /**
     * Whether mu changes between two samples @p a and @p b by more than
     * its round-off (1e6 ulps): only such pairs give a slope to 1e-6
     * (near s = 0 the samples lie 1e-11 s_max apart).
     */
    static bool
    measurable(const double a, const double b);

    /**
     * The slip rates of the scene, [0, s_max] (Friction/Maximum slip
     * rate), for a law that needs a velocity scale of its own (the
     * expression's difference quotient); called once before the run.
     */
    virtual void
    set_slip_rate_window(const double s_max);

    /** Parse the law's own subsection (called inside it). */
    virtual void
    parse_parameters(ParameterHandler &prm) = 0;

    /**
     * Declare, inside subsection Friction, the entry Law (every registered
     * name, and 'none') and the subsection of every registered law.
     */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * The law that Friction/Law names, with its parameters (called inside
     * subsection Friction); nullptr for Law = none.
     */
    static std::unique_ptr<FrictionLaw>
    create(ParameterHandler &prm);
  };


  class ConstantFriction : public FrictionLaw
  {
  public:
    ConstantFriction() = default;
    explicit ConstantFriction(const double mu)
      : mu(mu)
    {}
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm) override;
    double
    value(const double) const override
    {
      return mu;
    }
    double
    derivative(const double) const override
    {
      return 0;
    }
    bool
    is_constant() const override
    {
      return true;
    }
    std::string
    description() const override;
    double
    one_sided_lipschitz_constant(const double) const override
    {
      return 0;
    }
    double
    largest_value(const double) const override
    {
      return mu;
    }

  private:
    double mu = 0;
  };


  /** mu(s) = (a - b) exp(-alpha s) + b, eq. (90). */
  class ExponentialFriction : public FrictionLaw
  {
  public:
    ExponentialFriction() = default;
    ExponentialFriction(const double a, const double b, const double alpha)
      : a(a)
      , b(b)
      , alpha(alpha)
    {}
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm) override;
    double
    value(const double s) const override;
    double
    derivative(const double s) const override;
    bool
    is_constant() const override
    {
      return a == b || alpha == 0;
    }
    std::string
    description() const override;
    /** alpha (a - b): the steepest descent, at s = 0 (0 if mu grows). */
    double
    one_sided_lipschitz_constant(const double) const override
    {
      return std::max(0., alpha * (a - b));
    }
    /** max(a, b): at s = 0 where mu falls, as s grows where it rises. */
    double
    largest_value(const double) const override
    {
      return std::max(a, b);
    }

  private:
    double a = 1, b = 0.5, alpha = 2000;
  };


  /** mu(s) from a muparser expression in the variable s. */
  class ExpressionFriction : public FrictionLaw
  {
  public:
    ExpressionFriction();
    ExpressionFriction(const std::string &expression,
                       const std::string &constants);
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm) override;
    double
    value(const double s) const override;
    /**
     * A central difference quotient with the step h = 1e-6 max(s, s_law)
     * (one-sided, of second order too, below s = h), s_law the slip rate
     * over which mu changes by
     * its range at its steepest slope on the window
     * (set_slip_rate_window()): a velocity of the law, so that the step is
     * the same in any consistent units.
     */
    double
    derivative(const double s) const override;
    bool
    is_constant() const override;
    std::string
    description() const override;
    void
    set_slip_rate_window(const double s_max) override;

  private:
    /** Parse @p expression with the constants "name=value, ...". */
    void
    initialize(const std::string &expression, const std::string &constants);

    std::string                        expression;
    std::unique_ptr<FunctionParser<1>> parser;
    /** s_law of derivative() (1 before set_slip_rate_window()). */
    double velocity_scale = 1;
  };

} // namespace DynamicContact

#endif
