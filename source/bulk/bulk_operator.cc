#include <dynamic_contact/bulk/bulk_operator.h>

#include <string>

namespace DynamicContact
{
  template <int dim>
  void
  BulkOperator<dim>::reinit(const bool store)
  {
    reinit(store, true);
  }


  template <int dim>
  void
  BulkOperator<dim>::reinit(const bool store, const bool store_newton_matrix)
  {
    Assert(store_newton_matrix || !store,
           ExcMessage("Stored forms come with a stored K0."));
    load_vector.reinit(); // the mesh changed
    stored = store;
    // K0 and its pattern, which the stored forms but M share.
    newton.reinit(store_newton_matrix);
    stored_forms.clear();
    if (stored)
      {
        forms.clear();
        stored_forms.assemble(newton.sparsity_pattern());
      }
    else
      forms.reinit();
    current = TimeScheme();
    discretization.reinit_owned(tmp);
  }


  template <int dim>
  void
  BulkOperator<dim>::set_time_step(const TimeScheme &scheme)
  {
    Assert(scheme.time_step() > 0,
           ExcMessage("The time step must be positive."));
    if (scheme == current)
      return;
    newton.set_time_step(scheme, stored ? &stored_forms : nullptr);
    current = scheme;
  }


  template <int dim>
  void
  BulkOperator<dim>::newton_vmult(Vector_t &dst, const Vector_t &src) const
  {
    newton.vmult(dst, src);
  }


  template <int dim>
  std::vector<Tensor<2, dim>>
  BulkOperator<dim>::newton_blocks(
    const std::vector<std::array<types::global_dof_index, dim>> &nodes) const
  {
    return newton.node_blocks(nodes);
  }


  template <int dim>
  double
  BulkOperator<dim>::product(const Form      form,
                             const Vector_t &x,
                             const Vector_t &y) const
  {
    if (!stored)
      return forms.product(form, x, y);
    stored_forms.matrix(form).vmult(tmp, y);
    return x * tmp;
  }


  template <int dim>
  void
  BulkOperator<dim>::vmult(const Form      form,
                           Vector_t       &dst,
                           const Vector_t &src) const
  {
    if (stored)
      stored_forms.matrix(form).vmult(dst, src);
    else
      forms.vmult(form, dst, src);
  }


  template <int dim>
  void
  BulkOperator<dim>::memory_consumption(MemoryItems &items) const
  {
    // Epetra keeps one graph (the column indices) per pattern, shared by
    // the matrices made from it; each matrix adds its values.
    const double rows  = discretization.locally_owned.n_elements();
    const auto   graph = [&](const std::string                       &name,
                           const TrilinosWrappers::SparsityPattern &p) {
      items.push_back({name,
                       double(p.trilinos_sparsity_pattern().NumMyNonzeros()) *
                           sizeof(int) +
                         rows * 2 * sizeof(int),
                       false});
    };
    const auto values = [&](const std::string &name, const Matrix_t &A) {
      items.push_back(
        {name, stored_values_bytes(A) + rows * sizeof(double *), false});
    };
    if (newton.stored())
      graph("sparsity pattern (shared)", newton.sparsity_pattern());
    if (stored)
      {
        graph("sparsity pattern of M", stored_forms.mass_pattern());
        values("mass matrix M", stored_forms.matrix(Form::mass));
        values("elasticity matrix", stored_forms.matrix(Form::elasticity));
        if (material.has_viscosity())
          values("viscosity matrix", stored_forms.matrix(Form::viscosity));
        if (strain_norm)
          values("strain matrix (norm of V)",
                 stored_forms.matrix(Form::strain));
      }
    else
      items.push_back({"bulk forms (matrix-free cell data)",
                       forms.memory_consumption(),
                       false});
    if (newton.stored())
      values("bulk matrix K0", newton.matrix());
  }


  template <int dim>
  void
  BulkOperator<dim>::assemble_load_vector(const Scene<dim> &scene,
                                          const double      t,
                                          Vector_t         &load) const
  {
    load_vector.assemble(scene, t, load);
  }


  template class BulkOperator<2>;
  template class BulkOperator<3>;
} // namespace DynamicContact
