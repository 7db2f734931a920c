#ifndef dynamic_contact_bulk_stored_forms_h
#define dynamic_contact_bulk_stored_forms_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <dynamic_contact/bulk/cell_operators.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/material.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The bulk forms as stored matrices (BulkOperator with stored forms),
   * assembled once per mesh and condensed with its constraints: the mass
   * form M (without rho) on its own pattern, each component coupled with
   * itself; the elasticity form B, the viscosity form A (if the material is
   * viscous) and the Gram matrix of V (if asked for) on K0's pattern.
   */
  template <int dim>
  class StoredForms
  {
  public:
    using Form = typename CellOperators<dim>::Form;

    /** @p strain_norm: whether the Gram matrix of V is assembled. */
    StoredForms(const Discretization<dim>      &discretization,
                const KelvinVoigtMaterial<dim> &material,
                const bool                      strain_norm)
      : discretization(discretization)
      , material(material)
      , strain_norm(strain_norm)
    {}

    /** Free M's pattern and the matrices. */
    void
    clear();

    /**
     * Set up M's pattern on the current mesh and assemble the forms, all but
     * M on @p pattern (K0's).
     */
    void
    assemble(const TrilinosWrappers::SparsityPattern &pattern);

    /** The stored matrix of @p form. */
    const Matrix_t &
    matrix(const Form form) const;

    /** M's pattern. */
    const TrilinosWrappers::SparsityPattern &
    mass_pattern() const
    {
      return mass_sparsity;
    }

  private:
    const Discretization<dim>      &discretization;
    const KelvinVoigtMaterial<dim> &material;
    const bool                      strain_norm;

    /** M's: each component coupled with itself. */
    TrilinosWrappers::SparsityPattern mass_sparsity;
    Matrix_t                          mass_matrix;
    Matrix_t                          elasticity_matrix;
    Matrix_t                          viscosity_matrix;
    Matrix_t                          strain_matrix;
  };
} // namespace DynamicContact

#endif
