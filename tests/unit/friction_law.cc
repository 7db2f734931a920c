// The friction coefficient mu(s) of the slip rate (doc/theory.md section 1,
// eq. (90)): constant, exponential (a - b) exp(-alpha s) + b, and a
// muparser expression in s; values by hand, derivatives against central
// differences, is_constant, the one-sided Lipschitz constant
// max(0, -min mu'), check_nonnegative, FrictionLaw::create and its errors;
// the slip length's state law (SlipLength).

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/laws/friction_law.h>

#include "test_tools.h"

using namespace DynamicContact;
using test_tools::check;
using test_tools::close;
using test_tools::digits;
using test_tools::out;

namespace
{
  /**
   * FrictionLaw::create for Friction/Law = @p law from the entries the
   * laws declare (mu = 0.4, a = 1, b = 0.5, alpha = 2000, expression
   * 0.5 + 0.5 exp(-10 s)), with @p entries ("Subsection/Entry", value) set
   * on top.
   */
  std::unique_ptr<FrictionLaw>
  create(const std::string                                      &law,
         const std::vector<std::pair<std::string, std::string>> &entries = {})
  {
    dealii::ParameterHandler prm;
    prm.enter_subsection("Friction");
    FrictionLaw::declare_parameters(prm);
    prm.set("Law", law);
    std::vector<std::pair<std::string, std::string>> all = {
      {"Constant/Coefficient", "0.4"},
      {"Exponential/Static coefficient", "1"},
      {"Exponential/Dynamic coefficient", "0.5"},
      {"Exponential/Decay rate", "2000"},
      {"Expression/Function expression", "0.5 + 0.5*exp(-10*s)"}};
    all.insert(all.end(), entries.begin(), entries.end());
    for (const auto &[path, value] : all)
      {
        const auto slash = path.find('/');
        prm.enter_subsection(path.substr(0, slash));
        prm.set(path.substr(slash + 1), value);
        prm.leave_subsection();
      }
    auto object = FrictionLaw::create(prm);
    prm.leave_subsection();
    return object;
  }

  /** create(@p law), checked (message @p what) to make a @p Law. */
  template <class Law>
  std::unique_ptr<FrictionLaw>
  create_checked(const std::string &law, const std::string &what)
  {
    auto object = create(law);
    check(object != nullptr && dynamic_cast<Law *>(object.get()), what);
    return object;
  }

  /** max |mu'(s) - central difference| / max(1, |mu'(s)|) over @p points. */
  double
  derivative_error(const FrictionLaw &law, const std::vector<double> &points)
  {
    double worst = 0;
    for (const double s : points)
      {
        const double h  = 1e-4 * s; // s > 0
        const double fd = (law.value(s + h) - law.value(s - h)) / (2 * h);
        worst           = std::max(worst,
                         std::abs(fd - law.derivative(s)) /
                           std::max(1., std::abs(law.derivative(s))));
      }
    return worst;
  }

  /** The message of the exception @p f throws, or "" if none. */
  template <typename F>
  std::string
  thrown_message(const F &f, bool &is_deal_ii_exception)
  {
    is_deal_ii_exception = false;
    try
      {
        f();
      }
    catch (const std::exception &e)
      {
        is_deal_ii_exception =
          (dynamic_cast<const dealii::ExceptionBase *>(&e) != nullptr);
        return error_message(e);
      }
    return "";
  }

  /** mu and mu' at a slip rate, by hand. */
  struct Row
  {
    double s, value, derivative;
  };

  /**
   * Print mu and mu' (to @p derivative_digits digits; -0 as 0) at the rows'
   * slip rates and check them against the values by hand: mu to 1e-9, mu'
   * to @p derivative_tolerance.
   */
  void
  check_values(const FrictionLaw      &law,
               const std::vector<Row> &rows,
               const unsigned int      derivative_digits,
               const double            derivative_tolerance)
  {
    for (const Row &row : rows)
      {
        out() << "s = " << digits(row.s, 6)
              << "  mu = " << digits(law.value(row.s), 6) << "  mu' = "
              << digits(law.derivative(row.s) + 0., derivative_digits)
              << std::endl;
        check(std::abs(law.value(row.s) - row.value) <= 1e-9 &&
                std::abs(law.derivative(row.s) - row.derivative) <=
                  derivative_tolerance,
              "mu and mu' at s = " + digits(row.s, 3));
      }
  }

  bool
  contains(const std::string &text, const std::string &part)
  {
    return text.find(part) != std::string::npos;
  }


  void
  test_constant()
  {
    out() << "--- constant mu = 0.4" << std::endl;
    const auto law = create_checked<ConstantFriction>(
      "constant", "create(constant) is a ConstantFriction");
    check(law->value(0.) == 0.4 && law->value(1.) == 0.4 &&
            law->value(1e3) == 0.4,
          "mu(0) = mu(1) = mu(1000) = 0.4");
    check(law->derivative(0.) == 0 && law->derivative(2.) == 0, "mu' = 0");
    check(law->is_constant(), "is_constant");
    check(law->one_sided_lipschitz_constant(1.) == 0,
          "one-sided Lipschitz constant 0");
    check(law->FrictionLaw::one_sided_lipschitz_constant(1.) == 0,
          "sampled one-sided Lipschitz constant 0");
    bool deal_ii;
    check(thrown_message([&] { law->check_nonnegative(10.); }, deal_ii).empty(),
          "check_nonnegative passes");
    out() << law->description() << std::endl;
    check(law->description() == "mu = 0.4", "description");
  }


  void
  test_exponential()
  {
    out() << "--- exponential (a - b) exp(-alpha s) + b, a = 1, b = 0.5, "
             "alpha = 2000"
          << std::endl;
    const auto law = create_checked<ExponentialFriction>(
      "exponential", "create(exponential) is an ExponentialFriction");
    // By hand: 0.5 exp(-2) = 0.0676676416, 0.5 exp(-0.2) = 0.409365377.
    check_values(*law,
                 {{0., 1., -1000.},
                  {1e-4, 0.909365377, -818.730753},
                  {1e-3, 0.567667642, -135.335283},
                  {1., 0.5, 0.}},
                 6,
                 1e-6);
    check(derivative_error(*law, {1e-5, 1e-4, 5e-4, 1e-3, 3e-3, 0.01}) <= 1e-6,
          "mu' = central difference to 1e-6 at 6 points");
    check(!law->is_constant(), "not is_constant");
    check(ExponentialFriction(0.5, 0.5, 2000.).is_constant() &&
            ExponentialFriction(1., 0.5, 0.).is_constant(),
          "is_constant for a = b or alpha = 0");
    check(law->one_sided_lipschitz_constant(1.) == 1000.,
          "one-sided Lipschitz constant alpha (a - b) = 1000");
    const double sampled = law->FrictionLaw::one_sided_lipschitz_constant(1.);
    out() << "sampled one-sided Lipschitz constant " << digits(sampled, 4)
          << std::endl;
    check(close(sampled, 1000., 1e-4),
          "sampled one-sided Lipschitz constant = alpha (a - b) to 1e-4");
    const ExponentialFriction other(0.6, 0.2, 3.);
    check(close(other.one_sided_lipschitz_constant(5.), 1.2, 1e-15) &&
            close(other.FrictionLaw::one_sided_lipschitz_constant(5.),
                  1.2,
                  1e-4),
          "a = 0.6, b = 0.2, alpha = 3: one-sided Lipschitz constant 1.2");
    bool deal_ii;
    check(thrown_message([&] { law->check_nonnegative(10.); }, deal_ii).empty(),
          "check_nonnegative passes");
  }


  void
  test_expression()
  {
    out() << "--- expression 0.5 + 0.5*exp(-10*s)" << std::endl;
    const auto law = create_checked<ExpressionFriction>(
      "expression", "create(expression) is an ExpressionFriction");
    // By hand: 0.5 exp(-1) = 0.183939721, 0.5 exp(-0.5) = 0.303265330.
    check_values(*law,
                 {{0., 1., -5.},
                  {0.05, 0.803265330, -3.03265330},
                  {0.1, 0.683939721, -1.83939721},
                  {10., 0.5, 0.}},
                 4,
                 1e-5);
    check(derivative_error(*law, {0.01, 0.05, 0.1, 0.3, 1.}) <= 1e-6,
          "mu' = central difference to 1e-6 at 5 points");
    check(!law->is_constant(), "not is_constant");
    const double lipschitz = law->one_sided_lipschitz_constant(1.);
    out() << "one-sided Lipschitz constant " << digits(lipschitz, 4)
          << std::endl;
    check(close(lipschitz, 5., 1e-4),
          "one-sided Lipschitz constant -mu'(0) = 5 (sampled) to 1e-4");
    bool deal_ii;
    check(thrown_message([&] { law->check_nonnegative(10.); }, deal_ii).empty(),
          "check_nonnegative passes");
    out() << law->description() << std::endl;

    // Constants, and a law that does not depend on s.
    const ExpressionFriction with_constants("a*exp(-alpha*s) + b",
                                            "a=0.3, b=0.2, alpha=4");
    check(std::abs(with_constants.value(0.) - 0.5) <= 1e-15 &&
            std::abs(with_constants.value(0.25) - 0.310363832) <= 1e-9,
          "constants a=0.3, b=0.2, alpha=4: mu(0) = 0.5, mu(0.25) = "
          "0.3 exp(-1) + 0.2");
    const ExpressionFriction constant("0.3", "");
    check(constant.is_constant() && constant.value(7.) == 0.3 &&
            constant.one_sided_lipschitz_constant(1.) == 0 &&
            constant.derivative(0.5) == 0,
          "expression 0.3: is_constant, mu' = 0, Lipschitz constant 0");
    const ExpressionFriction step("0.6 + 0.1*(s > 200)", "");
    check(!step.is_constant() && step.value(300.) == 0.7,
          "expression 0.6 + 0.1*(s > 200): not constant (it changes only "
          "beyond s = 200)");
    const ExpressionFriction names("sin(0.5) + slope*0", "slope=2");
    check(names.is_constant(),
          "expression sin(0.5) + slope*0: constant (s only inside other "
          "names)");
    const ExpressionFriction increasing("0.3 + 0.1*s", "");
    check(!increasing.is_constant() &&
            increasing.one_sided_lipschitz_constant(1.) == 0,
          "increasing expression 0.3 + 0.1 s: Lipschitz constant 0");

    out() << "--- expression 0.5 - s" << std::endl;
    const ExpressionFriction negative("0.5 - s", "");
    check(close(negative.one_sided_lipschitz_constant(1.), 1., 1e-4),
          "0.5 - s: one-sided Lipschitz constant 1");
    check(
      thrown_message([&] { negative.check_nonnegative(0.4); }, deal_ii).empty(),
      "0.5 - s: check_nonnegative(0.4) passes");
    const std::string message =
      thrown_message([&] { negative.check_nonnegative(1.); }, deal_ii);
    check(!message.empty() && deal_ii,
          "0.5 - s: check_nonnegative(1) throws a deal.II exception");
    check(contains(message, "Friction"),
          "0.5 - s: the message names \"Friction\"");
    const ExpressionFriction not_a_number("sqrt(s - 2)", "");
    check(contains(thrown_message([&] { not_a_number.check_nonnegative(1.); },
                                  deal_ii),
                   "Friction"),
          "sqrt(s - 2): check_nonnegative(1) throws (not finite)");
  }


  void
  test_create_and_errors()
  {
    out() << "--- create and errors" << std::endl;
    check(create("none") == nullptr, "create(none) = nullptr");

    bool deal_ii;
    for (const std::string expression : {"0.5 +* s", "0.5 + x", "exp(-s"})
      {
        const std::string message = thrown_message(
          [&] {
            create("expression",
                   {{"Expression/Function expression", expression}});
          },
          deal_ii);
        check(!message.empty() && deal_ii &&
                contains(message, "Friction/Expression/Function expression"),
              "create('" + expression +
                "') throws, naming \"Friction/Expression/Function "
                "expression\"");
      }
    for (const std::string constants : {"a:0.3", "a=x"})
      {
        const std::string message = thrown_message(
          [&] {
            create("expression",
                   {{"Expression/Function expression", "a + 0*s"},
                    {"Expression/Function constants", constants}});
          },
          deal_ii);
        check(!message.empty() && deal_ii &&
                contains(message, "Friction/Expression/Function constants"),
              "constants '" + constants +
                "' throw, naming \"Friction/Expression/Function "
                "constants\"");
      }
  }


  /**
   * SlipLength (doc/theory.md section 1.6): L = 0 is the law; the state's
   * update is the exact solution at a constant slip rate (one step of k
   * equals eight of k/8); theta = 1/2 acts with the mean of the state over
   * the step; mu_e lies between m and mu(s) at any k; d mu_e/ds against
   * central differences; -d mu_e/ds below step_lipschitz_constant().
   */
  void
  test_slip_length()
  {
    out() << "--- slip length L = 0.01, v* = 0.001, exponential a = 1, "
             "b = 0.5, alpha = 2000"
          << std::endl;
    const ExponentialFriction law(1., 0.5, 2000.);
    const SlipLength          none, slip(0.01, 0.001);
    const TimeScheme          euler(1e-3, 1.), half(1e-3, 0.5);
    check(!none.active() && slip.active(), "active() only for L > 0");
    const auto plain = none.step_coefficient(law, 0.7, 2e-4, euler);
    check(plain.first == law.value(2e-4) &&
            plain.second == law.derivative(2e-4) &&
            none.end_state(law, 0.7, 2e-4, euler) == law.value(2e-4),
          "L = 0: mu_e = mu(s), its derivative mu'(s), the state mu(s)");

    const double s = 2e-3, m0 = 1., mu_s = law.value(s);
    const double exact =
      mu_s + (m0 - mu_s) * std::exp(-1e-3 * (s + 0.001) / 0.01);
    double m = m0;
    for (unsigned int i = 0; i < 8; ++i)
      m = slip.end_state(law, m, s, TimeScheme(1e-3 / 8, 1.));
    out() << "state after k = 1e-3 at s = 2e-3 from 1: "
          << digits(slip.end_state(law, m0, s, euler), 12) << ", closed form "
          << digits(exact, 12) << std::endl;
    check(close(slip.end_state(law, m0, s, euler), exact, 1e-14) &&
            close(m, exact, 1e-13),
          "the update is exact at a constant slip rate: one step of k "
          "equals the closed form and eight steps of k/8 (1e-13)");
    check(close(slip.step_coefficient(law, m0, s, half).first,
                0.5 * (m0 + exact),
                1e-14),
          "theta = 1/2 acts with the mean of the state at both ends");

    bool   between          = true;
    double worst_derivative = 0, worst_bound = 0;
    for (const double k : {1e-9, 1e-6, 1e-3, 1., 1e3})
      for (const double theta : {0.5, 0.75, 1.})
        for (const double start : {0.5, 0.8, 1.})
          for (const double rate : {0., 1e-5, 2e-4, 1e-3, 0.1, 10.})
            {
              const TimeScheme scheme(k, theta);
              const auto   e  = slip.step_coefficient(law, start, rate, scheme);
              const double lo = std::min(start, law.value(rate)),
                           hi = std::max(start, law.value(rate));
              between =
                between && e.first >= lo - 1e-15 && e.first <= hi + 1e-15;
              if (rate > 0)
                {
                  const double h = 1e-4 * rate;
                  const double fd =
                    (slip.step_coefficient(law, start, rate + h, scheme).first -
                     slip.step_coefficient(law, start, rate - h, scheme)
                       .first) /
                    (2 * h);
                  worst_derivative =
                    std::max(worst_derivative,
                             std::abs(fd - e.second) /
                               std::max(1., std::abs(e.second)));
                }
              const double bound =
                slip.step_lipschitz_constant(law.one_sided_lipschitz_constant(
                                               10.),
                                             law.largest_value(10.),
                                             scheme);
              worst_bound = std::max(worst_bound, -e.second / bound);
            }
    check(between, "mu_e lies between m and mu(s) at k from 1e-9 to 1e3");
    check(worst_derivative <= 1e-6,
          "d mu_e/ds against central differences (largest difference "
          "below 1e-6 max(1, |d mu_e/ds|))");
    check(worst_bound <= 1,
          "-d mu_e/ds <= step_lipschitz_constant() at every sample");
    out() << slip.description() << std::endl;
  }
} // namespace


int
main(int argc, char *argv[])
{
  return test_tools::run_tests(argc,
                               argv,
                               {test_constant,
                                test_exponential,
                                test_expression,
                                test_create_and_errors,
                                test_slip_length});
}
