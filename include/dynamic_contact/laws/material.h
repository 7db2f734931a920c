#ifndef dynamic_contact_material_h
#define dynamic_contact_material_h

#include <deal.II/base/symmetric_tensor.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The constants of the Kelvin-Voigt law: density, Young's modulus,
   * Poisson's ratio, the 2D plane model and the two constants of the
   * viscosity tensor (Parameters::Material reads them from the parameter
   * file).
   */
  struct MaterialConstants
  {
    enum class PlaneModel
    {
      plane_strain,
      plane_stress
    };
    double     density;
    double     young_modulus;
    double     poisson_ratio;
    PlaneModel plane_model;
    double     viscosity_lambda; // first constant of the viscosity tensor C
    double     viscosity_mu;     // second constant of C

    /**
     * sqrt((lambda + 2 mu)/rho) with the Lame constants of E and the
     * Poisson ratio: the body's P-wave speed, a velocity scale of the
     * scene.
     */
    double
    p_wave_speed() const;

    /**
     * sqrt(mu/rho): the body's shear (S-) wave speed, the same in plane
     * strain, plane stress and 3D; rho c_s is the body's radiation
     * impedance to tangential motion of its boundary (doc/theory.md
     * section 1.5).
     */
    double
    shear_wave_speed() const;
  };


  /** Isotropic fourth-order tensor lambda I (x) I + 2 mu I^sym. */
  template <int dim>
  SymmetricTensor<4, dim>
  isotropic_tensor(const double lambda, const double mu);

  /**
   * The first Lame constant that a 2D model uses: lambda itself in plane
   * strain (and in 3D), 2 lambda mu / (lambda + 2 mu) in plane stress (the
   * out-of-plane stress eliminated).
   */
  double
  effective_lambda(const double                        lambda,
                   const double                        mu,
                   const MaterialConstants::PlaneModel model,
                   const unsigned int                  dim);

  /**
   * The Kelvin-Voigt law sigma = C eps(u') + E eps(u), eq. (13): isotropic
   * elasticity tensor E from Young's modulus and Poisson's ratio (eq. (87)),
   * isotropic viscosity tensor C from its two constants; both reduced to the
   * 2D plane model.
   */
  template <int dim>
  class KelvinVoigtMaterial
  {
  public:
    explicit KelvinVoigtMaterial(const MaterialConstants &parameters);

    double
    density() const
    {
      return rho;
    }

    /** The elasticity tensor E. */
    const SymmetricTensor<4, dim> &
    elasticity() const
    {
      return elasticity_tensor;
    }

    /** The viscosity tensor C (zero in the paper's example). */
    const SymmetricTensor<4, dim> &
    viscosity() const
    {
      return viscosity_tensor;
    }

    bool
    has_viscosity() const
    {
      return viscous;
    }

    /**
     * The coercivity constant c2 of C (H(C)(b), eq. (31)): its smallest
     * eigenvalue as a map on symmetric tensors, min(2 mu_v, 2 mu_v + dim
     * lambda_v) with lambda_v of the plane model; 0 without viscosity.
     */
    double
    viscous_coercivity() const;

    /** Lame constants of E as the plane model uses them. */
    double
    lambda() const
    {
      return lame_lambda;
    }
    double
    mu() const
    {
      return lame_mu;
    }

    /**
     * The constrained (P-wave) modulus lambda + 2 mu of the model: the
     * stiffness of uniaxial strain, sigma_yy = M eps_yy.
     */
    double
    constrained_modulus() const
    {
      return lame_lambda + 2 * lame_mu;
    }

    /** sigma = C eps(w) + E eps(u). */
    SymmetricTensor<2, dim>
    stress(const SymmetricTensor<2, dim> &strain,
           const SymmetricTensor<2, dim> &strain_rate) const;

    /**
     * In 2D, the stress sigma_zz normal to the plane: lambda tr eps(u) +
     * lambda_v tr eps(w) in plane strain, 0 in plane stress (and in 3D).
     */
    double
    out_of_plane_stress(const SymmetricTensor<2, dim> &strain,
                        const SymmetricTensor<2, dim> &strain_rate) const;

  private:
    double                  rho;
    bool                    plane_strain;
    double                  lame_lambda;
    double                  viscous_lambda;
    double                  lame_mu;
    bool                    viscous;
    SymmetricTensor<4, dim> elasticity_tensor;
    SymmetricTensor<4, dim> viscosity_tensor;
  };

  /**
   * Von Mises equivalent stress sqrt(3/2 s:s), s the deviator of the 3D
   * stress; in 2D the stress normal to the plane is @p out_of_plane (zero in
   * plane stress, KelvinVoigtMaterial::out_of_plane_stress() in plane
   * strain).
   */
  template <int dim>
  double
  von_mises_stress(const SymmetricTensor<2, dim> &stress,
                   const double                   out_of_plane = 0);
} // namespace DynamicContact

#endif
