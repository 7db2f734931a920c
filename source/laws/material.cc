#include <dynamic_contact/laws/material.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  double
  MaterialConstants::p_wave_speed() const
  {
    const double nu     = poisson_ratio;
    const double lambda = young_modulus * nu / ((1 + nu) * (1 - 2 * nu));
    const double mu     = young_modulus / (2 * (1 + nu));
    return std::sqrt((lambda + 2 * mu) / density);
  }

  double
  MaterialConstants::shear_wave_speed() const
  {
    const double mu = young_modulus / (2 * (1 + poisson_ratio));
    return std::sqrt(mu / density);
  }


  template <int dim>
  SymmetricTensor<4, dim>
  isotropic_tensor(const double lambda, const double mu)
  {
    SymmetricTensor<4, dim> C;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            C[i][j][k][l] = (i == j && k == l ? lambda : 0.) +
                            (i == k && j == l ? mu : 0.) +
                            (i == l && j == k ? mu : 0.);
    return C;
  }


  double
  effective_lambda(const double                        lambda,
                   const double                        mu,
                   const MaterialConstants::PlaneModel model,
                   const unsigned int                  dim)
  {
    if (dim == 2 && model == MaterialConstants::PlaneModel::plane_stress)
      return (lambda + 2 * mu == 0 ? 0. : 2 * lambda * mu / (lambda + 2 * mu));
    return lambda;
  }


  template <int dim>
  KelvinVoigtMaterial<dim>::KelvinVoigtMaterial(const MaterialConstants &p)
    : rho(p.density)
    , plane_strain(dim == 2 &&
                   p.plane_model == MaterialConstants::PlaneModel::plane_strain)
  {
    const double E     = p.young_modulus;
    const double kappa = p.poisson_ratio;
    // Eq. (87): lambda = E kappa/((1+kappa)(1-2 kappa)), 2 mu = E/(1+kappa).
    const double lambda = E * kappa / ((1 + kappa) * (1 - 2 * kappa));
    lame_mu             = E / (2 * (1 + kappa));
    lame_lambda         = effective_lambda(lambda, lame_mu, p.plane_model, dim);
    elasticity_tensor   = isotropic_tensor<dim>(lame_lambda, lame_mu);

    viscous = (p.viscosity_lambda != 0 || p.viscosity_mu != 0);
    viscous_lambda =
      effective_lambda(p.viscosity_lambda, p.viscosity_mu, p.plane_model, dim);
    viscosity_tensor = isotropic_tensor<dim>(viscous_lambda, p.viscosity_mu);
  }


  template <int dim>
  double
  KelvinVoigtMaterial<dim>::viscous_coercivity() const
  {
    // An isotropic tensor has the eigenvalue 2 mu_v on the deviators and
    // 2 mu_v + dim lambda_v on the identity.
    if (!viscous)
      return 0.;
    const double mu_v = viscosity_tensor[0][1][0][1];
    return std::min(2 * mu_v, 2 * mu_v + dim * viscous_lambda);
  }


  template <int dim>
  SymmetricTensor<2, dim>
  KelvinVoigtMaterial<dim>::stress(
    const SymmetricTensor<2, dim> &strain,
    const SymmetricTensor<2, dim> &strain_rate) const
  {
    SymmetricTensor<2, dim> sigma = elasticity_tensor * strain;
    if (viscous)
      sigma += viscosity_tensor * strain_rate;
    return sigma;
  }


  template <int dim>
  double
  KelvinVoigtMaterial<dim>::out_of_plane_stress(
    const SymmetricTensor<2, dim> &strain,
    const SymmetricTensor<2, dim> &strain_rate) const
  {
    if (!plane_strain)
      return 0.;
    return lame_lambda * trace(strain) +
           (viscous ? viscous_lambda * trace(strain_rate) : 0.);
  }


  template <int dim>
  double
  von_mises_stress(const SymmetricTensor<2, dim> &stress,
                   const double                   out_of_plane)
  {
    // The deviator of the 3D stress (in 2D with sigma_zz = out_of_plane).
    SymmetricTensor<2, 3> sigma;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        sigma[i][j] = stress[i][j];
    if (dim == 2)
      sigma[2][2] = out_of_plane;
    const SymmetricTensor<2, 3> s = deviator(sigma);
    return std::sqrt(1.5 * scalar_product(s, s));
  }


  template SymmetricTensor<4, 2>
  isotropic_tensor<2>(const double, const double);
  template SymmetricTensor<4, 3>
  isotropic_tensor<3>(const double, const double);
  template class KelvinVoigtMaterial<2>;
  template class KelvinVoigtMaterial<3>;
  template double
  von_mises_stress<2>(const SymmetricTensor<2, 2> &, const double);
  template double
  von_mises_stress<3>(const SymmetricTensor<2, 3> &, const double);
} // namespace DynamicContact
