#ifndef dynamic_contact_bulk_operator_h
#define dynamic_contact_bulk_operator_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/bulk/bulk_load.h>
#include <dynamic_contact/bulk/bulk_newton_matrix.h>
#include <dynamic_contact/bulk/cell_operators.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/bulk/stored_forms.h>
#include <dynamic_contact/laws/material.h>

#include <array>
#include <vector>

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
   *
   * The operator owns its parts: the stored forms (StoredForms), K0
   * (BulkNewtonMatrix), the forms' cell data (CellOperators) and the load
   * vector's cells and quadrature (BulkLoad).
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
                 const bool                      strain_norm = true)
      : discretization(discretization)
      , material(material)
      , strain_norm(strain_norm)
      , forms(discretization, material)
      , stored_forms(discretization, material, strain_norm)
      , newton(discretization, material, forms)
      , load_vector(discretization)
    {}

    /**
     * Set up K0's pattern and the forms on the current mesh: with
     * @p stored, assemble M, B (A if the material is viscous, the Gram
     * matrix of V if asked for); else set up the forms' cell data.
     */
    void
    reinit(const bool stored);

    /**
     * The same, with @p store_newton_matrix false: K0 not stored either
     * (matrix-free forms only), applied cell by cell (newton_vmult()),
     * its nodal blocks computed from the cells (newton_blocks()). For the
     * assembled solver with Solver/Preconditioner = matrix-free GMG.
     */
    void
    reinit(const bool stored, const bool store_newton_matrix);

    /** Whether K0 is a stored matrix (newton_matrix()). */
    bool
    stores_newton_matrix() const
    {
      return newton.stored();
    }

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

    /**
     * The cell data of the forms on the current mesh (reinit_cell_data()),
     * or nullptr where the forms are stored matrices.
     */
    const MatrixFree<dim, double> *
    cell_data() const
    {
      return stored ? nullptr : &forms.cell_data();
    }

    /** K0 for the last k and theta (only if stores_newton_matrix()). */
    const Matrix_t &
    newton_matrix() const
    {
      Assert(newton.stored(), ExcMessage("K0 is not stored."));
      return newton.matrix();
    }

    /**
     * @p dst = K0 @p src for vectors in master form (collective): the
     * stored K0, or cell by cell.
     */
    void
    newton_vmult(Vector_t &dst, const Vector_t &src) const;

    /**
     * The dim x dim blocks of K0 at nodes: blocks[p][a][b] = K0(dofs[p][a],
     * dofs[p][b]) for DoFs this process owns, from the stored K0 or from the
     * cells (collective then: each process's owned cells, condensed with
     * the constraints as the stored K0 is, summed over the processes; a
     * constrained DoF's diagonal entry is the mean of its node's
     * unconstrained ones there, as it is a stand-in in the stored K0 too).
     */
    std::vector<Tensor<2, dim>>
    newton_blocks(
      const std::vector<std::array<types::global_dof_index, dim>> &dofs) const;

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
      return newton.sparsity_pattern();
    }

  private:
    using Form = typename CellOperators<dim>::Form;

    const Discretization<dim>      &discretization;
    const KelvinVoigtMaterial<dim> &material;
    const bool                      strain_norm;

    /** Whether the forms are stored matrices (the last reinit()). */
    bool stored = true;
    /** The forms applied cell by cell (matrix-free forms). */
    CellOperators<dim> forms;
    /** The forms as matrices (stored forms). */
    StoredForms<dim> stored_forms;
    /** K0, stored or applied cell by cell. */
    BulkNewtonMatrix<dim> newton;
    /** The loaded cells and faces of the load vector. */
    BulkLoad<dim> load_vector;
    /** The time scheme K0 was formed for. */
    TimeScheme       current;
    mutable Vector_t tmp;

    /** x^T F y, from the stored matrix or the cells. */
    double
    product(const Form form, const Vector_t &x, const Vector_t &y) const;

    /** @p dst = F @p src, from the stored matrix or the cells. */
    void
    vmult(const Form form, Vector_t &dst, const Vector_t &src) const;
  };


  /** K0 as an operator for deal.II's solvers: BulkOperator::newton_vmult(). */
  template <int dim>
  struct BulkMatrixOperator
  {
    const BulkOperator<dim> &bulk;

    void
    vmult(Vector_t &dst, const Vector_t &src) const
    {
      bulk.newton_vmult(dst, src);
    }
  };
} // namespace DynamicContact

#endif
