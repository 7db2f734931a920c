#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/laws/well_posedness.h>
#include <dynamic_contact/parameters/well_posedness_report.h>

namespace DynamicContact
{
  template <int dim>
  std::string
  well_posedness_report(const RunParameters &parameters)
  {
    const auto &friction = parameters.friction;
    if (!friction.law || friction.law->is_constant())
      return "";
    const KelvinVoigtMaterial<dim> material(parameters.material);
    WellPosedness::Data            data;
    data.weakening =
      friction.law->one_sided_lipschitz_constant(friction.maximum_slip_rate);
    data.normal_stress      = parameters.foundation.law->pressure_bound();
    data.density            = parameters.material.density;
    data.shear_wave_speed   = parameters.material.shear_wave_speed();
    data.viscous_coercivity = material.viscous_coercivity();
    data.end_time           = parameters.time.end_time;
    data.slip_length        = friction.slip_length.active();
    std::string report      = WellPosedness(data).report();
    if (friction.slip_length.active())
      report += "    slip length (Friction/Slip length): the coefficient "
                "follows mu(s) over a slip, not at once; its instantaneous "
                "weakening is 0, so condition (a) does not forbid "
                "convergence, and the theorems do not cover the state law "
                "(doc/theory.md section 1.6)\n";
    return report;
  }


  template std::string
  well_posedness_report<2>(const RunParameters &);
  template std::string
  well_posedness_report<3>(const RunParameters &);
} // namespace DynamicContact
