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
  /** mu = Value: the constant law again, under another name. */
  class FixedFriction : public FrictionLaw
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Value", "0.5", Patterns::Double(0), "mu.");
    }
    void
    parse_parameters(ParameterHandler &prm) override
    {
      mu = prm.get_double("Value");
    }
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
    description() const override
    {
      return "mu = " + std::to_string(mu) + " (test law)";
    }

  private:
    double mu = 0.5;
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
  class LinearLaw : public Interface
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Coefficient", "5e9", Patterns::Double(0), "c.");
    }
    void
    parse_parameters(ParameterHandler &prm) override
    {
      c = prm.get_double("Coefficient");
    }
    double
    value(const double r) const override
    {
      return c * std::max(r, 0.);
    }
    double
    derivative(const double r) const override
    {
      return r > 0 ? c : 0.;
    }
    double
    primitive(const double r) const override
    {
      return r > 0 ? 0.5 * c * r * r : 0.;
    }
    bool
    is_zero() const override
    {
      return c == 0;
    }

  private:
    double c = 5e9;
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
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  // The entries that choose accept the new names (their patterns list
  // them) and document them.
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

  const std::vector<std::string> columns = {"normal_force",
                                            "tangential_force",
                                            "kinetic_energy",
                                            "elastic_energy",
                                            "dofs"};

  compare("friction law 'fixed' = 'constant'",
          series("fixed", {"Friction/Law=fixed", "Friction/Fixed/Value=0.4"}),
          series("constant",
                 {"Friction/Law=constant",
                  "Friction/Constant/Coefficient=0.4"}),
          columns,
          0.);

  compare("normal law 'linear' = capped ramp with an unreached cap",
          series("linear",
                 {"Foundation/Normal compliance/Law=linear",
                  "Foundation/Normal compliance/Linear/Coefficient=5e9"}),
          series("ramp",
                 {"Foundation/Normal compliance/Capped ramp/Stiffness=5e9",
                  "Foundation/Normal compliance/Capped ramp/Cap=1e17"}),
          columns,
          1e-10);

  {
    const auto ramp =
      series("damping-ramp",
             {"Foundation/Normal damping/Capped ramp/Coefficient=1e8",
              "Foundation/Normal damping/Capped ramp/Cap=1e17"});
    compare("damping law 'linear' = capped ramp with an unreached cap",
            series("linear-damping",
                   {"Foundation/Normal damping/Law=linear",
                    "Foundation/Normal damping/Linear/Coefficient=1e8"}),
            ramp,
            columns,
            1e-10);
    // The run takes its damping from the law: ten times its coefficient
    // changes the series.
    check(test_tools::largest_difference(
            series("linear-damping-1e9",
                   {"Foundation/Normal damping/Law=linear",
                    "Foundation/Normal damping/Linear/Coefficient=1e9"}),
            ramp) > 1e-6,
          "damping law 'linear': its coefficient acts");
  }

  compare("strategy 'everywhere' (levels 0 to 1) = Global refinements = 1",
          series("everywhere",
                 {"Mesh refinement/Strategy=everywhere",
                  "Mesh refinement/Minimum level=0",
                  "Mesh refinement/Maximum level=1"}),
          series("global", {"Geometry/Global refinements=1"}),
          columns,
          1e-10);
}
