#include <deal.II/base/exceptions.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/laws/foundation.h>

#include <cmath>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    /** Declare a capped ramp's slope entry @p slope and its cap. */
    void
    declare_ramp(ParameterHandler  &prm,
                 const std::string &slope,
                 const std::string &slope_default,
                 const std::string &slope_documentation,
                 const std::string &cap_documentation)
    {
      prm.declare_entry(slope,
                        slope_default,
                        Patterns::Double(),
                        slope_documentation);
      prm.declare_entry("Cap", "1e17", Patterns::Double(), cap_documentation);
    }

    /** The capped ramp of the entries (@p path names them in errors). */
    CappedRamp
    parse_ramp(ParameterHandler  &prm,
               const std::string &slope_entry,
               const std::string &path)
    {
      const double slope = prm.get_double(slope_entry);
      const double cap   = prm.get_double("Cap");
      AssertThrow(std::isfinite(slope) && slope >= 0,
                  ExcMessage(path + slope_entry + " must be >= 0, got " +
                             str(slope) + "."));
      AssertThrow(std::isfinite(cap) && cap > 0,
                  ExcMessage(path + "Cap must be positive, got " + str(cap) +
                             "."));
      return CappedRamp(slope, cap);
    }
  } // namespace


  template <>
  void
  CappedRampLaw<NormalLaw>::declare_parameters(ParameterHandler &prm)
  {
    declare_ramp(prm,
                 "Stiffness",
                 "5e9",
                 "c_nu in p(r) = min(c_nu r_+, c3) (Pa/m), >= 0.",
                 "c3, the bound of p (Pa), > 0. The paper's 1e8 GPa/m is "
                 "not reached.");
  }

  template <>
  void
  CappedRampLaw<NormalLaw>::parse_parameters(ParameterHandler &prm)
  {
    ramp =
      parse_ramp(prm, "Stiffness", "Foundation/Normal compliance/Capped ramp/");
  }

  template <>
  void
  CappedRampLaw<DampingLaw>::declare_parameters(ParameterHandler &prm)
  {
    declare_ramp(prm,
                 "Coefficient",
                 "1e8",
                 "d_nu in q(r) = min(d_nu r_+, c4) (Pa s/m), >= 0. Zero "
                 "switches the damped response off.",
                 "c4, the bound of q (Pa), > 0.");
  }

  template <>
  void
  CappedRampLaw<DampingLaw>::parse_parameters(ParameterHandler &prm)
  {
    ramp =
      parse_ramp(prm, "Coefficient", "Foundation/Normal damping/Capped ramp/");
  }

  DYNAMIC_CONTACT_REGISTER(NormalLaw,
                           CappedRampLaw<NormalLaw>,
                           "capped ramp",
                           "the paper's p(r) = min(c_nu r_+, c3), eq. (88).");
  DYNAMIC_CONTACT_REGISTER(DampingLaw,
                           CappedRampLaw<DampingLaw>,
                           "capped ramp",
                           "the paper's q(r) = min(d_nu r_+, c4), eq. (88).");


  void
  Foundation::declare_parameters(ParameterHandler &prm)
  {
    {
      const ScopedSubsection section(prm, "Normal compliance");
      PluginRegistry<NormalLaw>::instance().declare_parameters(
        prm,
        "Law",
        "capped ramp",
        "The normal compliance p(u_nu) of the penetration u_nu, with its "
        "parameters in the subsection of the law's name:");
    }

    const ScopedSubsection section(prm, "Normal damping");
    PluginRegistry<DampingLaw>::instance().declare_parameters(
      prm,
      "Law",
      "capped ramp",
      "The normal damped response q(u'_nu) of the normal velocity, with "
      "its parameters in the subsection of the law's name:");
    prm.declare_entry(
      "Only in contact",
      "false",
      Patterns::Bool(),
      "false: q acts wherever the normal velocity is positive, as eq. (17) "
      "is written (a continuous law). true: q acts only where the body "
      "penetrates (u_nu > 0), a physical variant with a discontinuous law.");
  }


  Foundation
  Foundation::create(ParameterHandler &prm)
  {
    std::shared_ptr<const NormalLaw> p;
    {
      const ScopedSubsection section(prm, "Normal compliance");
      p = PluginRegistry<NormalLaw>::instance().create(prm.get("Law"), prm);
    }
    const ScopedSubsection            section(prm, "Normal damping");
    std::shared_ptr<const DampingLaw> q =
      PluginRegistry<DampingLaw>::instance().create(prm.get("Law"), prm);
    return Foundation(p, q, prm.get_bool("Only in contact"));
  }
} // namespace DynamicContact
