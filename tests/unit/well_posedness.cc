// The well-posedness report (doc/theory.md section 1.5): the ratios
//   R = L S/(rho c_s)              (radiation damping against the weakening)
//   G = 2 (L S)^2 T/(rho c2)       (the viscosity against the weakening,
//                                   the paper's Remark 8)
// against closed forms for data chosen by hand; the normal stresses at which
// they reach 1; L = alpha (a - b) of the exponential law and 0 of a constant
// one; the shear wave speed; c2 against the smallest eigenvalue of the
// viscosity tensor; c3 + c4 of the foundation (infinite for a law without a
// bound); the same report in SI, mm-t-s and in-lbf-s; the report of scenes
// of prm/ (none where mu does not depend on the slip rate).

#include <deal.II/lac/lapack_full_matrix.h>

#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/laws/well_posedness.h>
#include <dynamic_contact/parameters/well_posedness_report.h>

#include "test_tools.h"

#include <algorithm>
#include <limits>

using namespace DynamicContact;
using test_tools::check;
using test_tools::close;
using test_tools::digits;
using test_tools::out;
using PlaneModel = Parameters::Material::PlaneModel;

namespace
{
  const double infinity = std::numeric_limits<double>::infinity();

  bool
  contains(const std::string &text, const std::string &part)
  {
    return text.find(part) != std::string::npos;
  }

  /**
   * L = 2, S = 0.1, rho = 4, c_s = 0.5 (mu = 1), c2 = 0.5, T = 3:
   * R = 2 0.1/(4 0.5) = 0.1, G = 2 (0.2)^2 3/(4 0.5) = 0.12; R = 1 at
   * S = rho c_s/L = 1 = 1 mu, G = 1 at S = sqrt(rho c2/(2 T))/L = sqrt(1/3)/2.
   */
  WellPosedness::Data
  hand_data()
  {
    WellPosedness::Data d;
    d.weakening          = 2;
    d.normal_stress      = 0.1;
    d.density            = 4;
    d.shear_wave_speed   = 0.5;
    d.viscous_coercivity = 0.5;
    d.end_time           = 3;
    return d;
  }


  void
  test_closed_form()
  {
    out() << "--- closed forms" << std::endl;
    const WellPosedness w(hand_data());
    out() << w.report();
    check(close(w.shear_modulus(), 1., 1e-15), "mu = rho c_s^2 = 1");
    check(close(w.radiation_ratio(), 0.1, 1e-14), "R = L S/(rho c_s) = 0.1");
    check(close(w.radiation_critical_stress(), 1., 1e-14),
          "R = 1 at S = rho c_s/L = 1 mu");
    check(close(w.growth_exponent(), 0.12, 1e-14),
          "G = 2 (L S)^2 T/(rho c2) = 0.12");
    check(close(w.growth_critical_stress(), std::sqrt(1. / 3) / 2, 1e-14),
          "G = 1 at S = sqrt(rho c2/(2 T))/L = sqrt(1/3)/2 mu");

    // At the critical stresses the ratios are 1.
    WellPosedness::Data d = hand_data();
    d.normal_stress       = w.radiation_critical_stress() * w.shear_modulus();
    check(close(WellPosedness(d).radiation_ratio(), 1., 1e-14),
          "R = 1 at its critical stress");
    d.normal_stress = w.growth_critical_stress() * w.shear_modulus();
    check(close(WellPosedness(d).growth_exponent(), 1., 1e-14),
          "G = 1 at its critical stress");
    check(contains(w.report(), "= 1.00e-01: holds by a factor 1.00e+01") &&
            contains(w.report(), "= 1.20e-01: holds by a factor 8.33e+00") &&
            contains(w.report(), "steady sliding is stable") &&
            contains(w.report(), "moderate constant"),
          "the report: both hold, with their factors");

    // Twenty times the normal stress: R = 2, G = 48 (both fail).
    d.normal_stress           = 2;
    const std::string failing = WellPosedness(d).report();
    out() << failing;
    check(contains(failing, "= 2.00e+00: fails by a factor 2.00e+00") &&
            contains(failing, "= 4.80e+01: fails by a factor 4.80e+01") &&
            contains(failing, "only the viscosity bounds") &&
            contains(failing, "will not converge at practical resolutions"),
          "the report at S = 2: both fail, the viscosity bounds the growth");
    // The estimate of G against the growth rate s0 = (R^2 - 1) mu/mu_v of
    // the uniform mode on a Kelvin-Voigt half-space (doc/theory.md
    // section 1.5; c2 = 2 mu_v): G/T = s0 + mu/mu_v.
    const WellPosedness f(d);
    const double        mu_v = 0.5 * d.viscous_coercivity;
    const double        s0   = (std::pow(f.radiation_ratio(), 2) - 1) / mu_v;
    check(close(f.growth_exponent() / d.end_time, s0 + 1 / mu_v, 1e-14),
          "G/T = s0 + mu/mu_v, s0 the growth rate of the uniform mode");
  }


  void
  test_laws()
  {
    out() << "--- the laws' constants" << std::endl;
    const ExponentialFriction exponential(1, 0.5, 2000);
    const double              L = exponential.one_sided_lipschitz_constant(1e4);
    out() << "exponential (1, 0.5, 2000): L = " << digits(L) << std::endl;
    check(close(L, 2000 * 0.5, 1e-15), "exponential law: L = alpha (a - b)");
    const ConstantFriction constant(0.4);
    check(constant.one_sided_lipschitz_constant(1e4) == 0,
          "constant law: L = 0");

    WellPosedness::Data d = hand_data();
    d.weakening           = constant.one_sided_lipschitz_constant(1e4);
    const WellPosedness w(d);
    out() << w.report();
    check(w.radiation_ratio() == 0 && w.growth_exponent() == 0 &&
            w.radiation_critical_stress() == infinity &&
            w.growth_critical_stress() == infinity,
          "L = 0: R = G = 0, no critical stress");
    d.normal_stress = infinity;
    check(WellPosedness(d).radiation_ratio() == 0 &&
            WellPosedness(d).growth_exponent() == 0,
          "L = 0 and S unbounded: R = G = 0");

    // E = 2.6, kappa = 0.3: mu = 1, lambda = 1.5; rho = 4.
    Parameters::Material m{};
    m.density       = 4;
    m.young_modulus = 2.6;
    m.poisson_ratio = 0.3;
    check(close(m.shear_wave_speed(), 0.5, 1e-15), "c_s = sqrt(mu/rho) = 0.5");
    check(close(m.p_wave_speed(), std::sqrt(3.5 / 4), 1e-15),
          "c_p = sqrt((lambda + 2 mu)/rho)");
  }


  void
  test_elastic_and_unbounded()
  {
    out() << "--- elastic body, unbounded normal stress" << std::endl;
    WellPosedness::Data d = hand_data();
    d.viscous_coercivity  = 0;
    d.normal_stress       = 1e3; // R = 1000
    const WellPosedness w(d);
    out() << w.report();
    check(w.growth_exponent() == infinity, "c2 = 0: G infinite");
    check(contains(w.report(), "fails by a factor 1.00e+03") &&
            contains(w.report(), "will not converge under refinement") &&
            contains(w.report(),
                     "no viscosity (C = 0): the paper's existence and "
                     "uniqueness theorem does not apply"),
          "elastic: ill-posed, and the paper's theorem does not apply");

    d.viscous_coercivity = 0.5;
    d.normal_stress      = infinity;
    const WellPosedness u(d);
    out() << u.report();
    check(u.radiation_ratio() == infinity && u.growth_exponent() == infinity,
          "S unbounded: R and G infinite");
    check(contains(u.report(), "cannot be checked a priori") &&
            contains(u.report(), "< 1 where p + q < 1.00e+00 mu") &&
            contains(u.report(), "< 1 where p + q < 2.89e-01 mu"),
          "S unbounded: the report gives the critical stresses only");
  }


  /** The data of hand_data() in units of @p length and @p mass (SI). */
  WellPosedness::Data
  in_units(const double length, const double mass)
  {
    WellPosedness::Data d = hand_data();
    d.normal_stress       = 1e4;           // R = 1e4, G = 1.2e9: fail by much
    const double stress   = mass / length; // Pa in the new units
    d.weakening *= length;                 // s/m
    d.normal_stress /= stress;
    d.density /= mass / (length * length * length);
    d.shear_wave_speed /= length;
    d.viscous_coercivity /= stress; // Pa s
    return d;
  }


  void
  test_units()
  {
    out() << "--- units" << std::endl;
    const WellPosedness si(in_units(1, 1));
    const WellPosedness mm(in_units(1e-3, 1e3));
    const WellPosedness inch(in_units(0.0254, 4.4482216152605 / 0.0254));
    out() << si.report();
    check(mm.report() == si.report() && inch.report() == si.report(),
          "the same report in SI, mm-t-s and in-lbf-s");
    for (const WellPosedness *w : {&mm, &inch})
      check(close(w->radiation_ratio(), si.radiation_ratio(), 1e-12) &&
              close(w->growth_exponent(), si.growth_exponent(), 1e-12) &&
              close(w->radiation_critical_stress(),
                    si.radiation_critical_stress(),
                    1e-12) &&
              close(w->growth_critical_stress(),
                    si.growth_critical_stress(),
                    1e-12),
            "the ratios and critical stresses agree to 1e-12");
  }


  /** The smallest eigenvalue of @p C on symmetric tensors (Mandel basis). */
  template <int dim>
  double
  smallest_eigenvalue(const SymmetricTensor<4, dim> &C)
  {
    const auto               basis = test_tools::mandel_basis<dim>();
    LAPACKFullMatrix<double> A(basis.size(), basis.size());
    for (unsigned int a = 0; a < basis.size(); ++a)
      for (unsigned int b = 0; b < basis.size(); ++b)
        A(a, b) = scalar_product(basis[a], C * basis[b]);
    A.compute_eigenvalues();
    double smallest = infinity;
    for (unsigned int a = 0; a < basis.size(); ++a)
      smallest = std::min(smallest, A.eigenvalue(a).real());
    return smallest;
  }


  template <int dim>
  void
  test_coercivity(const PlaneModel model, const std::string &name)
  {
    // (lambda_v, mu_v): none, the braking block's, a negative lambda_v
    // (3 lambda_v + 2 mu_v = 0.5 >= 0, the parameters' bound).
    for (const auto &[lambda_v, mu_v] : std::vector<std::pair<double, double>>{
           {0., 0.}, {1e6, 1e6}, {-0.5, 1.}})
      {
        Parameters::Material m{};
        m.density          = 1000;
        m.young_modulus    = 1e11;
        m.poisson_ratio    = 0.3;
        m.plane_model      = model;
        m.viscosity_lambda = lambda_v;
        m.viscosity_mu     = mu_v;
        const KelvinVoigtMaterial<dim> material(m);
        const double                   c2 = material.viscous_coercivity();
        const double expected = smallest_eigenvalue(material.viscosity());
        out() << name << ", lambda_v = " << lambda_v << ", mu_v = " << mu_v
              << ": c2 = " << digits(c2) << std::endl;
        check(std::abs(c2 - expected) <= 1e-12 * std::max(1., c2),
              name + ": c2 is the smallest eigenvalue of C");
      }
  }


  /** A normal compliance without a bound (ResponseLaw's default). */
  class Unbounded : public NormalLaw
  {
  public:
    double
    value(const double r) const override
    {
      return std::max(r, 0.);
    }
    double
    derivative(const double r) const override
    {
      return r > 0 ? 1. : 0.;
    }
    double
    primitive(const double r) const override
    {
      return r > 0 ? 0.5 * r * r : 0.;
    }
    bool
    is_zero() const override
    {
      return false;
    }
    void
    parse_parameters(ParameterHandler &) override
    {}
  };


  void
  test_viscous_coercivity()
  {
    out() << "--- viscous coercivity" << std::endl;
    test_coercivity<2>(PlaneModel::plane_strain, "plane strain");
    test_coercivity<2>(PlaneModel::plane_stress, "plane stress");
    test_coercivity<3>(PlaneModel::plane_strain, "3D");
  }


  void
  test_foundation_bound()
  {
    out() << "--- the foundation's bound" << std::endl;
    const Foundation both(CappedRamp(5, 3), CappedRamp(2, 4), false);
    check(both.pressure_bound() == 7, "c3 + c4 = 3 + 4");
    const Foundation no_damping(CappedRamp(5, 3), CappedRamp(0, 4), false);
    check(no_damping.pressure_bound() == 3, "q switched off: c3 alone");
    const Foundation unbounded(std::make_shared<Unbounded>(),
                               std::make_shared<CappedRampLaw<DampingLaw>>(
                                 CappedRamp(2, 4)),
                               false);
    check(unbounded.pressure_bound() == infinity,
          "a law without a bound: unbounded");
  }


  /** The report of the scene prm/@p name. */
  std::string
  scene_report(const std::string &name)
  {
    ParameterHandler    prm;
    const RunParameters p = read_parameters(test_tools::scene(name), {}, prm);
    return p.dimension == 2 ? well_posedness_report<2>(p) :
                              well_posedness_report<3>(p);
  }


  void
  test_scenes()
  {
    out() << "--- scenes" << std::endl;
    // The paper's data: L = 1000 s/m, S = 2e17 Pa, rho c_s = 1000
    // sqrt(1e11/(2.6 1000)) = 6.2017e6 Pa s/m: R = 3.2249e13.
    const std::string paper = scene_report("barboteu_danan_2016_small.prm");
    out() << "barboteu_danan_2016_small.prm:" << std::endl << paper;
    check(contains(paper, "L S/(rho c_s) = 3.22e+13: fails") &&
            contains(paper, "does not apply"),
          "the paper's scene: R = 3.22e13, no viscosity");
    const std::string braking = scene_report("braking_block.prm");
    out() << "braking_block.prm:" << std::endl << braking;
    check(contains(braking, "2 (L S)^2 T/(rho c2) = "),
          "the braking block (viscous): both ratios");
    check(scene_report("sliding_block.prm").empty() &&
            scene_report("figure3_psi5_small.prm").empty(),
          "constant friction and none: no report");
  }
} // namespace


int
main(int argc, char *argv[])
{
  return test_tools::run_tests(argc,
                               argv,
                               {test_closed_form,
                                test_laws,
                                test_elastic_and_unbounded,
                                test_units,
                                test_viscous_coercivity,
                                test_foundation_bound,
                                test_scenes});
}
