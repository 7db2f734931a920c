#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/laws/friction_law.h>

#include <cctype>

#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    /** Declare the entry @p name, a number (Patterns::Double()). */
    void
    declare_number(ParameterHandler  &prm,
                   const std::string &name,
                   const std::string &default_value,
                   const std::string &documentation)
    {
      prm.declare_entry(name, default_value, Patterns::Double(), documentation);
    }
  } // namespace


  std::vector<double>
  FrictionLaw::sample_points(const double s_max)
  {
    std::vector<double> s = {0.};
    for (double x = 1e-11 * s_max; x < s_max; x *= 1.02)
      s.push_back(x);
    for (unsigned int i = 1; i <= 1000; ++i)
      s.push_back(s_max * i / 1000.);
    std::sort(s.begin(), s.end());
    return s;
  }


  double
  FrictionLaw::one_sided_lipschitz_constant(const double s_max) const
  {
    const auto s      = sample_points(s_max);
    double     lambda = 0;
    for (unsigned int i = 1; i < s.size(); ++i)
      {
        const double a = value(s[i - 1]), b = value(s[i]);
        if (s[i] > s[i - 1] && measurable(a, b))
          lambda = std::max(lambda, -(b - a) / (s[i] - s[i - 1]));
      }
    return lambda;
  }


  double
  FrictionLaw::largest_value(const double s_max) const
  {
    double largest = 0;
    for (const double s : sample_points(s_max))
      largest = std::max(largest, value(s));
    return largest;
  }


  bool
  FrictionLaw::measurable(const double a, const double b)
  {
    return std::abs(b - a) >= 1e6 * std::numeric_limits<double>::epsilon() *
                                std::max(std::abs(a), std::abs(b));
  }


  void
  FrictionLaw::set_slip_rate_window(const double)
  {}


  void
  FrictionLaw::check_nonnegative(const double s_max) const
  {
    for (const double s : sample_points(s_max))
      {
        const double mu = value(s);
        AssertThrow(std::isfinite(mu) && mu >= 0,
                    ExcMessage("Friction/Maximum slip rate = " + sig6(s_max) +
                               ": the friction coefficient " + description() +
                               " must be finite and >= 0 on the slip rates "
                               "[0, " +
                               sig6(s_max) + "], but mu(" + sig6(s) +
                               ") = " + sig6(mu) + "."));
      }
  }


  namespace
  {
    using FrictionLaws = PluginRegistry<FrictionLaw>;

  } // namespace


  void
  FrictionLaw::declare_parameters(ParameterHandler &prm)
  {
    const auto &laws = FrictionLaws::instance();
    prm.declare_entry(
      "Law",
      "none",
      Patterns::Selection("none|" + laws.names()),
      "The friction coefficient mu(s) of the slip rate s = |w_tau|, with "
      "the parameters in the subsection of the law's name: 'none' "
      "(frictionless: no multiplier, no sets, no loop). " +
        laws.documentation());
    laws.declare_subsections(prm);
  }


  std::unique_ptr<FrictionLaw>
  FrictionLaw::create(ParameterHandler &prm)
  {
    const std::string name = prm.get("Law");
    if (name == "none")
      return nullptr;
    return FrictionLaws::instance().create(name, prm);
  }


  void
  ConstantFriction::declare_parameters(ParameterHandler &prm)
  {
    declare_number(prm,
                   "Coefficient",
                   "0",
                   "mu, >= 0. Zero means no friction.");
  }

  void
  ConstantFriction::parse_parameters(ParameterHandler &prm)
  {
    mu = prm.get_double("Coefficient");
    AssertThrow(std::isfinite(mu) && mu >= 0,
                ExcMessage("Friction/Constant/Coefficient must be >= 0, got " +
                           str(mu) + "."));
  }

  DYNAMIC_CONTACT_REGISTER(FrictionLaw,
                           ConstantFriction,
                           "constant",
                           "mu = Coefficient.");


  void
  ExponentialFriction::declare_parameters(ParameterHandler &prm)
  {
    declare_number(prm, "Static coefficient", "1", "a = mu(0).");
    declare_number(prm,
                   "Dynamic coefficient",
                   "0.5",
                   "b = mu(infinity), 0 < b <= a.");
    declare_number(prm, "Decay rate", "2000", "alpha (s/m), >= 0.");
  }

  void
  ExponentialFriction::parse_parameters(ParameterHandler &prm)
  {
    a     = prm.get_double("Static coefficient");
    b     = prm.get_double("Dynamic coefficient");
    alpha = prm.get_double("Decay rate");
    AssertThrow(std::isfinite(b) && b > 0,
                ExcMessage(
                  "Friction/Exponential/Dynamic coefficient must be positive, "
                  "got " +
                  str(b) + "."));
    AssertThrow(std::isfinite(a) && a >= b,
                ExcMessage("Friction/Exponential/Static coefficient must be >= "
                           "the dynamic coefficient (a >= b), got a = " +
                           str(a) + "."));
    AssertThrow(std::isfinite(alpha) && alpha >= 0,
                ExcMessage(
                  "Friction/Exponential/Decay rate must be >= 0, got " +
                  str(alpha) + "."));
  }

  DYNAMIC_CONTACT_REGISTER(FrictionLaw,
                           ExponentialFriction,
                           "exponential",
                           "the paper's slip weakening, eq. (90): mu(s) = "
                           "(a - b) exp(-alpha s) + b.");


  void
  ExpressionFriction::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Function expression",
                      "0.5",
                      Patterns::Anything(),
                      "mu(s), a function of the slip rate s (m/s) in "
                      "muparser syntax.");
    prm.declare_entry("Function constants",
                      "",
                      Patterns::Anything(),
                      "Constants of the expression, as name=value pairs "
                      "separated by commas.");
  }

  void
  ExpressionFriction::parse_parameters(ParameterHandler &prm)
  {
    initialize(prm.get("Function expression"), prm.get("Function constants"));
  }

  DYNAMIC_CONTACT_REGISTER(FrictionLaw,
                           ExpressionFriction,
                           "expression",
                           "mu(s) given by Function expression.");


  std::string
  ConstantFriction::description() const
  {
    std::ostringstream s;
    s << "mu = " << mu;
    return s.str();
  }


  double
  ExponentialFriction::value(const double s) const
  {
    return (a - b) * std::exp(-alpha * s) + b;
  }

  double
  ExponentialFriction::derivative(const double s) const
  {
    return -alpha * (a - b) * std::exp(-alpha * s);
  }

  std::string
  ExponentialFriction::description() const
  {
    std::ostringstream s;
    s << "mu(s) = (" << a << " - " << b << ") exp(-" << alpha << " s) + " << b;
    return s.str();
  }


  ExpressionFriction::ExpressionFriction()
  {
    initialize("0.5", "");
  }


  ExpressionFriction::ExpressionFriction(const std::string &expression,
                                         const std::string &constants)
  {
    initialize(expression, constants);
  }


  void
  ExpressionFriction::initialize(const std::string &expression,
                                 const std::string &constants)
  {
    this->expression = expression;
    parser           = std::make_unique<FunctionParser<1>>(1);
    std::map<std::string, double> constant_map;
    for (const auto &pair : Utilities::split_string_list(constants, ','))
      {
        const auto terms = Utilities::split_string_list(pair, '=');
        AssertThrow(terms.size() == 2,
                    ExcMessage("Friction/Expression/Function constants: '" +
                               pair + "' is not of the form name=value."));
        try
          {
            constant_map[terms[0]] = Utilities::string_to_double(terms[1]);
          }
        catch (const std::exception &)
          {
            AssertThrow(false,
                        ExcMessage("Friction/Expression/Function constants: '" +
                                   terms[1] + "' is not a number."));
          }
      }
    try
      {
        const SilenceStderr silence;
        parser->initialize("s", expression, constant_map);
        parser->value(Point<1>(0.));
      }
    catch (const std::exception &e)
      {
        AssertThrow(
          false,
          ExcMessage("Friction/Expression/Function expression: cannot parse '" +
                     expression + "': " + expression_error_message(e)));
      }
  }

  double
  ExpressionFriction::value(const double s) const
  {
    return parser->value(Point<1>(s));
  }

  double
  ExpressionFriction::derivative(const double s) const
  {
    const double h = 1e-6 * std::max(s, velocity_scale);
    if (s >= h)
      return (value(s + h) - value(s - h)) / (2 * h);
    // Near s = 0, one-sided and of second order too.
    return (-3 * value(s) + 4 * value(s + h) - value(s + 2 * h)) / (2 * h);
  }

  void
  ExpressionFriction::set_slip_rate_window(const double s_max)
  {
    // The range of mu and its steepest slope on the window (sampled).
    const auto s  = sample_points(s_max);
    double     lo = value(0.), hi = lo, slope = 0;
    double     mu_last = lo;
    for (unsigned int i = 1; i < s.size(); ++i)
      {
        const double mu = value(s[i]);
        lo              = std::min(lo, mu);
        hi              = std::max(hi, mu);
        if (s[i] > s[i - 1] && measurable(mu_last, mu))
          slope = std::max(slope, std::abs(mu - mu_last) / (s[i] - s[i - 1]));
        mu_last = mu;
      }
    velocity_scale = (slope > 0 && std::isfinite(slope) && hi > lo) ?
                       std::min(s_max, (hi - lo) / slope) :
                       s_max;
  }

  bool
  ExpressionFriction::is_constant() const
  {
    // Constant exactly when the slip rate s does not occur in the
    // expression as a name of its own (sampling mu at a few rates would
    // take 0.6 + 0.1*(s > 200) for a constant and run one pass only).
    const auto name_char = [](const char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    };
    for (std::size_t i = 0; i < expression.size(); ++i)
      if (expression[i] == 's' && (i == 0 || !name_char(expression[i - 1])) &&
          (i + 1 == expression.size() || !name_char(expression[i + 1])))
        return false;
    return true;
  }

  std::string
  ExpressionFriction::description() const
  {
    return "mu(s) = " + expression;
  }


  double
  SlipLength::end_state(const FrictionLaw &law,
                        const double       m,
                        const double       s,
                        const TimeScheme  &scheme) const
  {
    const double mu = law.value(s);
    if (!active())
      return mu;
    return mu + (m - mu) * std::exp(-scheme.time_step() * (s + v_ref) / L);
  }

  std::pair<double, double>
  SlipLength::step_coefficient(const FrictionLaw &law,
                               const double       m,
                               const double       s,
                               const TimeScheme  &scheme) const
  {
    const double mu = law.value(s), dmu = law.derivative(s);
    if (!active())
      return {mu, dmu};
    const double k  = scheme.time_step();
    const double E  = std::exp(-k * (s + v_ref) / L);
    const double th = scheme.effective_derivative();
    return {scheme.weighted(mu + (m - mu) * E, m),
            th * ((1 - E) * dmu - (m - mu) * E * k / L)};
  }

  double
  SlipLength::step_lipschitz_constant(const double      lipschitz,
                                      const double      mu_max,
                                      const TimeScheme &scheme) const
  {
    // d mu_e/ds >= -theta ((1 - E) lipschitz + E mu_max k/L), a convex
    // combination (m - mu(s) <= mu_max: 0 <= mu <= mu_max, m the same).
    if (!active())
      return lipschitz;
    return std::max(lipschitz, mu_max * scheme.time_step() / L);
  }

  std::string
  SlipLength::description() const
  {
    std::ostringstream s;
    s << "slip length L = " << L << ", reference slip rate v* = " << v_ref;
    return s.str();
  }
} // namespace DynamicContact
