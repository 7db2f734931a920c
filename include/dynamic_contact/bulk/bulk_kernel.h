#ifndef dynamic_contact_bulk_kernel_h
#define dynamic_contact_bulk_kernel_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/matrix_free/evaluation_flags.h>

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/laws/material.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The integrand of the bulk matrix K0 = (rho/k) M + theta A + theta^2 k B
   * for a time scheme: (m u, v) + (S eps(u), eps(v)) with m = rho/k and
   * S = theta C + theta^2 k E. One definition for the assembly of K0
   * (BulkOperator) and for its applications cell by cell (CellOperators,
   * the levels of BulkMultigrid). An isotropic S = lambda I (x) I + 2 mu Id
   * is applied as such, a fifth of the operations of the general
   * contraction.
   */
  template <int dim>
  class BulkKernel
  {
  public:
    BulkKernel() = default;

    BulkKernel(const TimeScheme &scheme, const KelvinVoigtMaterial<dim> &material)
      : mass(scheme.mass_coefficient(material.density()))
      , stiffness(scheme.elasticity_coefficient() * material.elasticity())
    {
      if (material.has_viscosity())
        stiffness += scheme.viscosity_coefficient() * material.viscosity();
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = k; l < dim; ++l)
              vectorized[i][j][k][l] = stiffness[i][j][k][l];
      const double lambda_ = stiffness[0][0][1][1];
      const double mu      = stiffness[0][1][0][1];
      const SymmetricTensor<4, dim> iso =
        lambda_ * outer_product(unit_symmetric_tensor<dim>(),
                                unit_symmetric_tensor<dim>()) +
        2 * mu * identity_tensor<dim>();
      isotropic = (iso - stiffness).norm() <= 1e-12 * stiffness.norm();
      lambda    = lambda_;
      two_mu    = 2 * mu;
    }

    /** m = rho/k. */
    double mass = 0;
    /** S = theta C + theta^2 k E. */
    SymmetricTensor<4, dim> stiffness;

    /**
     * On the cell batch of @p phi (an FEEvaluation of the vector field
     * with its values read): evaluate, submit m u and S eps(u), integrate.
     */
    template <typename Evaluation>
    void
    apply(Evaluation &phi) const
    {
      phi.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
      for (unsigned int q = 0; q < phi.n_q_points; ++q)
        {
          phi.submit_value(mass * phi.get_value(q), q);
          const auto eps = phi.get_symmetric_gradient(q);
          if (isotropic)
            {
              auto                          sigma      = two_mu * eps;
              const VectorizedArray<double> volumetric = lambda * trace(eps);
              for (unsigned int d = 0; d < dim; ++d)
                sigma[d][d] += volumetric;
              phi.submit_symmetric_gradient(sigma, q);
            }
          else
            phi.submit_symmetric_gradient(vectorized * eps, q);
        }
      phi.integrate(EvaluationFlags::values | EvaluationFlags::gradients);
    }

  private:
    SymmetricTensor<4, dim, VectorizedArray<double>> vectorized;
    bool                                             isotropic = false;
    VectorizedArray<double>                          lambda    = 0;
    VectorizedArray<double>                          two_mu    = 0;
  };
} // namespace DynamicContact

#endif
