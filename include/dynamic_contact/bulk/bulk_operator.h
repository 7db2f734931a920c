#ifndef dynamic_contact_bulk_operator_h
#define dynamic_contact_bulk_operator_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/face_load_quadrature.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/bulk/strain_gram.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/time/time_scheme.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The linear part of the scheme (doc/theory.md section 2; the theta-scheme
   * generalizes it, theta = 1 being backward Euler): the mass matrix M
   * (without rho), the elasticity matrix B of a_E and the viscosity matrix A
   * of a_C, assembled once per mesh and condensed with the mesh's
   * constraints, and the bulk Newton matrix
   *   K0 = (rho/k) M + A + k B,
   * formed from them (no reassembly) whenever k changes; and, if asked for,
   * the inner product (eps(u), eps(v)) of V (the norm of the
   * convexification loop's stopping rule), evaluated from the mesh's cells
   * (StrainGram), not stored. Nothing of Gamma_3 is in here: the contact
   * terms are added by the step solver.
   *
   * The matrices share one sparsity pattern, but for M: it couples each
   * displacement component with itself only, so it has a pattern of its
   * own with 1/dim of the entries.
   */
  template <int dim>
  class BulkOperator
  {
  public:
    /**
     * With @p strain_norm, also the inner product of V (strain_product());
     * a scene without a convexification loop does not need it.
     */
    BulkOperator(const Discretization<dim>      &discretization,
                 const KelvinVoigtMaterial<dim> &material,
                 const bool                      strain_norm = true);

    /**
     * Assemble M, B (A if the material is viscous) on the current mesh, and
     * set up the strain product's cell data if asked for.
     */
    void
    reinit();

    /**
     * Form K0 = (rho/k) M + theta A + theta^2 k B for the scheme's time step
     * k and theta (a no-op if both are unchanged).
     */
    void
    set_time_step(const TimeScheme &scheme);

    /** K0 for the last k and theta. */
    const Matrix_t &
    newton_matrix() const
    {
      return bulk_matrix;
    }

    const Matrix_t &
    mass() const
    {
      return mass_matrix;
    }
    const Matrix_t &
    elasticity() const
    {
      return elasticity_matrix;
    }
    /** Only valid if has_viscosity(). */
    const Matrix_t &
    viscosity() const
    {
      return viscosity_matrix;
    }
    bool
    has_viscosity() const
    {
      return material.has_viscosity();
    }

    /** x^T M y etc. for vectors in master form. */
    double
    mass_product(const Vector_t &x, const Vector_t &y) const
    {
      return product(mass_matrix, x, y);
    }
    double
    elastic_product(const Vector_t &x, const Vector_t &y) const
    {
      return product(elasticity_matrix, x, y);
    }
    double
    viscous_product(const Vector_t &x, const Vector_t &y) const
    {
      return material.has_viscosity() ? product(viscosity_matrix, x, y) : 0;
    }
    /**
     * (eps(x), eps(y))_{L^2}: the inner product of V, eq. (22) (only if
     * the operator was made with strain_norm).
     */
    double
    strain_product(const Vector_t &x, const Vector_t &y) const
    {
      Assert(strain_norm, ExcMessage("The inner product of V was not set up."));
      return strain_gram.product(x, y);
    }

    /**
     * The load vector f_n = (f_0(t), v) + (f_2(t), v)_Gamma_2, condensed,
     * at time t.
     */
    void
    assemble_load_vector(const Scene<dim> &scene,
                         const double      t,
                         Vector_t         &load) const;

    /** The time step K0 was formed for (0 before the first call). */
    double
    time_step() const
    {
      return current.time_step();
    }

    /**
     * The scheme (k, theta) K0 was formed for. The solvers get a step's
     * scheme as an argument and check it against this one; what they derive
     * from K0 alone (its factorization, its AMG) is kept for this scheme.
     */
    const TimeScheme &
    scheme() const
    {
      return current;
    }

    /**
     * What the operator holds on this process: the sparsity pattern (one
     * graph, which every matrix shares) and each matrix's values.
     */
    void
    memory_consumption(MemoryItems &items) const;

    /** A sparsity pattern for matrices that share K0's structure. */
    const TrilinosWrappers::SparsityPattern &
    sparsity_pattern() const
    {
      return pattern;
    }

  private:
    const Discretization<dim>      &discretization;
    const KelvinVoigtMaterial<dim> &material;
    const bool                      strain_norm;

    TrilinosWrappers::SparsityPattern pattern;
    /** M's: each component coupled with itself. */
    TrilinosWrappers::SparsityPattern mass_pattern;
    Matrix_t                          mass_matrix;
    Matrix_t                          elasticity_matrix;
    Matrix_t                          viscosity_matrix;
    Matrix_t                          bulk_matrix;
    StrainGram<dim>                   strain_gram;

    /**
     * The locally owned cells with a load (Scene::carries_load), found by
     * the first assemble_load_vector() on a mesh: the load of a step is
     * assembled on them alone.
     */
    mutable std::vector<typename DoFHandler<dim>::active_cell_iterator>
                              loaded_cells;
    mutable const Scene<dim> *loaded_cells_scene = nullptr;
    /** Their loaded faces, and the index of each face's cell in the list. */
    mutable std::vector<typename FaceLoadQuadrature<dim>::Face> loaded_faces;
    mutable std::vector<unsigned int> loaded_face_cell;
    mutable std::vector<Vector<double>> face_values;
    FaceLoadQuadrature<dim>             face_quadrature;
    TimeScheme                current;
    mutable Vector_t          tmp;

    /** x^T A y. */
    double
    product(const Matrix_t &A, const Vector_t &x, const Vector_t &y) const;

    /** The patterns of the mesh, and the matrices on them (zero). */
    void
    reinit_matrices();
  };
} // namespace DynamicContact

#endif
