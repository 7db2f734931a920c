#include <deal.II/lac/full_matrix.h>

#include <dynamic_contact/bulk/stored_forms.h>

#include "bulk_assembly.h"

namespace DynamicContact
{
  template <int dim>
  void
  StoredForms<dim>::clear()
  {
    mass_sparsity.clear();
    for (Matrix_t *m :
         {&mass_matrix, &elasticity_matrix, &viscosity_matrix, &strain_matrix})
      m->clear();
  }


  template <int dim>
  void
  StoredForms<dim>::assemble(const TrilinosWrappers::SparsityPattern &pattern)
  {
    make_pattern(discretization,
                 component_couplings<dim>(/*each_with_itself=*/true),
                 mass_sparsity);
    mass_matrix.reinit(mass_sparsity);
    elasticity_matrix.reinit(pattern);
    if (strain_norm)
      strain_matrix.reinit(pattern);
    if (material.has_viscosity())
      viscosity_matrix.reinit(pattern);

    const unsigned int n = discretization.fe.n_dofs_per_cell();
    FullMatrix<double> local_mass(n, n), local_elasticity(n, n),
      local_viscosity(n, n), local_strain(n, n);
    const auto &E = material.elasticity();
    const auto &C = material.viscosity();
    for_each_point(
      discretization,
      [&](const std::vector<Tensor<1, dim>>          &phi,
          const std::vector<SymmetricTensor<2, dim>> &eps,
          const double                                JxW) {
        for (unsigned int i = 0; i < n; ++i)
          {
            const auto E_eps_i = E * eps[i];
            const auto C_eps_i =
              material.has_viscosity() ? C * eps[i] : E_eps_i;
            for (unsigned int j = 0; j < n; ++j)
              {
                local_mass(i, j) += phi[i] * phi[j] * JxW;
                local_elasticity(i, j) += (E_eps_i * eps[j]) * JxW;
                if (strain_norm)
                  local_strain(i, j) += (eps[i] * eps[j]) * JxW;
                if (material.has_viscosity())
                  local_viscosity(i, j) += (C_eps_i * eps[j]) * JxW;
              }
          }
      },
      [&](const std::vector<types::global_dof_index> &dofs) {
        const auto &constraints = discretization.constraints;
        constraints.distribute_local_to_global(local_mass, dofs, mass_matrix);
        constraints.distribute_local_to_global(local_elasticity,
                                               dofs,
                                               elasticity_matrix);
        if (strain_norm)
          constraints.distribute_local_to_global(local_strain,
                                                 dofs,
                                                 strain_matrix);
        if (material.has_viscosity())
          constraints.distribute_local_to_global(local_viscosity,
                                                 dofs,
                                                 viscosity_matrix);
        for (auto *local :
             {&local_mass, &local_elasticity, &local_viscosity, &local_strain})
          *local = 0;
      });
    mass_matrix.compress(VectorOperation::add);
    elasticity_matrix.compress(VectorOperation::add);
    if (strain_norm)
      strain_matrix.compress(VectorOperation::add);
    if (material.has_viscosity())
      viscosity_matrix.compress(VectorOperation::add);
  }


  template <int dim>
  const Matrix_t &
  StoredForms<dim>::matrix(const Form form) const
  {
    switch (form)
      {
        case Form::mass:
          return mass_matrix;
        case Form::elasticity:
          return elasticity_matrix;
        case Form::viscosity:
          return viscosity_matrix;
        default:
          return strain_matrix;
      }
  }


  template class StoredForms<2>;
  template class StoredForms<3>;
} // namespace DynamicContact
