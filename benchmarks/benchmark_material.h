#ifndef dynamic_contact_benchmark_material_h
#define dynamic_contact_benchmark_material_h

#include <dynamic_contact/parameters/parameters.h>

/**
 * The material of the paper's scene without viscosity (E = 1e11 Pa,
 * nu = 0.3, rho = 1000 kg/m^3, plane strain), whose K0 = (rho/k) M + k B
 * the solver benchmarks (amg_comparison.cc, direct_comparison.cc)
 * precondition and factorize.
 */
inline DynamicContact::Parameters::Material
benchmark_material()
{
  DynamicContact::Parameters::Material material;
  material.density       = 1000;
  material.young_modulus = 1e11;
  material.poisson_ratio = 0.3;
  material.plane_model =
    DynamicContact::Parameters::Material::PlaneModel::plane_strain;
  material.viscosity_lambda = 0;
  material.viscosity_mu     = 0;
  return material;
}

#endif
