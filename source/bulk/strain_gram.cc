#include <deal.II/base/quadrature_lib.h>
#include <deal.II/matrix_free/fe_evaluation.h>

#include <dynamic_contact/bulk/strain_gram.h>

namespace DynamicContact
{
  template <int dim>
  StrainGram<dim>::StrainGram(const Discretization<dim> &d)
    : discretization(d)
  {}


  template <int dim>
  void
  StrainGram<dim>::reinit()
  {
    typename MatrixFree<dim, double>::AdditionalData data;
    // One thread, cells in a fixed order: the sums do not depend on the
    // threads.
    data.tasks_parallel_scheme =
      MatrixFree<dim, double>::AdditionalData::none;
    data.mapping_update_flags = update_gradients | update_JxW_values;
    matrix_free.reinit(discretization.mapping,
                       discretization.dof_handler,
                       discretization.constraints,
                       QGauss<1>(discretization.fe.degree + 1),
                       data);
    matrix_free.initialize_dof_vector(x_work);
    matrix_free.initialize_dof_vector(y_work);
  }


  template <int dim>
  void
  StrainGram<dim>::import(const Vector_t &source, Work_t &target) const
  {
    const IndexSet &owned = discretization.locally_owned;
    const auto     &local = source.trilinos_vector();
    // Both vectors keep the owned entries in the order of the owned index
    // set.
    AssertDimension(static_cast<unsigned int>(local.MyLength()),
                    owned.n_elements());
    if (owned.is_contiguous())
      for (unsigned int k = 0; k < owned.n_elements(); ++k)
        target.local_element(k) = local[0][k];
    else
      for (unsigned int k = 0; k < owned.n_elements(); ++k)
        target(owned.nth_index_in_set(k)) = local[0][k];
    target.update_ghost_values();
  }


  template <int dim>
  double
  StrainGram<dim>::product(const Vector_t &x, const Vector_t &y) const
  {
    const bool same = (&x == &y);
    import(x, x_work);
    if (!same)
      import(y, y_work);

    // The degree is known at run time only (FEEvaluation's -1).
    FEEvaluation<dim, -1, 0, dim, double> phi_x(matrix_free), phi_y(matrix_free);
    double                                sum = 0;
    for (unsigned int batch = 0; batch < matrix_free.n_cell_batches(); ++batch)
      {
        phi_x.reinit(batch);
        phi_x.read_dof_values(x_work);
        phi_x.evaluate(EvaluationFlags::gradients);
        if (!same)
          {
            phi_y.reinit(batch);
            phi_y.read_dof_values(y_work);
            phi_y.evaluate(EvaluationFlags::gradients);
          }
        const auto         &phi = same ? phi_x : phi_y;
        VectorizedArray<double> cells = 0;
        for (unsigned int q = 0; q < phi_x.n_q_points; ++q)
          cells += scalar_product(phi_x.get_symmetric_gradient(q),
                                  phi.get_symmetric_gradient(q)) *
                   phi_x.JxW(q);
        for (unsigned int lane = 0;
             lane < matrix_free.n_active_entries_per_cell_batch(batch);
             ++lane)
          sum += cells[lane];
      }
    return Utilities::MPI::sum(sum, discretization.comm);
  }


  template <int dim>
  double
  StrainGram<dim>::memory_consumption() const
  {
    return matrix_free.memory_consumption() + x_work.memory_consumption() +
           y_work.memory_consumption();
  }


  template class StrainGram<2>;
  template class StrainGram<3>;
} // namespace DynamicContact
