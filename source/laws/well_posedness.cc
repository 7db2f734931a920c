#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/laws/well_posedness.h>

#include <cmath>
#include <limits>

namespace DynamicContact
{
  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();

    /** Three significant digits: the report's ratios. */
    std::string
    sig3(const double x)
    {
      return scientific(x, 2);
    }

    /** "holds by a factor 1/r" (r < 1) or "fails by a factor r". */
    std::string
    verdict(const double ratio)
    {
      return ratio < 1 ? "holds by a factor " + sig3(1 / ratio) :
                         "fails by a factor " + sig3(ratio);
    }

    /** "where p + q < X mu" for the critical stress X (in units of mu). */
    std::string
    below(const double critical_stress)
    {
      return "where p + q < " + sig3(critical_stress) + " mu";
    }
  } // namespace


  double
  WellPosedness::shear_modulus() const
  {
    return data.density * data.shear_wave_speed * data.shear_wave_speed;
  }


  double
  WellPosedness::relative_normal_stress() const
  {
    return data.normal_stress / shear_modulus();
  }


  double
  WellPosedness::radiation_ratio() const
  {
    if (data.weakening == 0)
      return 0.;
    return data.weakening * data.normal_stress /
           (data.density * data.shear_wave_speed);
  }


  double
  WellPosedness::radiation_critical_stress() const
  {
    // L S* = rho c_s, S*/mu = rho c_s/(L rho c_s^2) = 1/(L c_s).
    if (data.weakening == 0)
      return infinity;
    return 1. / (data.weakening * data.shear_wave_speed);
  }


  double
  WellPosedness::growth_exponent() const
  {
    if (data.weakening == 0)
      return 0.;
    const double weakening_stress = data.weakening * data.normal_stress;
    if (data.viscous_coercivity == 0 || !std::isfinite(weakening_stress))
      return infinity;
    return 2 * weakening_stress * weakening_stress * data.end_time /
           (data.density * data.viscous_coercivity);
  }


  double
  WellPosedness::growth_critical_stress() const
  {
    // 2 (L S*)^2 T = rho c2.
    if (data.weakening == 0)
      return infinity;
    return std::sqrt(data.density * data.viscous_coercivity /
                     (2 * data.end_time)) /
           (data.weakening * shear_modulus());
  }


  std::string
  WellPosedness::radiation_line() const
  {
    const std::string name = "    radiation damping, L S/(rho c_s)";
    if (data.weakening == 0)
      return name + " = 0 (no weakening): holds at any normal stress\n";
    if (!std::isfinite(data.normal_stress))
      return name + " < 1 " + below(radiation_critical_stress()) + "\n";
    const double r    = radiation_ratio();
    std::string  line = name + " = " + sig3(r) + ": " + verdict(r) +
                       " (below 1 " + below(radiation_critical_stress()) +
                       "): ";
    if (r < 1)
      return line + "the body's radiation damping outweighs the weakening, "
                    "steady sliding is stable\n";
    if (data.slip_length)
      return line + "the steady-sliding law outruns the body's radiation "
                    "damping; with the slip length the coefficient does not "
                    "weaken at once (last line)\n";
    if (data.viscous_coercivity == 0)
      return line + "with an elastic body the problem is ill-posed, friction "
                    "quantities will not converge under refinement\n";
    return line + "the weakening outruns the body's radiation damping, only "
                  "the viscosity bounds the growth of slip perturbations "
                  "(next line)\n";
  }


  std::string
  WellPosedness::viscosity_line() const
  {
    const std::string name =
      "    viscosity against the weakening (the paper's Remark 8)";
    if (data.viscous_coercivity == 0)
      return name + ": no viscosity (C = 0): the paper's existence and "
                    "uniqueness theorem does not apply\n";
    if (data.weakening == 0)
      return name + ", 2 (L S)^2 T/(rho c2) = 0 (no weakening): holds at any "
                    "normal stress\n";
    if (!std::isfinite(data.normal_stress))
      return name + ", 2 (L S)^2 T/(rho c2) < 1 " +
             below(growth_critical_stress()) + "\n";
    const double g    = growth_exponent();
    std::string  line = name + ", 2 (L S)^2 T/(rho c2) = " + sig3(g) + ": " +
                       verdict(g) + " (below 1 " +
                       below(growth_critical_stress()) + "): ";
    if (g <= 1)
      return line + "slip perturbations grow at most by a factor e over the "
                    "run, the paper's error estimate (Theorem 6) holds with a "
                    "moderate constant\n";
    if (radiation_ratio() < 1)
      return line +
             "the paper's estimate lets slip perturbations grow by up "
             "to exp(" +
             sig3(g) +
             ") over the run, a pessimistic bound here: the radiation "
             "damping keeps sliding stable\n";
    return line + "slip perturbations may grow by up to exp(" + sig3(g) +
           ") over the run, friction quantities will not converge at "
           "practical resolutions\n";
  }


  std::string
  WellPosedness::report() const
  {
    std::string heading = "  well-posedness (doc/theory.md section 1.5), "
                          "with L the largest weakening rate |mu'| and S";
    if (std::isfinite(data.normal_stress))
      heading += " = c3 + c4 = " + sig3(relative_normal_stress()) +
                 " mu the largest normal stress p + q the caps allow:\n";
    else
      heading += " the largest normal stress p + q: unbounded (a law of the "
                 "foundation has no cap), the conditions cannot be checked "
                 "a priori:\n";
    return heading + radiation_line() + viscosity_line();
  }
} // namespace DynamicContact
