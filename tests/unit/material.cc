// The Kelvin-Voigt material of doc/theory.md section 1 (eq. (87)):
// E = 2.6, kappa = 0.3 give mu = 1, lambda = 1.5 (plane strain and 3D) and
// lambda* = 2 lambda mu/(lambda + 2 mu) = 6/7 in plane stress, so
//   M = lambda + 2 mu = 3.5 (plane strain, 3D), E/(1 - kappa^2) = 20/7
//   (plane stress).
// The eigenvalues of an isotropic tensor on symmetric tensors (Mandel basis)
// are 2 mu (dim(dim+1)/2 - 1 times) and dim lambda + 2 mu (once).

#include <deal.II/lac/lapack_full_matrix.h>

#include <dynamic_contact/laws/material.h>

#include "test_tools.h"

#include <algorithm>

using namespace DynamicContact;
using test_tools::check;
using test_tools::digits;
using test_tools::out;
using PlaneModel = Parameters::Material::PlaneModel;

namespace
{
  Parameters::Material
  material_parameters(const double     E,
                      const double     kappa,
                      const PlaneModel model,
                      const double     viscosity_lambda = 0,
                      const double     viscosity_mu     = 0)
  {
    Parameters::Material p{};
    p.density          = 1000;
    p.young_modulus    = E;
    p.poisson_ratio    = kappa;
    p.plane_model      = model;
    p.viscosity_lambda = viscosity_lambda;
    p.viscosity_mu     = viscosity_mu;
    return p;
  }


  /** Sorted eigenvalues of C as a map on symmetric tensors. */
  template <int dim>
  std::vector<double>
  eigenvalues(const SymmetricTensor<4, dim> &C)
  {
    const auto               basis = test_tools::mandel_basis<dim>();
    const unsigned int       n     = basis.size();
    LAPACKFullMatrix<double> A(n, n);
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        A(a, b) = scalar_product(basis[a], C * basis[b]);
    A.compute_eigenvalues();
    std::vector<double> values;
    for (unsigned int a = 0; a < n; ++a)
      values.push_back(A.eigenvalue(a).real());
    std::sort(values.begin(), values.end());
    return values;
  }

  template <int dim>
  bool
  major_and_minor_symmetric(const SymmetricTensor<4, dim> &C)
  {
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            if (C[i][j][k][l] != C[k][l][i][j] ||
                C[i][j][k][l] != C[j][i][k][l] ||
                C[i][j][k][l] != C[i][j][l][k])
              return false;
    return true;
  }

  /** The largest difference of two entries (of all, as the symmetric
   *  tensors store each entry once). */
  template <int rank, int dim>
  double
  max_difference(const SymmetricTensor<rank, dim> &A,
                 const SymmetricTensor<rank, dim> &B)
  {
    double d = 0;
    for (unsigned int i = 0;
         i < SymmetricTensor<rank, dim>::n_independent_components;
         ++i)
      d = std::max(d, std::abs(A.access_raw_entry(i) - B.access_raw_entry(i)));
    return d;
  }


  /** Positive definite for every valid Poisson ratio (-1, 1/2). */
  template <int dim>
  void
  test_positive_definite(const std::string &name, const PlaneModel model)
  {
    double smallest = 1e300;
    for (const double kappa : {-0.9, -0.5, 0., 0.3, 0.45, 0.499})
      {
        const KelvinVoigtMaterial<dim> m(
          material_parameters(1e11, kappa, model));
        smallest = std::min(smallest, eigenvalues(m.elasticity())[0] / 1e11);
      }
    check(smallest > 0,
          name + ": positive definite for kappa in {-0.9, ..., 0.499}");
    if (model == PlaneModel::plane_strain)
      {
        // kappa = 0.6 is not a material: dim lambda + 2 mu < 0.
        const KelvinVoigtMaterial<dim> m(material_parameters(1e11, 0.6, model));
        check(eigenvalues(m.elasticity())[0] < 0,
              name + ": not positive definite for kappa = 0.6");
      }
  }


  /**
   * Lame constants, symmetry, eigenvalues (hence positive definiteness),
   * uniaxial strain and pure shear of one model, E = 2.6, kappa = 0.3.
   */
  template <int dim>
  void
  test_model(const std::string &name,
             const PlaneModel   model,
             const double       lambda_expected,
             const double       M_expected,
             const double       bulk_eigenvalue)
  {
    out() << "--- " << name << std::endl;
    const KelvinVoigtMaterial<dim> material(
      material_parameters(2.6, 0.3, model));
    out() << "lambda = " << digits(material.lambda(), 6)
          << "  mu = " << digits(material.mu(), 6)
          << "  M = " << digits(material.constrained_modulus(), 6) << std::endl;
    check(test_tools::close(material.lambda(), lambda_expected, 1e-14) &&
            test_tools::close(material.mu(), 1., 1e-14),
          name + ": Lame constants");
    check(test_tools::close(material.constrained_modulus(), M_expected, 1e-14),
          name + ": constrained modulus M");
    check(material.density() == 1000, name + ": density");

    const SymmetricTensor<4, dim> &C = material.elasticity();
    check(major_and_minor_symmetric(C), name + ": major and minor symmetry");
    check(max_difference(
            C, isotropic_tensor<dim>(material.lambda(), material.mu())) == 0,
          name + ": E = isotropic_tensor(lambda, mu)");

    const auto values = eigenvalues(C);
    out() << "eigenvalues:";
    for (const double v : values)
      out() << ' ' << digits(v, 6);
    out() << std::endl;
    bool as_expected = true;
    for (unsigned int a = 0; a + 1 < values.size(); ++a)
      as_expected = as_expected && test_tools::close(values[a], 2., 1e-12);
    as_expected =
      as_expected && test_tools::close(values.back(), bulk_eigenvalue, 1e-12);
    check(as_expected,
          name + ": eigenvalues 2 mu and " + digits(bulk_eigenvalue, 6));

    test_positive_definite<dim>(name, model);

    // Uniaxial strain eps_yy: sigma_yy = M eps, sigma_xx = lambda eps.
    const double            eps = 1e-3;
    SymmetricTensor<2, dim> strain;
    strain[1][1]                        = eps;
    const SymmetricTensor<2, dim> sigma = material.stress(strain, strain);
    out() << "uniaxial strain: sigma_xx = " << digits(sigma[0][0], 6)
          << "  sigma_yy = " << digits(sigma[1][1], 6)
          << "  sigma_xy = " << digits(sigma[0][1], 6) << std::endl;
    check(test_tools::close(sigma[1][1],
                            material.constrained_modulus() * eps,
                            1e-14) &&
            test_tools::close(sigma[1][1], M_expected * eps, 1e-14),
          name + ": uniaxial strain sigma_yy = M eps");
    check(test_tools::close(sigma[0][0], lambda_expected * eps, 1e-14) &&
            sigma[0][1] == 0,
          name + ": uniaxial strain sigma_xx = lambda eps, sigma_xy = 0");

    // Shear eps_xy = gamma/2: sigma_xy = mu gamma, no normal stress.
    SymmetricTensor<2, dim> shear;
    shear[0][1]                       = 0.5e-3;
    const SymmetricTensor<2, dim> tau = material.stress(shear, shear);
    check(test_tools::close(tau[0][1], 1e-3, 1e-14) && tau[0][0] == 0 &&
            tau[1][1] == 0,
          name + ": shear sigma_xy = 2 mu eps_xy");
  }


  /**
   * Plane stress is the 3D tensor with sigma_zz = 0 eliminated (static
   * condensation).
   */
  void
  test_plane_stress_is_condensed_3d()
  {
    out() << "--- plane stress = 3D with sigma_zz = 0 eliminated" << std::endl;
    const double                 lambda = 1.5, mu = 1.;
    const SymmetricTensor<4, 3>  C3 = isotropic_tensor<3>(lambda, mu);
    const KelvinVoigtMaterial<2> plane_stress(
      material_parameters(2.6, 0.3, PlaneModel::plane_stress));
    const SymmetricTensor<4, 2> &C2 = plane_stress.elasticity();

    SymmetricTensor<4, 2> condensed;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = 0; l < 2; ++l)
            condensed[i][j][k][l] =
              C3[i][j][k][l] - C3[i][j][2][2] * C3[2][2][k][l] / C3[2][2][2][2];
    check(max_difference(C2, condensed) <= 1e-14,
          "C_plane_stress = C3 - C3(:,zz) C3(zz,:)/C3(zz,zz) in plane");

    SymmetricTensor<2, 2> e2;
    e2[0][0] = 1e-3;
    e2[1][1] = -2e-3;
    e2[0][1] = 0.5e-3;
    SymmetricTensor<2, 3> e3;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        e3[i][j] = e2[i][j];
    e3[2][2] = -lambda / (lambda + 2 * mu) * (e2[0][0] + e2[1][1]);
    const SymmetricTensor<2, 3> s3 = C3 * e3;
    const SymmetricTensor<2, 2> s2 = plane_stress.stress(e2, e2);
    out() << "3D: sigma_xx = " << digits(s3[0][0], 6)
          << "  sigma_yy = " << digits(s3[1][1], 6)
          << "  sigma_xy = " << digits(s3[0][1], 6) << "  sigma_zz = "
          << digits(std::abs(s3[2][2]) < 1e-15 ? 0. : s3[2][2], 6) << std::endl;
    out() << "plane stress: sigma_xx = " << digits(s2[0][0], 6)
          << "  sigma_yy = " << digits(s2[1][1], 6)
          << "  sigma_xy = " << digits(s2[0][1], 6) << std::endl;
    check(std::abs(s3[2][2]) <= 1e-15, "3D: sigma_zz = 0 for that eps_zz");
    check(std::abs(s2[0][0] - s3[0][0]) <= 1e-15 &&
            std::abs(s2[1][1] - s3[1][1]) <= 1e-15 &&
            std::abs(s2[0][1] - s3[0][1]) <= 1e-15,
          "plane stress: in-plane stresses equal the 3D ones");
    // By hand: tr = -1e-3, lambda* = 6/7: sigma_xx = -6/7e-3 + 2e-3.
    check(test_tools::close(s2[0][0], 8e-3 / 7, 1e-13) &&
            test_tools::close(s2[1][1], -34e-3 / 7, 1e-13) &&
            test_tools::close(s2[0][1], 1e-3, 1e-13),
          "plane stress: sigma = (8/7, -34/7, 1) 1e-3 by hand");
  }


  /**
   * Uniaxial stress gives E in 3D and in plane stress; in 3D the plane
   * model is ignored; effective_lambda.
   */
  void
  test_uniaxial_stress()
  {
    out() << "--- uniaxial stress" << std::endl;
    const double E = 2.6, kappa = 0.3, s = 1e-2;
    {
      const KelvinVoigtMaterial<3> m(
        material_parameters(E, kappa, PlaneModel::plane_strain));
      SymmetricTensor<2, 3> e;
      e[0][0]                           = s / E;
      e[1][1]                           = -kappa * s / E;
      e[2][2]                           = -kappa * s / E;
      const SymmetricTensor<2, 3> sigma = m.stress(e, e);
      SymmetricTensor<2, 3>       expected;
      expected[0][0] = s;
      out() << "3D: sigma_xx/eps_xx = " << digits(sigma[0][0] / e[0][0], 6)
            << std::endl;
      check(max_difference(sigma, expected) <= 1e-15,
            "3D: eps = s/E (1, -kappa, -kappa) gives sigma = (s, 0, 0)");
      // The same from the compliance: 1/S_xxxx = E, -S_yyxx/S_xxxx = kappa.
      const SymmetricTensor<4, 3> S = invert(m.elasticity());
      check(test_tools::close(1 / S[0][0][0][0], E, 1e-12) &&
              test_tools::close(-S[1][1][0][0] / S[0][0][0][0], kappa, 1e-12),
            "3D: inverse tensor gives E and kappa");
    }
    {
      const KelvinVoigtMaterial<2> m(
        material_parameters(E, kappa, PlaneModel::plane_stress));
      SymmetricTensor<2, 2> e;
      e[0][0]                           = s / E;
      e[1][1]                           = -kappa * s / E;
      const SymmetricTensor<2, 2> sigma = m.stress(e, e);
      SymmetricTensor<2, 2>       expected;
      expected[0][0] = s;
      out() << "plane stress: sigma_xx/eps_xx = "
            << digits(sigma[0][0] / e[0][0], 6) << std::endl;
      check(max_difference(sigma, expected) <= 1e-15,
            "plane stress: eps = s/E (1, -kappa) gives sigma = (s, 0)");
    }
    {
      // In 3D the plane model is ignored.
      const KelvinVoigtMaterial<3> strain3(
        material_parameters(E, kappa, PlaneModel::plane_strain));
      const KelvinVoigtMaterial<3> stress3(
        material_parameters(E, kappa, PlaneModel::plane_stress));
      check(max_difference(strain3.elasticity(), stress3.elasticity()) == 0 &&
              test_tools::close(stress3.lambda(), 1.5, 1e-14),
            "3D: the plane model is ignored");
    }
    check(effective_lambda(1.5, 1., PlaneModel::plane_stress, 2) == 3. / 3.5 &&
            effective_lambda(1.5, 1., PlaneModel::plane_strain, 2) == 1.5 &&
            effective_lambda(1.5, 1., PlaneModel::plane_stress, 3) == 1.5 &&
            effective_lambda(0., 0., PlaneModel::plane_stress, 2) == 0.,
          "effective_lambda: 2 lambda mu/(lambda + 2 mu) in plane stress only");
  }


  /** The viscosity tensor C from (lambda_v, mu_v) = (0.4, 0.1). */
  template <int dim>
  void
  test_viscosity(const std::string &name,
                 const PlaneModel   model,
                 const double       lambda_v_expected)
  {
    out() << "--- viscosity, " << name << std::endl;
    const KelvinVoigtMaterial<dim> elastic(
      material_parameters(2.6, 0.3, model));
    check(!elastic.has_viscosity() && elastic.viscosity().norm() == 0,
          name + ": (0, 0): no viscosity, C = 0");
    SymmetricTensor<2, dim> zero, rate;
    rate[0][0] = 1.;
    check(elastic.stress(zero, rate).norm() == 0,
          name + ": (0, 0): the strain rate makes no stress");

    const KelvinVoigtMaterial<dim> viscous(
      material_parameters(2.6, 0.3, model, 0.4, 0.1));
    check(viscous.has_viscosity(), name + ": (0.4, 0.1): viscous");
    check(max_difference(viscous.viscosity(),
                         isotropic_tensor<dim>(lambda_v_expected, 0.1)) <=
            1e-15,
          name + ": C = isotropic_tensor(" + digits(lambda_v_expected, 6) +
            ", 0.1)");
    check(major_and_minor_symmetric(viscous.viscosity()),
          name + ": C major and minor symmetric");
    check(max_difference(viscous.elasticity(), elastic.elasticity()) == 0,
          name + ": viscosity leaves E unchanged");

    // sigma = C eps(w) + E eps(u): rate e_xx, strain e_xy = 1e-3.
    SymmetricTensor<2, dim> strain;
    strain[0][1]                        = 1e-3;
    const SymmetricTensor<2, dim> sigma = viscous.stress(strain, rate);
    out() << "sigma_xx = " << digits(sigma[0][0], 6)
          << "  sigma_yy = " << digits(sigma[1][1], 6)
          << "  sigma_xy = " << digits(sigma[0][1], 6) << std::endl;
    check(test_tools::close(sigma[0][0], lambda_v_expected + 0.2, 1e-14) &&
            test_tools::close(sigma[1][1], lambda_v_expected, 1e-14) &&
            test_tools::close(sigma[0][1], 2e-3, 1e-14),
          name + ": sigma = C eps(w) + E eps(u) by hand");
  }


  void
  test_von_mises()
  {
    out() << "--- von Mises" << std::endl;
    const double tau = 2., s = 3.;
    {
      SymmetricTensor<2, 3> shear;
      shear[0][1] = tau;
      SymmetricTensor<2, 3> uniaxial;
      uniaxial[0][0]                = s;
      SymmetricTensor<2, 3> shifted = uniaxial;
      shifted += 5. * unit_symmetric_tensor<3>();
      out() << "3D: pure shear " << digits(von_mises_stress(shear), 6)
            << "  uniaxial " << digits(von_mises_stress(uniaxial), 6)
            << std::endl;
      check(test_tools::close(von_mises_stress(shear),
                              std::sqrt(3.) * tau,
                              1e-14),
            "3D: pure shear tau gives sqrt(3) tau");
      check(test_tools::close(von_mises_stress(uniaxial), s, 1e-14),
            "3D: uniaxial stress s gives s");
      check(test_tools::close(von_mises_stress(shifted), s, 1e-14),
            "3D: a hydrostatic stress adds nothing");
    }
    {
      SymmetricTensor<2, 2> shear;
      shear[0][1] = tau;
      out() << "2D: pure shear " << digits(von_mises_stress(shear), 6)
            << std::endl;
      check(test_tools::close(von_mises_stress(shear),
                              std::sqrt(3.) * tau,
                              1e-14),
            "2D: pure shear tau gives sqrt(3) tau");

      // The in-plane stress (s, 0; 0, 0) with sigma_zz = 0 is uniaxial:
      // von Mises sqrt(s_xx^2 - s_xx s_yy + s_yy^2 + 3 s_xy^2) = s.
      SymmetricTensor<2, 2> uniaxial;
      uniaxial[0][0] = s;
      out() << "2D: uniaxial " << digits(von_mises_stress(uniaxial), 6)
            << std::endl;
      check(test_tools::close(von_mises_stress(uniaxial), s, 1e-14),
            "2D: uniaxial in-plane stress s gives s");
    }
  }
} // namespace


int
main(int argc, char *argv[])
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // name, model, lambda, M, dim lambda + 2 mu
  test_model<2>("plane strain", PlaneModel::plane_strain, 1.5, 3.5, 5.);
  test_model<2>(
    "plane stress", PlaneModel::plane_stress, 6. / 7., 20. / 7., 26. / 7.);
  test_model<3>("3D", PlaneModel::plane_strain, 1.5, 3.5, 6.5);
  test_plane_stress_is_condensed_3d();
  test_uniaxial_stress();
  test_viscosity<2>("plane strain", PlaneModel::plane_strain, 0.4);
  test_viscosity<2>("plane stress", PlaneModel::plane_stress, 0.08 / 0.6);
  test_viscosity<3>("3D", PlaneModel::plane_strain, 0.4);
  test_von_mises();
}
