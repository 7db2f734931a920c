#include <deal.II/base/exceptions.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/laws/foundation.h>

#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>

namespace DynamicContact
{
  namespace
  {
    /** The entries of a capped ramp law: its slope's, and the cap's. */
    struct RampEntries
    {
      std::string slope;
      std::string slope_default;
      std::string slope_documentation;
      std::string cap_documentation;
      /** The path of the subsection (errors name it). */
      std::string path;
    };

    /** The entries of CappedRampLaw<Interface>. */
    template <class Interface>
    RampEntries
    ramp_entries()
    {
      if constexpr (std::is_same_v<Interface, NormalLaw>)
        return {"Stiffness",
                "5e9",
                "c_nu in p(r) = min(c_nu r_+, c3) (Pa/m), >= 0.",
                "c3, the bound of p (Pa), > 0. The paper's 1e8 GPa/m is "
                "not reached.",
                "Foundation/Normal compliance/Capped ramp/"};
      else
        return {"Coefficient",
                "1e8",
                "d_nu in q(r) = min(d_nu r_+, c4) (Pa s/m), >= 0. Zero "
                "switches the damped response off.",
                "c4, the bound of q (Pa), > 0.",
                "Foundation/Normal damping/Capped ramp/"};
    }
  } // namespace


  template <class Interface>
  void
  CappedRampLaw<Interface>::declare_parameters(ParameterHandler &prm)
  {
    const RampEntries e = ramp_entries<Interface>();
    prm.declare_entry(e.slope,
                      e.slope_default,
                      Patterns::Double(),
                      e.slope_documentation);
    prm.declare_entry("Cap", "1e17", Patterns::Double(), e.cap_documentation);
  }


  template <class Interface>
  void
  CappedRampLaw<Interface>::parse_parameters(ParameterHandler &prm)
  {
    const RampEntries e     = ramp_entries<Interface>();
    const double      slope = prm.get_double(e.slope);
    const double      cap   = prm.get_double("Cap");
    AssertThrow(std::isfinite(slope) && slope >= 0,
                ExcMessage(e.path + e.slope + " must be >= 0, got " +
                           str(slope) + "."));
    AssertThrow(std::isfinite(cap) && cap > 0,
                ExcMessage(e.path + "Cap must be positive, got " + str(cap) +
                           "."));
    ramp = CappedRamp(slope, cap);
  }


  template class CappedRampLaw<NormalLaw>;
  template class CappedRampLaw<DampingLaw>;

  DYNAMIC_CONTACT_REGISTER(NormalLaw,
                           CappedRampLaw<NormalLaw>,
                           "capped ramp",
                           "the paper's p(r) = min(c_nu r_+, c3), eq. (88).");
  DYNAMIC_CONTACT_REGISTER(DampingLaw,
                           CappedRampLaw<DampingLaw>,
                           "capped ramp",
                           "the paper's q(r) = min(d_nu r_+, c4), eq. (88).");


  namespace
  {
    /**
     * Declare the entry Law of the registered @p Interface laws ('capped
     * ramp' by default), whose text begins with @p what, and a subsection
     * per law.
     */
    template <class Interface>
    void
    declare_law(ParameterHandler &prm, const std::string &what)
    {
      PluginRegistry<Interface>::instance().declare_parameters(
        prm,
        "Law",
        "capped ramp",
        what + ", with its parameters in the subsection of the law's name:");
    }
  } // namespace


  void
  Foundation::declare_parameters(ParameterHandler &prm)
  {
    {
      const ScopedSubsection section(prm, "Normal compliance");
      declare_law<NormalLaw>(
        prm, "The normal compliance p(u_nu) of the penetration u_nu");
    }

    const ScopedSubsection section(prm, "Normal damping");
    declare_law<DampingLaw>(
      prm, "The normal damped response q(u'_nu) of the normal velocity");
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
