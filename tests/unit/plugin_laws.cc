// A new law or refinement strategy takes one class and one registration
// (doc/extending.md): this file adds a friction law, a law of the
// foundation (as normal compliance and as normal damping) and a refinement
// strategy of its own, chooses them in the parameter file, and checks that
// the runs use them: each gives the same time series as the built-in it
// mimics (constant friction, the capped ramp with a cap that is never
// reached, uniform refinement), and the new names are in the
// patterns of the entries that choose them.

#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/mesh/refinement_strategy.h>

#include "test_tools.h"

using namespace DynamicContact;
using test_tools::check;

namespace
{
  /**
   * What a law of one coefficient declares and parses: the entry
   * Law::entry, a number >= 0 (default Law::default_value).
   */
  template <class Law, class Interface>
  class OneCoefficient : public Interface
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(Law::entry,
                        Law::default_value,
                        Patterns::Double(0),
                        Law::documentation);
    }
    void
    parse_parameters(ParameterHandler &prm) override
    {
      coefficient = prm.get_double(Law::entry);
    }

  protected:
    double coefficient = std::stod(Law::default_value);
  };


  /** mu = Value: the constant law again, under another name. */
  class FixedFriction : public OneCoefficient<FixedFriction, FrictionLaw>
  {
  public:
    static constexpr const char *entry = "Value", *default_value = "0.5",
                                *documentation = "mu.";
    double
    value(const double) const override
    {
      return coefficient;
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
    description() const override
    {
      return "mu = " + std::to_string(coefficient) + " (test law)";
    }
  };
  DYNAMIC_CONTACT_REGISTER(FrictionLaw,
                           FixedFriction,
                           "fixed",
                           "a test law: mu = Value.");


  /**
   * p(r) = c r_+ (or q(r) = c r_+), without a cap; everything else from
   * ResponseLaw. One class for both laws of the foundation.
   */
  template <class Interface>
  class LinearLaw : public OneCoefficient<LinearLaw<Interface>, Interface>
  {
  public:
    static constexpr const char *entry = "Coefficient", *default_value = "5e9",
                                *documentation = "c.";
    double
    value(const double r) const override
    {
      return this->coefficient * std::max(r, 0.);
    }
    double
    derivative(const double r) const override
    {
      return r > 0 ? this->coefficient : 0.;
    }
    double
    primitive(const double r) const override
    {
      return r > 0 ? 0.5 * this->coefficient * r * r : 0.;
    }
    bool
    is_zero() const override
    {
      return this->coefficient == 0;
    }
  };
  DYNAMIC_CONTACT_REGISTER(NormalLaw,
                           LinearLaw<NormalLaw>,
                           "linear",
                           "a test law: p(r) = Coefficient r_+.");
  DYNAMIC_CONTACT_REGISTER(DampingLaw,
                           LinearLaw<DampingLaw>,
                           "linear",
                           "a test law: q(r) = Coefficient r_+.");


  /** Every cell asks for the finest level. */
  template <int dim>
  class Everywhere : public RefinementStrategy<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &)
    {}
    void
    parse_parameters(ParameterHandler &) override
    {}
    typename RefinementStrategy<dim>::Levels
    levels(const AdaptationContext<dim> &) const override
    {
      return [](const auto &, const unsigned int max_level) {
        return static_cast<int>(max_level);
      };
    }
  };
  DYNAMIC_CONTACT_REGISTER_STRATEGY(Everywhere,
                                    "everywhere",
                                    "a test strategy: the finest level "
                                    "everywhere.");


  std::vector<StepRecord<2>>
  series(const std::string &name, std::vector<std::string> overrides)
  {
    overrides.push_back("Output/Directory=output-" + name);
    overrides.push_back("Time/End time=0.25");
    return test_tools::run<2>(
             test_tools::scene("barboteu_danan_2016_small.prm"), overrides)
      ->time_series();
  }

  /** The largest difference of the columns over the steps (relative). */
  void
  compare(const std::string                &what,
          const std::vector<StepRecord<2>> &a,
          const std::vector<StepRecord<2>> &b,
          const std::vector<std::string>   &columns,
          const double                      tolerance)
  {
    check(a.size() == b.size() && a.size() > 10, what + ": same steps");
    double worst = 0;
    for (unsigned int n = 0; n < a.size(); ++n)
      for (const auto &column : columns)
        {
          const auto   q = test_tools::quantity<2>(column);
          const double x = q.of(a[n]), y = q.of(b[n]);
          worst = std::max(worst,
                           std::abs(x - y) /
                             std::max({std::abs(x), std::abs(y), 1e-300}));
        }
    check(worst <= tolerance,
          what + ": " + columns.front() + ", ... agree to " +
            test_tools::digits(tolerance, 1));
  }


  /**
   * The entries that choose accept the new names (their patterns list
   * them) and document them.
   */
  void
  check_names()
  {
    ParameterHandler prm;
    RunParameters::declare_parameters(prm, 2);
    for (const auto &[path, name] :
         std::vector<std::pair<std::string, std::string>>{
           {"Friction/Law", "fixed"},
           {"Foundation/Normal compliance/Law", "linear"},
           {"Foundation/Normal damping/Law", "linear"},
           {"Mesh refinement/Strategy", "everywhere"}})
      {
        const auto sections = test_tools::split(path, '/');
        for (unsigned int i = 0; i + 1 < sections.size(); ++i)
          prm.enter_subsection(sections[i]);
        bool accepted = true;
        try
          {
            prm.set(sections.back(), name);
          }
        catch (const std::exception &)
          {
            accepted = false;
          }
        for (unsigned int i = 0; i + 1 < sections.size(); ++i)
          prm.leave_subsection();
        check(accepted, path + " = " + name + " is accepted");
      }
  }


  /** A run of a new law or strategy (its name, its overrides). */
  struct Run
  {
    std::string              name;
    std::vector<std::string> overrides;
  };

  /**
   * The new law's run, the built-in's it must equal (to the tolerance);
   * if @p acting names a run, it must differ from the built-in's.
   */
  struct Comparison
  {
    std::string what;
    Run         new_law, built_in;
    double      tolerance;
    Run         acting;
    std::string acting_what;
  };
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_names();

  const std::vector<std::string> columns     = {"normal_force",
                                                "tangential_force",
                                                "kinetic_energy",
                                                "elastic_energy",
                                                "dofs"};
  const std::vector<Comparison>  comparisons = {
     {"friction law 'fixed' = 'constant'",
      {"fixed", {"Friction/Law=fixed", "Friction/Fixed/Value=0.4"}},
      {"constant",
       {"Friction/Law=constant", "Friction/Constant/Coefficient=0.4"}},
      0.,
      {},
      ""},
     {"normal law 'linear' = capped ramp with an unreached cap",
      {"linear",
       {"Foundation/Normal compliance/Law=linear",
        "Foundation/Normal compliance/Linear/Coefficient=5e9"}},
      {"ramp",
       {"Foundation/Normal compliance/Capped ramp/Stiffness=5e9",
        "Foundation/Normal compliance/Capped ramp/Cap=1e17"}},
      1e-10,
      {},
      ""},
     // The run takes its damping from the law: ten times its coefficient
     // changes the series.
     {"damping law 'linear' = capped ramp with an unreached cap",
      {"linear-damping",
       {"Foundation/Normal damping/Law=linear",
        "Foundation/Normal damping/Linear/Coefficient=1e8"}},
      {"damping-ramp",
       {"Foundation/Normal damping/Capped ramp/Coefficient=1e8",
        "Foundation/Normal damping/Capped ramp/Cap=1e17"}},
      1e-10,
      {"linear-damping-1e9",
       {"Foundation/Normal damping/Law=linear",
        "Foundation/Normal damping/Linear/Coefficient=1e9"}},
      "damping law 'linear': its coefficient acts"},
     {"strategy 'everywhere' (levels 0 to 1) = Global refinements = 1",
      {"everywhere",
       {"Mesh refinement/Strategy=everywhere",
        "Mesh refinement/Minimum level=0",
        "Mesh refinement/Maximum level=1"}},
      {"global", {"Geometry/Global refinements=1"}},
      1e-10,
      {},
      ""}};
  for (const Comparison &x : comparisons)
    {
      const auto built_in = series(x.built_in.name, x.built_in.overrides);
      compare(x.what,
              series(x.new_law.name, x.new_law.overrides),
              built_in,
              columns,
              x.tolerance);
      if (!x.acting.name.empty())
        check(test_tools::largest_difference(
                series(x.acting.name, x.acting.overrides), built_in) > 1e-6,
              x.acting_what);
    }
}
