#ifndef dynamic_contact_bulk_operator_h
#define dynamic_contact_bulk_operator_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/face_load_quadrature.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/bulk/cell_operators.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/time/time_scheme.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The linear part of the scheme (doc/theory.md section 2; the theta-scheme
   * generalizes it, theta = 1 being backward Euler): the mass form M
   * (without rho), the elasticity form B of a_E, the viscosity form A of a_C,
   * the inner product (eps(u), eps(v)) of V (the norm of the
   * convexification loop's stopping rule), and the bulk Newton matrix
   *   K0 = (rho/k) M + A + k B,
   * all condensed with the mesh's constraints. Nothing of Gamma_3 is in
   * here: the contact terms are added by the step solver.
   *
   * Two ways to hold the forms, chosen per mesh (reinit()):
   * - stored: M, B, A (and the Gram matrix of V) are assembled once per
   *   mesh and K0 is summed from them when the time scheme changes. Their
   *   products are sparse matrix-vector products, the fastest for the
   *   small meshes of the condensed solver, which takes many of them per
   *   step for its cheap solves.
   * - matrix-free: the forms are applied cell by cell (CellOperators) and
   *   K0, the one stored matrix, is assembled directly when the mesh or
   *   the time scheme changes: 8 bytes per entry of K0's pattern less for
   *   each form (and M's pattern), for the large meshes of the assembled
   *   solver, whose Krylov solves cost far more than the forms' products.
   * The two give the same forms to round-off.
   */
  template <int dim>
  class BulkOperator
  {
  public:
    /**
     * @p strain_norm: whether strain_product() is used (a scene without a
     * convexification loop does not).
     */
    BulkOperator(const Discretization<dim>      &discretization,
                 const KelvinVoigtMaterial<dim> &material,
                 const bool                      strain_norm = true);

    /**
     * Set up K0's pattern and the forms on the current mesh: with
     * @p stored, assemble M, B (A if the material is viscous, the Gram
     * matrix of V if asked for); else set up the forms' cell data.
     */
    void
    reinit(const bool stored);

    /** Whether the forms are stored matrices (the last reinit()). */
    bool
    stores_forms() const
    {
      return stored;
    }

    /**
     * Form K0 = (rho/k) M + theta A + theta^2 k B for the scheme's time step
     * k and theta (a no-op if both are unchanged): summed from the stored
     * matrices, or assembled.
     */
    void
    set_time_step(const TimeScheme &scheme);

    /** K0 for the last k and theta. */
    const Matrix_t &
    newton_matrix() const
    {
      return bulk_matrix;
    }

    /** @p dst = M @p src, for vectors in master form (collective). */
    void
    mass_vmult(Vector_t &dst, const Vector_t &src) const
    {
      vmult(Form::mass, dst, src);
    }
    /** @p dst = B @p src. */
    void
    elasticity_vmult(Vector_t &dst, const Vector_t &src) const
    {
      vmult(Form::elasticity, dst, src);
    }
    /** @p dst = A @p src (only with viscosity). */
    void
    viscosity_vmult(Vector_t &dst, const Vector_t &src) const
    {
      vmult(Form::viscosity, dst, src);
    }
    bool
    has_viscosity() const
    {
      return material.has_viscosity();
    }
    /** The material the forms are made of. */
    const KelvinVoigtMaterial<dim> &
    material_law() const
    {
      return material;
    }

    /** x^T M y etc. for vectors in master form (collective). */
    double
    mass_product(const Vector_t &x, const Vector_t &y) const
    {
      return product(Form::mass, x, y);
    }
    double
    elastic_product(const Vector_t &x, const Vector_t &y) const
    {
      return product(Form::elasticity, x, y);
    }
    double
    viscous_product(const Vector_t &x, const Vector_t &y) const
    {
      return material.has_viscosity() ? product(Form::viscosity, x, y) : 0;
    }
    /**
     * (eps(x), eps(y))_{L^2}: the inner product of V, eq. (22) (only if
     * the operator was made with strain_norm).
     */
    double
    strain_product(const Vector_t &x, const Vector_t &y) const
    {
      Assert(strain_norm, ExcMessage("The inner product of V was not made."));
      return product(Form::strain, x, y);
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
     * graph, which the matrices share; M has its own), each stored matrix's
     * values, or the forms' cell data.
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
    using Form = typename CellOperators<dim>::Form;

    const Discretization<dim>      &discretization;
    const KelvinVoigtMaterial<dim> &material;
    const bool                      strain_norm;

    bool                              stored = true;
    TrilinosWrappers::SparsityPattern pattern;
    /** M's: each component coupled with itself (stored forms only). */
    TrilinosWrappers::SparsityPattern mass_pattern;
    Matrix_t                          mass_matrix;
    Matrix_t                          elasticity_matrix;
    Matrix_t                          viscosity_matrix;
    Matrix_t                          strain_matrix;
    Matrix_t                          bulk_matrix;
    CellOperators<dim>                forms;

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

    /** The stored matrix of @p form. */
    const Matrix_t &
    matrix(const Form form) const;

    /** x^T F y, from the stored matrix or the cells. */
    double
    product(const Form form, const Vector_t &x, const Vector_t &y) const;

    /** @p dst = F @p src, from the stored matrix or the cells. */
    void
    vmult(const Form form, Vector_t &dst, const Vector_t &src) const;

    /** The stored forms: M, B, A, the Gram matrix of V on their patterns. */
    void
    assemble_forms();

    /** K0 assembled cell by cell (matrix-free forms). */
    void
    assemble_bulk_matrix(const TimeScheme &scheme);
  };
} // namespace DynamicContact

#endif
