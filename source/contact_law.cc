#include <dynamic_contact/contact_law.h>

namespace DynamicContact
{
  const char *
  to_string(const ContactState state)
  {
    switch (state)
      {
        case ContactState::free:
          return "free";
        case ContactState::stick:
          return "stick";
        case ContactState::slip:
          return "slip";
      }
    return "?";
  }


  NormalResponse
  normal_response(const Foundation &foundation,
                  const double      u_nu,
                  const double      w_nu,
                  const double      k)
  {
    const CappedRamp &p = foundation.compliance();
    const CappedRamp &q = foundation.damping();
    NormalResponse    r;
    r.u_nu                 = u_nu;
    r.w_nu                 = w_nu;
    r.compliance_active    = p.active(u_nu);
    r.compliance_saturated = p.saturated(u_nu);
    const bool damping     = foundation.damping_acts(u_nu);
    r.damping_active       = damping && q.active(w_nu);
    r.damping_saturated    = damping && q.saturated(w_nu);
    r.pressure             = foundation.pressure(u_nu, w_nu);
    r.dpressure_dw =
      k * p.derivative(u_nu) + (damping ? q.derivative(w_nu) : 0.);
    return r;
  }
} // namespace DynamicContact
