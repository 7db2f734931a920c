#ifndef dynamic_contact_reduced_system_h
#define dynamic_contact_reduced_system_h

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/contact/boundary_compliance.h>
#include <dynamic_contact/contact/mixed_precision_lu.h>
#include <dynamic_contact/laws/contact_law.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace DynamicContact
{
  /**
   * An iterate of the condensed solver on Gamma_3 and its linearization
   * at every node (every process holds every node, in GatheredBoundary's
   * order).
   */
  template <int dim>
  struct BoundaryIterate
  {
    std::vector<Tensor<1, dim>>         w;      // nodal velocities w_n
    std::vector<Tensor<1, dim>>         lambda; // friction forces
    std::vector<Tensor<1, dim>>         w_old;  // w_{n-1}
    std::vector<NodeLinearization<dim>> lin;
    std::vector<Tensor<1, dim>>         forces;    // f_i at the iterate
    std::vector<Tensor<1, dim>>         base_true; // normal force + slip value
    // The same, minus the springs' s w_i (what condensation with K0' uses);
    // lin[i].block is likewise B_i - s I at spring nodes.
    std::vector<Tensor<1, dim>> g;
    std::vector<Tensor<1, dim>> base;
    // w_free - C g at every node (CondensedSolver's boundary iteration).
    std::vector<Tensor<1, dim>> response;
    std::uint64_t               signature = 0; // of the sets
    std::vector<unsigned int>   active;
    double equilibrium_squares = 0; // sum |w_i - (w_free - C g)_i|^2
    double equilibrium         = 0; // largest
    double f_scale             = 0; // largest force, >= resolvable_force()
    double law_residual        = 0; // largest
    double law_squares         = 0; // sum of squares
  };


  /**
   * The reduced dense system of a Newton step on the active nodes of
   * Gamma_3, the second part of the condensed solver (CondensedSolver):
   *   dw_i + sum_j C_ij (B_j dw_j + T_j l_j) = r_i,
   *   t_s . (w_i + dw_i) = 0 at stick nodes (l_j their tangential force),
   * reduced to the forces. With B_j = U_j V_j^T of rank k_j (a normal law,
   * a 2D slip law: rank 1) and y_j = V_j^T dw_j, dw_i = r_i - sum_j C_ij
   * (U_j y_j + T_j l_j), and the unknowns y and l solve
   *   y_i + V_i^T sum_j C_ij (U_j y_j + T_j l_j) = V_i^T r_i,
   *   t_s^T sum_j C_ij (U_j y_j + T_j l_j) = t_s^T r_i - target_s,
   * sum_j k_j + (dim - 1) n_stick unknowns instead of dim n + (dim - 1)
   * n_stick (the same Newton step; in 2D about half as many unknowns, an
   * LU several times cheaper). The unknown of a stick tangent is c_s l_s,
   * c_s = t_s^T C_ii t_s, so that it is a velocity like y and every entry
   * of the reduced matrix a pure number: its pivoting, and in single
   * precision its accuracy, do not depend on the units of the scene.
   *
   * Systems of large_system unknowns or more are factorized in single
   * precision with refinement (MixedPrecisionLU), and a factorization
   * serves the next matrix of the same layout while its refinement
   * converges (MixedPrecisionLU::reuse_for()): the matrices of successive
   * Newton iterations differ little.
   */
  template <int dim>
  class ReducedSystem
  {
  public:
    ReducedSystem(const GatheredBoundary<dim>   &gathered,
                  const BoundaryCompliance<dim> &compliance)
      : gathered(gathered)
      , compliance(compliance)
    {}

    /**
     * Forget the last factorization: a new step starts afresh, so that a
     * step is solved the same whatever came before it (a resumed run
     * repeats an uninterrupted one to the byte); and C may have changed.
     */
    void
    reset();

    /**
     * One Newton step on the active nodes of @p it for the right-hand side
     * @p r (one entry per active node), with the time scheme @p scheme of
     * the step (the stick condition acts on the weighted velocity): the
     * increments dw, the new friction forces (every node) and the new
     * linearized forces (every node). One step of iterative refinement on
     * the unreduced system removes the round-off of the reduction (a second
     * reduced solve and one more product with C on the active nodes); if
     * @p far_from_solution, it is left out where the reduced system has
     * large_system unknowns or more.
     */
    void
    step(const BoundaryIterate<dim>        &it,
         const TimeScheme                  &scheme,
         const std::vector<Tensor<1, dim>> &r,
         std::vector<Tensor<1, dim>>       &dw,
         std::vector<Tensor<1, dim>>       &lambda,
         std::vector<Tensor<1, dim>>       &new_forces,
         const bool                         far_from_solution = false);

    /**
     * Reduced systems of this many unknowns or more are factorized in
     * single precision (MixedPrecisionLU) and may skip the refinement of
     * step(): below it the O(n^2) work of the refinements costs about what
     * they save.
     */
    static constexpr unsigned int large_system = 512;

    /** The bytes of the dense system and its factor. */
    double
    memory_consumption() const
    {
      return double(matrix.m()) * matrix.n() * sizeof(double) +
             (lu ? lu->memory_consumption() : 0.);
    }

  private:
    const GatheredBoundary<dim>   &gathered;
    const BoundaryCompliance<dim> &compliance;

    /**
     * The last reduced matrix of the step, its factorization (possibly of
     * an earlier matrix of the same layout) and its layout (the active
     * nodes, then the offsets of their unknowns).
     */
    LAPACKFullMatrix<double>          matrix;
    std::unique_ptr<MixedPrecisionLU> lu;
    std::vector<unsigned int>         layout;

    /**
     * The unknowns of the current step, per active node: the row vectors
     * (V_i, then the tangents), the column vectors (U_i, then the
     * tangents over their compliance c_s), the number of low-rank terms, the
     * stick targets, and the offsets of each node's unknowns.
     */
    std::vector<unsigned int>                active;
    std::vector<unsigned int>                offset;
    std::vector<unsigned int>                n_low_rank;
    std::vector<std::vector<Tensor<1, dim>>> row_vectors, column_vectors;
    std::vector<std::vector<double>>         stick_target;
    /** Work space of solve(). */
    std::vector<Tensor<1, dim>> force_change, basis;
    std::vector<double>         basis_value;

    /** The unknowns of each active node of @p it. */
    void
    set_up_unknowns(const BoundaryIterate<dim> &it, const TimeScheme &scheme);

    /** The reduced matrix, and its factorization (or the last one's). */
    void
    assemble_and_factorize();

    /**
     * The reduced system for the right-hand side @p rr and stick targets
     * @p tg: its unknowns @p xx and the velocities @p dd.
     */
    void
    solve(const std::vector<Tensor<1, dim>>      &rr,
          const std::vector<std::vector<double>> &tg,
          Vector<double>                         &xx,
          std::vector<Tensor<1, dim>>            &dd);

    /**
     * dd_a onto the affine constraints its node's rows know exactly
     * (V^T dd = y, t_s . dd = target_s).
     */
    void
    project_onto_rows(const unsigned int                      a,
                      const Vector<double>                   &xx,
                      const std::vector<std::vector<double>> &tg,
                      Tensor<1, dim>                         &dd);

    /** The tangential force at stick node @p a from the unknowns. */
    Tensor<1, dim>
    stick_force(const Vector<double> &xx, const unsigned int a) const;

    /** One step of iterative refinement of @p x and @p dw. */
    void
    refine(const BoundaryIterate<dim>        &it,
           const std::vector<Tensor<1, dim>> &r,
           Vector<double>                    &x,
           std::vector<Tensor<1, dim>>       &dw);
  };
} // namespace DynamicContact

#endif
