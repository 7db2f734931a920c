// The deformable foundation of doc/theory.md section 1, eq. (88):
//   p(r) = min(c_nu r_+, c3),  q(r) = min(d_nu r_+, c4),  Pi(r) = int_0^r p,
// and the pressure p(u_nu) + q(w_nu), with and without "damping only in
// contact". Expected values are written out by hand for
//   c_nu = 2, c3 = 3 (kink at 1.5),  d_nu = 0.5, c4 = 0.25 (kink at 0.5).

#include <dynamic_contact/laws/foundation.h>

#include "test_tools.h"

using namespace DynamicContact;
using test_tools::check;
using test_tools::digits;
using test_tools::out;

namespace
{
  /** Composite Simpson rule for int_0^r f, n (even) panels. */
  template <typename F>
  double
  simpson(const F &f, const double r, const unsigned int n)
  {
    const double h   = r / n;
    double       sum = f(0.) + f(r);
    for (unsigned int i = 1; i < n; ++i)
      sum += (i % 2 == 1 ? 4. : 2.) * f(i * h);
    return sum * h / 3.;
  }

  bool
  near(const double a, const double b, const double tol)
  {
    return std::abs(a - b) <= tol;
  }

  /** The paper's foundation: capped ramps (c_nu, c3) and (d_nu, c4). */
  Foundation
  foundation_parameters(const double c_nu,
                        const double c3,
                        const double d_nu,
                        const double c4,
                        const bool   only_in_contact)
  {
    return Foundation(CappedRamp(c_nu, c3),
                      CappedRamp(d_nu, c4),
                      only_in_contact);
  }


  void
  test_ramp_values()
  {
    out() << "--- p(r) = min(2 r_+, 3): value, derivative, sets, primitive"
          << std::endl;
    const CappedRamp p(2., 3.);
    // r, value, derivative, active, saturated, primitive (by hand).
    struct Row
    {
      double r, value, derivative;
      bool   active, saturated;
      double primitive;
    };
    const std::vector<Row> rows = {
      {-1.0, 0., 0., false, false, 0.},
      {-1e-3, 0., 0., false, false, 0.},
      {0.0, 0., 0., false, false, 0.},
      {0.5, 1., 2., true, false, 0.25},
      {1.5, 3., 0., true, true, 2.25}, // the kink c3/c_nu
      {2.0, 3., 0., true, true, 3.75}, // 2.25 + 3 * 0.5
      {10., 3., 0., true, true, 27.75} // 2.25 + 3 * 8.5
    };
    for (const Row &row : rows)
      {
        out() << "r = " << digits(row.r, 6)
              << "  p = " << digits(p.value(row.r), 6)
              << "  p' = " << digits(p.derivative(row.r), 6)
              << "  active = " << p.active(row.r)
              << "  saturated = " << p.saturated(row.r)
              << "  Pi = " << digits(p.primitive(row.r), 6) << std::endl;
        const std::string at = " at r = " + digits(row.r, 6);
        check(near(p.value(row.r), row.value, 1e-14), "value" + at);
        check(near(p.derivative(row.r), row.derivative, 1e-14),
              "derivative" + at);
        check(p.active(row.r) == row.active, "active" + at);
        check(p.saturated(row.r) == row.saturated, "saturated" + at);
        check(near(p.primitive(row.r), row.primitive, 1e-13), "primitive" + at);
      }

    out() << "--- q(r) = min(0.5 r_+, 0.25)" << std::endl;
    const CappedRamp q(0.5, 0.25);
    check(near(q.value(-2.), 0., 0) && near(q.value(0.2), 0.1, 1e-15) &&
            near(q.value(0.5), 0.25, 1e-15) && near(q.value(4.), 0.25, 0),
          "q: 0, 0.1, 0.25, 0.25 at r = -2, 0.2, 0.5 (kink), 4");
    check(near(q.derivative(0.2), 0.5, 0) && near(q.derivative(0.7), 0., 0),
          "q': 0.5 below the kink, 0 beyond");
    check(near(q.primitive(0.2), 0.01, 1e-15) &&
            near(q.primitive(1.), 0.0625 + 0.125, 1e-15),
          "q: Pi(0.2) = 0.01, Pi(1) = 0.0625 + 0.25 * 0.5");
  }


  void
  test_derivative()
  {
    out() << "--- derivative vs. central differences (away from kinks)"
          << std::endl;
    for (const CappedRamp &ramp : {CappedRamp(2., 3.), CappedRamp(0.5, 0.25)})
      {
        double       worst = 0;
        const double h     = 1e-6;
        for (const double r : {-0.7, 0.1, 0.3, 0.45, 1.2, 2.5, 7.})
          {
            const double fd = (ramp.value(r + h) - ramp.value(r - h)) / (2 * h);
            worst = std::max(worst, std::abs(fd - ramp.derivative(r)));
          }
        check(worst <= 1e-7,
              "slope " + digits(ramp.get_slope(), 3) +
                ": |p' - central difference| <= 1e-7 at 7 points");
      }
  }


  void
  test_primitive()
  {
    out() << "--- primitive vs. composite Simpson, and Pi' = p" << std::endl;
    const CappedRamp p(2., 3.);
    for (const double r : {-0.5, 0.7, 1.5, 2., 10.})
      {
        const double quadrature =
          simpson([&](const double s) { return p.value(s); }, r, 20000);
        out() << "r = " << digits(r, 6)
              << "  Pi = " << digits(p.primitive(r), 6)
              << "  Simpson = " << digits(quadrature + 0., 6) << std::endl;
        check(near(p.primitive(r),
                   quadrature,
                   1e-6 * (1 + std::abs(quadrature))),
              "Pi(" + digits(r, 3) + ") = Simpson to 1e-6");
      }
    double       worst = 0;
    const double h     = 1e-6;
    for (const double r : {-0.5, 0., 0.7, 1.5, 2., 10.})
      worst =
        std::max(worst,
                 std::abs((p.primitive(r + h) - p.primitive(r - h)) / (2 * h) -
                          p.value(r)));
    check(worst <= 1e-5,
          "(Pi(r+h) - Pi(r-h))/2h = p(r) to 1e-5, kink and 0 included");
    // Pi is convex (p nondecreasing): midpoint below the chord.
    bool convex = true;
    for (const double a : {-1., 0., 0.5, 1.4})
      for (const double b : {0.3, 1.6, 5.})
        convex = convex && p.primitive(0.5 * (a + b)) <=
                             0.5 * (p.primitive(a) + p.primitive(b)) + 1e-15;
    check(convex, "Pi convex: Pi((a+b)/2) <= (Pi(a) + Pi(b))/2");
  }


  /**
   * The step dissipation of doc/theory.md section 6,
   * p(b)(b - a) - (Pi(b) - Pi(a)) >= 0, by hand and from Pi.
   */
  void
  test_dissipation()
  {
    const CappedRamp p(2., 3.);
    out() << "--- dissipation p(b)(b - a) - (Pi(b) - Pi(a))" << std::endl;
    struct Step
    {
      double a, b, expected;
    };
    for (const Step &step : std::vector<Step>{{-1., 0.5, 1.25},
                                              {0.5, -1., 0.25},
                                              {0.2, 1., 0.64},
                                              {1., 0.2, 0.64},
                                              {1., 2., 0.25},
                                              {2., 1., 0.75},
                                              {-1., 3., 5.25},
                                              {3., -1., 6.75},
                                              {2., 5., 0.},
                                              {0.7, 0.7, 0.}})
      {
        const double d = p.dissipation(step.a, step.b);
        const double from_primitive =
          p.value(step.b) * (step.b - step.a) -
          (p.primitive(step.b) - p.primitive(step.a));
        out() << "a = " << digits(step.a, 6) << "  b = " << digits(step.b, 6)
              << "  dissipation = " << digits(d, 6) << std::endl;
        check(d >= 0 && near(d, step.expected, 1e-13) &&
                near(d, from_primitive, 1e-13),
              "dissipation(" + digits(step.a, 3) + ", " + digits(step.b, 3) +
                ") >= 0, by hand and from Pi");
      }
    check(CappedRamp(0., 3.).dissipation(-1., 2.) == 0,
          "zero stiffness: no dissipation");
  }


  void
  test_zero_stiffness()
  {
    out() << "--- zero stiffness: no force" << std::endl;
    const CappedRamp zero(0., 3.);
    bool             nothing = true;
    for (const double r : {-1., 0., 0.5, 1e3})
      nothing = nothing && zero.value(r) == 0 && zero.derivative(r) == 0 &&
                !zero.active(r) && !zero.saturated(r) && zero.primitive(r) == 0;
    check(nothing,
          "CappedRamp(0, 3): value, derivative, primitive 0, never "
          "active or saturated");

    const Foundation none(foundation_parameters(0., 3., 0., 0.25, false));
    check(!none.has_damping(), "c_nu = d_nu = 0: no damping");
    check(none.pressure(1., 1.) == 0 && none.pressure(1e3, 1e3) == 0,
          "c_nu = d_nu = 0: pressure 0 at u_nu = w_nu = 1 and 1e3");

    const Foundation undamped(foundation_parameters(2., 3., 0., 0.25, false));
    check(!undamped.has_damping() && undamped.pressure(1., 1.) == 2.,
          "d_nu = 0: no damping, pressure p(1) = 2 whatever w_nu");
  }


  void
  test_pressure()
  {
    out() << "--- pressure p(u_nu) + q(w_nu)" << std::endl;
    const Foundation f(foundation_parameters(2., 3., 0.5, 0.25, false));
    check(f.has_damping(), "d_nu = 0.5: damping");
    check(f.compliance().value(1.) == 2. && f.damping().value(0.2) == 0.1,
          "compliance() and damping() are p and q");
    struct Row
    {
      double u, w, pressure;
    };
    const std::vector<Row> rows = {{1., 0.2, 2.1},
                                   {2., 1., 3.25},
                                   {-1., -1., 0.},
                                   {1., -1., 2.},
                                   {-0.1, 0.2, 0.1}, // q acts out of contact
                                   {0., 0.2, 0.1}};
    for (const Row &row : rows)
      {
        out() << "u_nu = " << digits(row.u, 6)
              << "  w_nu = " << digits(row.w, 6)
              << "  pressure = " << digits(f.pressure(row.u, row.w), 6)
              << std::endl;
        check(near(f.pressure(row.u, row.w), row.pressure, 1e-14) &&
                near(f.pressure(row.u, row.w),
                     f.compliance().value(row.u) + f.damping().value(row.w),
                     1e-15),
              "pressure = p + q at u_nu = " + digits(row.u, 3) +
                ", w_nu = " + digits(row.w, 3));
      }
    check(f.damping_acts(-1.) && f.damping_acts(0.) && f.damping_acts(1.),
          "default: damping acts at every u_nu (eq. (17) as written)");

    out() << "--- damping only in contact" << std::endl;
    const Foundation g(foundation_parameters(2., 3., 0.5, 0.25, true));
    check(!g.damping_acts(-0.1) && !g.damping_acts(0.) && g.damping_acts(0.1),
          "only in contact: damping acts iff u_nu > 0");
    for (const Row &row : std::vector<Row>{{-0.1, 0.2, 0.},
                                           {0., 0.2, 0.},
                                           {0.1, 0.2, 0.3},
                                           {1., 1., 2.25},
                                           {0.1, -0.2, 0.2}})
      {
        out() << "u_nu = " << digits(row.u, 6)
              << "  w_nu = " << digits(row.w, 6)
              << "  pressure = " << digits(g.pressure(row.u, row.w), 6)
              << std::endl;
        check(near(g.pressure(row.u, row.w), row.pressure, 1e-14),
              "only in contact: pressure at u_nu = " + digits(row.u, 3) +
                ", w_nu = " + digits(row.w, 3));
      }
  }
} // namespace


int
main(int argc, char *argv[])
{
  return test_tools::run_tests(argc,
                               argv,
                               {test_ramp_values,
                                test_derivative,
                                test_primitive,
                                test_dissipation,
                                test_zero_stiffness,
                                test_pressure});
}
