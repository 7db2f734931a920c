#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/bulk/error_norms.h>

#include <cmath>

namespace DynamicContact
{
  template <int dim>
  Errors
  compute_errors(const Discretization<dim>      &d,
                 const KelvinVoigtMaterial<dim> &material,
                 const Scene<dim>               &scene,
                 const double                    t,
                 const Vector_t                 &u,
                 const Vector_t                 &w)
  {
    Function<dim> &u_exact = scene.exact_displacement();
    Function<dim> &w_exact = scene.exact_velocity();
    u_exact.set_time(t);
    w_exact.set_time(t);

    const QGauss<dim>                    quadrature(d.fe.degree + 2);
    FEValues<dim>                        fe_values =
      d.cell_values(quadrature,
                    update_values | update_gradients |
                      update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    std::vector<Tensor<1, dim>>          w_h(quadrature.size());
    std::vector<Tensor<1, dim>>          grad_u(dim);
    Vector<double>                       w_value(dim);
    double                               strain = 0, velocity = 0, elastic = 0;
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_symmetric_gradients(u, eps);
          fe_values[displacement].get_function_values(w, w_h);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Point<dim> &x = fe_values.quadrature_point(q);
              u_exact.vector_gradient(x, grad_u);
              Tensor<2, dim> gradient;
              for (unsigned int c = 0; c < dim; ++c)
                gradient[c] = grad_u[c];
              const SymmetricTensor<2, dim> e = eps[q] - symmetrize(gradient);
              w_exact.vector_value(x, w_value);
              Tensor<1, dim> dw = w_h[q];
              for (unsigned int c = 0; c < dim; ++c)
                dw[c] -= w_value(c);
              const double JxW = fe_values.JxW(q);
              strain += (e * e) * JxW;
              velocity += dw.norm_square() * JxW;
              elastic += (e * (material.elasticity() * e)) * JxW;
            }
        }
    strain   = Utilities::MPI::sum(strain, d.comm);
    velocity = Utilities::MPI::sum(velocity, d.comm);
    elastic  = Utilities::MPI::sum(elastic, d.comm);
    Errors errors;
    errors.strain   = std::sqrt(strain);
    errors.velocity = std::sqrt(velocity);
    errors.energy   = std::sqrt(material.density() * velocity + elastic);
    return errors;
  }


  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                                \
  template Errors compute_errors<dim>(const Discretization<dim> &,      \
                                      const KelvinVoigtMaterial<dim> &, \
                                      const Scene<dim> &,               \
                                      const double,                     \
                                      const Vector_t &,                 \
                                      const Vector_t &);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
