#include <deal.II/base/quadrature_lib.h>
#include <deal.II/matrix_free/fe_evaluation.h>

#include <dynamic_contact/bulk/bulk_kernel.h>
#include <dynamic_contact/bulk/cell_operators.h>

namespace DynamicContact
{
  namespace
  {
    template <int dim>
    SymmetricTensor<4, dim, VectorizedArray<double>>
    vectorized(const SymmetricTensor<4, dim> &T)
    {
      SymmetricTensor<4, dim, VectorizedArray<double>> V;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = k; l < dim; ++l)
              V[i][j][k][l] = T[i][j][k][l];
      return V;
    }
  } // namespace


  void
  copy_owned(const Vector_t                             &source,
             LinearAlgebra::distributed::Vector<double> &target)
  {
    const auto &local = source.trilinos_vector();
    AssertDimension(static_cast<unsigned int>(local.MyLength()),
                    target.locally_owned_size());
    for (int k = 0; k < local.MyLength(); ++k)
      target.local_element(k) = local[0][k];
  }


  void
  copy_owned(const LinearAlgebra::distributed::Vector<double> &source,
             Vector_t                                         &target)
  {
    auto &local = target.trilinos_vector();
    AssertDimension(static_cast<unsigned int>(local.MyLength()),
                    source.locally_owned_size());
    for (int k = 0; k < local.MyLength(); ++k)
      local[0][k] = source.local_element(k);
  }


  template <int dim>
  void
  reinit_cell_data(MatrixFree<dim, double>         &matrix_free,
                   const Mapping<dim>              &mapping,
                   const DoFHandler<dim>           &dof_handler,
                   const AffineConstraints<double> &constraints)
  {
    typename MatrixFree<dim, double>::AdditionalData data;
    // One thread, cells in a fixed order: the sums do not depend on the
    // threads.
    data.tasks_parallel_scheme =
      MatrixFree<dim, double>::AdditionalData::none;
    data.mapping_update_flags =
      update_values | update_gradients | update_JxW_values;
    matrix_free.reinit(mapping,
                       dof_handler,
                       constraints,
                       QGauss<1>(dof_handler.get_fe().degree + 1),
                       data);
  }


  template <int dim>
  CellOperators<dim>::CellOperators(const Discretization<dim>      &d,
                                    const KelvinVoigtMaterial<dim> &material)
    : discretization(d)
    , elasticity(vectorized(material.elasticity()))
    , viscosity(vectorized(material.viscosity()))
  {}


  template <int dim>
  void
  CellOperators<dim>::reinit()
  {
    reinit_cell_data(matrix_free,
                     discretization.mapping,
                     discretization.dof_handler,
                     discretization.constraints);
    matrix_free.initialize_dof_vector(x_work);
    matrix_free.initialize_dof_vector(y_work);
  }


  template <int dim>
  void
  CellOperators<dim>::clear()
  {
    matrix_free.clear();
    x_work.reinit(0);
    y_work.reinit(0);
  }


  template <int dim>
  const typename CellOperators<dim>::Tensor4_t &
  CellOperators<dim>::tensor(const Form form) const
  {
    return form == Form::viscosity ? viscosity : elasticity;
  }


  template <int dim>
  void
  CellOperators<dim>::import(const Vector_t &source, Work_t &target) const
  {
    target.zero_out_ghost_values();
    copy_owned(source, target);
    target.update_ghost_values();
  }


  namespace
  {
    /**
     * x^T F y on this process's cells, F as CellOperators::product() says,
     * with the FEEvaluation of the polynomial degree @p degree (-1: known
     * at run time only, slower).
     */
    template <int dim, int degree, typename Form, typename Tensor4>
    double
    local_product(const MatrixFree<dim, double>                    &mf,
                  const Form                                        form,
                  const Tensor4                                    &T,
                  const LinearAlgebra::distributed::Vector<double> &x,
                  const LinearAlgebra::distributed::Vector<double> &y,
                  const bool                                        same)
    {
      const auto flags = (form == Form::mass ? EvaluationFlags::values :
                                               EvaluationFlags::gradients);
      const bool stress = (form == Form::elasticity || form == Form::viscosity);
      FEEvaluation<dim, degree, degree + 1, dim, double> phi_x(mf), phi_y(mf);
      double sum = 0;
      for (unsigned int batch = 0; batch < mf.n_cell_batches(); ++batch)
        {
          phi_x.reinit(batch);
          phi_x.read_dof_values(x);
          phi_x.evaluate(flags);
          if (!same)
            {
              phi_y.reinit(batch);
              phi_y.read_dof_values(y);
              phi_y.evaluate(flags);
            }
          const auto             &phi   = same ? phi_x : phi_y;
          VectorizedArray<double> cells = 0;
          for (unsigned int q = 0; q < phi_x.n_q_points; ++q)
            {
              VectorizedArray<double> integrand;
              if (form == Form::mass)
                integrand = phi_x.get_value(q) * phi.get_value(q);
              else if (stress)
                integrand =
                  scalar_product(T * phi_x.get_symmetric_gradient(q),
                                 phi.get_symmetric_gradient(q));
              else
                integrand = scalar_product(phi_x.get_symmetric_gradient(q),
                                           phi.get_symmetric_gradient(q));
              cells += integrand * phi_x.JxW(q);
            }
          for (unsigned int lane = 0;
               lane < mf.n_active_entries_per_cell_batch(batch);
               ++lane)
            sum += cells[lane];
        }
      return sum;
    }


    /**
     * y += F x on this process's cells (before compress), F given by
     * @p apply(phi) on each cell batch (evaluate, submit, integrate), with
     * the FEEvaluation of the polynomial degree @p degree as above.
     */
    template <int dim, int degree, typename Apply>
    void
    local_vmult(const MatrixFree<dim, double>                    &mf,
                const Apply                                      &apply,
                LinearAlgebra::distributed::Vector<double>       &y,
                const LinearAlgebra::distributed::Vector<double> &x)
    {
      FEEvaluation<dim, degree, degree + 1, dim, double> phi(mf);
      for (unsigned int batch = 0; batch < mf.n_cell_batches(); ++batch)
        {
          phi.reinit(batch);
          phi.read_dof_values(x);
          apply(phi);
          phi.distribute_local_to_global(y);
        }
    }


    /** The form @p form of CellOperators on a cell batch. */
    template <typename Form, typename Tensor4>
    struct ApplyForm
    {
      const Form     form;
      const Tensor4 &T;

      template <typename Evaluation>
      void
      operator()(Evaluation &phi) const
      {
        const auto flags = (form == Form::mass ? EvaluationFlags::values :
                                                 EvaluationFlags::gradients);
        phi.evaluate(flags);
        for (unsigned int q = 0; q < phi.n_q_points; ++q)
          if (form == Form::mass)
            phi.submit_value(phi.get_value(q), q);
          else if (form == Form::strain)
            phi.submit_symmetric_gradient(phi.get_symmetric_gradient(q), q);
          else
            phi.submit_symmetric_gradient(T * phi.get_symmetric_gradient(q),
                                          q);
        phi.integrate(flags);
      }
    };
  } // namespace


  template <int dim>
  double
  CellOperators<dim>::product(const Form      form,
                              const Vector_t &x,
                              const Vector_t &y) const
  {
    const bool same = (&x == &y);
    import(x, x_work);
    if (!same)
      import(y, y_work);
    const Tensor4_t &T = tensor(form);
    double           sum;
    // The common degrees compiled for their degree, the others at run
    // time.
    switch (discretization.fe.degree)
      {
        case 1:
          sum = local_product<dim, 1>(matrix_free, form, T, x_work, y_work, same);
          break;
        case 2:
          sum = local_product<dim, 2>(matrix_free, form, T, x_work, y_work, same);
          break;
        default:
          sum =
            local_product<dim, -1>(matrix_free, form, T, x_work, y_work, same);
      }
    return Utilities::MPI::sum(sum, discretization.comm);
  }


  template <int dim>
  template <typename Apply>
  void
  CellOperators<dim>::apply_cells(const Apply    &apply,
                                  Vector_t       &dst,
                                  const Vector_t &src) const
  {
    import(src, x_work);
    y_work = 0;
    switch (discretization.fe.degree)
      {
        case 1:
          local_vmult<dim, 1>(matrix_free, apply, y_work, x_work);
          break;
        case 2:
          local_vmult<dim, 2>(matrix_free, apply, y_work, x_work);
          break;
        default:
          local_vmult<dim, -1>(matrix_free, apply, y_work, x_work);
      }
    y_work.compress(VectorOperation::add);

    copy_owned(y_work, dst);
  }


  template <int dim>
  void
  CellOperators<dim>::vmult(const Form      form,
                            Vector_t       &dst,
                            const Vector_t &src) const
  {
    apply_cells(ApplyForm<Form, Tensor4_t>{form, tensor(form)}, dst, src);
  }


  template <int dim>
  void
  CellOperators<dim>::vmult(const BulkKernel<dim> &kernel,
                            Vector_t              &dst,
                            const Vector_t        &src) const
  {
    apply_cells([&kernel](auto &phi) { kernel.apply(phi); }, dst, src);
  }


  template <int dim>
  double
  CellOperators<dim>::memory_consumption() const
  {
    return matrix_free.memory_consumption() + x_work.memory_consumption() +
           y_work.memory_consumption();
  }


  template void
  reinit_cell_data(MatrixFree<2, double> &,
                   const Mapping<2> &,
                   const DoFHandler<2> &,
                   const AffineConstraints<double> &);
  template void
  reinit_cell_data(MatrixFree<3, double> &,
                   const Mapping<3> &,
                   const DoFHandler<3> &,
                   const AffineConstraints<double> &);
  template class CellOperators<2>;
  template class CellOperators<3>;
} // namespace DynamicContact
