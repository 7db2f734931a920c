#ifndef dynamic_contact_condensed_newton_h
#define dynamic_contact_condensed_newton_h

#include <deal.II/lac/full_matrix.h>

#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/contact/contact_newton.h>
#include <dynamic_contact/contact/mixed_precision_lu.h>
#include <dynamic_contact/contact/system_newton.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>

namespace DynamicContact
{
  /**
   * Semismooth Newton by static condensation onto Gamma_3. Everything off
   * Gamma_3 is linear, so with w_free = K0^{-1} b and the compliance
   * (Delassus) matrix of the nodes, C_ij = P_i [K0^{-1}]_ij P_j^T,
   *   w_i = w_free,i - sum_j C_ij f_j(w_j, lambda_j)
   * is the whole nonlinear problem, of the size of the contact zone. Each
   * Newton iteration solves a dense system on the active nodes (stick
   * constraints as equations with the tangential forces as unknowns);
   * nothing of size of the mesh is factorized more than once per mesh and
   * time step. With a CHOLMOD factor (one process, or the whole factor on
   * every process) C is the inverse of the Schur complement of K0' on
   * Gamma_3, all of it at once (the factorization eliminates the DoFs of
   * Gamma_3 last: BulkSolver::inverse_block()); with MUMPS in 3D likewise
   * from MUMPS's Schur complement where it agrees with the solves;
   * else the columns of C are computed when a node first becomes active
   * (dim solves with the factorized K0 each). C is kept while K0 is
   * unchanged. A step costs a solve with K0 for w_free, one for the
   * velocity of each convexification pass, and in the whole-system phase
   * one plus one or two per Newton step (newton_step()), plus the dense
   * iterations.
   *
   * What is factorized is K0' = K0 + S, S stiff springs (s I, s the largest
   * diagonal entry of K0 there) at two (2D) or three (3D) extreme nodes of
   * Gamma_3: a body held only by the foundation has rigid motions that K0
   * restrains by inertia alone, and K0 is then too ill-conditioned for the
   * condensation to reach a tight tolerance. The springs are removed again
   * exactly: their nodes enter the dense system with the force f - S w and
   * the block B - S, so the Newton iterates are those of K0.
   *
   * Two phases, each a globalized_newton() iteration: on Gamma_3 alone
   * (w_Gamma = w_free - C f, no solve with K0 but for new columns of C),
   * which finds the active sets, then on the whole system, whose Newton
   * steps this class solves by the same condensation (the LinearBackend
   * role: a solve with K0', a dense solve and a solve with K0' or a sum of
   * stored columns each), which polishes the
   * solution where the cancellation in w_free - C f limits phase 1.
   *
   * The dense tables couple every pair of nodes, so Gamma_3 is replicated on
   * every process (GatheredBoundary): the right choice while the contact
   * boundary is small (Solver/Contact solver = auto decides).
   */
  template <int dim>
  class CondensedNewton : public ContactNewton<dim>, public LinearBackend<dim>
  {
  public:
    using Result = ContactNewtonResult;

    explicit CondensedNewton(const ContactProblem<dim> &problem);

    void
    reinit() override;

    Result
    solve(const Vector_t                    &rhs,
          const std::vector<Tensor<1, dim>> &u_old,
          const std::vector<Tensor<1, dim>> &w_old,
          const FrictionCoefficients        &mu,
          std::vector<Tensor<1, dim>>       &lambda,
          Vector_t                          &w) override;

    /**
     * Phase 1 only, stopped at the relative residual @p velocity_accuracy
     * / w_scale if that is larger than the Newton tolerance: the nodal
     * velocities w_free - C g of its iterate, no solve with K0' (w is left
     * as it was).
     */
    Result
    solve_provisional(const Vector_t                    &rhs,
                      const std::vector<Tensor<1, dim>> &u_old,
                      const std::vector<Tensor<1, dim>> &w_old,
                      const FrictionCoefficients        &mu,
                      std::vector<Tensor<1, dim>>       &lambda,
                      Vector_t                          &w,
                      const double velocity_accuracy = 0) override;

    /**
     * Phase 2 of the last provisional solve: the solution itself; the
     * earlier pass's velocity K0'^{-1} (b - sum_j P_j^T g_j) in one block
     * solve with the first solve of phase 2.
     */
    Result
    finalize(Vector_t                    &w,
             std::vector<Tensor<1, dim>> &lambda,
             Vector_t                    *previous = nullptr) override;

    std::vector<Tensor<1, dim>>
    provisional_velocities() const override;

    /** From the dense compliance C of Gamma_3 (every node, replicated). */
    double
    compliance_radius(const std::vector<Tensor<2, dim>> &roots) override;

    /** The whole-system Newton step by condensation (phase 2). */
    void
    newton_step(const SystemNewton<dim>  &system,
                const SystemIterate<dim> &x,
                SystemIterate<dim>       &full,
                Result                   &result) override;

  private:
    const ContactProblem<dim> problem;
    /** Gamma_3 on every process, in one order. */
    GatheredBoundary<dim> gathered;

    /** K0' = K0 + S (see above), factorized. */
    Matrix_t regularized;
    /** The spring nodes (indices into all_nodes()) and their stiffness. */
    std::vector<unsigned int> spring_nodes;
    std::vector<double>       spring_stiffness; // one per node of all_nodes()

    /** Solver for K0': a factorization, or CG with AMG. */
    BulkSolver bulk_solver;
    TimeScheme prepared_scheme;

    /** columns[j][i] = C_ij, empty until node j was first active. */
    std::vector<std::vector<Tensor<2, dim>>> columns;
    /** For each node of all_nodes(): its index among the owned nodes, or -1. */
    std::vector<int> owned_index;

    /** The data of the current solve at every node. */
    std::vector<Tensor<1, dim>> u_old_all, w_old_all;
    FrictionCoefficients        mu_all;

    /**
     * The whole responses K0'^{-1} P_j^T e_c (owned entries, index
     * dim j + c), kept beside C while they fit in full_column_budget bytes
     * on every process and a sum of all of them reads fewer numbers than a
     * solve (BulkSolver::solve_cost(): with MUMPS; with a Cholesky factor a
     * solve is as fast or faster): with them a provisional velocity or a
     * whole-system step is a sum of columns instead of a solve with K0'.
     */
    std::vector<std::vector<double>> full_columns;
    std::size_t                      stored_full_columns = 0;
    /**
     * Node j's whole responses are stored (the same on every process: a
     * process that owns no DoF stores empty ones).
     */
    std::vector<bool> full_column_stored;
    /** The largest number of owned DoFs of a process. */
    types::global_dof_index      max_owned_dofs     = 0;
    static constexpr std::size_t full_column_budget = std::size_t(512) << 20;

    /**
     * x = K0'^{-1} sum_{j in nodes} P_j^T f_j from the stored whole columns;
     * false (and x untouched) if some column is not stored. The same answer
     * on every process.
     */
    bool
    apply_full_columns(const std::vector<Tensor<1, dim>> &f,
                       const std::vector<unsigned int>   &nodes,
                       Vector_t                          &x) const;


    Vector_t solution, right_hand_side, residual, increment, scratch;

    /** K0'^{-1} b for the last b (the passes of a step share it). */
    Vector_t                    free_response, cached_rhs;
    std::vector<Tensor<1, dim>> w_free_nodes;
    bool                        free_response_valid = false;

    /** The linearization of every node at an iterate. */
    struct Iterate
    {
      std::vector<Tensor<1, dim>>         w;      // nodal velocities w_n
      std::vector<Tensor<1, dim>>         lambda; // friction forces
      std::vector<Tensor<1, dim>>         w_old;  // w_{n-1}
      std::vector<NodeLinearization<dim>> lin;
      std::vector<Tensor<1, dim>>         forces; // f_i at the iterate
      std::vector<Tensor<1, dim>> base_true;      // normal force + slip value
      // The same, minus the springs' s w_i (what condensation with K0' uses);
      // lin[i].block is likewise B_i - s I at spring nodes.
      std::vector<Tensor<1, dim>> g;
      std::vector<Tensor<1, dim>> base;
      // w_free - C g at every node (BoundaryProblem::evaluate()).
      std::vector<Tensor<1, dim>> response;
      std::uint64_t               signature = 0; // of the sets
      std::vector<unsigned int>   active;
      double equilibrium_squares = 0; // sum |w_i - (w_free - C g)_i|^2
      double equilibrium         = 0; // largest
      double f_scale             = 0;
      double law_residual        = 0; // largest
      double law_squares         = 0; // sum of squares
    };

    /** Linearize every node at it.w, it.lambda (the current solve's data). */
    void
    linearize(Iterate &it) const;

    /** Phase 1 as globalized_newton() sees it (defined in the .cc). */
    class BoundaryProblem;

    /**
     * What a provisional solve leaves for finalize(): its data (owned
     * nodes) and the phase-1 iterate (every node).
     */
    struct Pending
    {
      std::vector<Tensor<1, dim>> u_old, w_old;
      FrictionCoefficients        mu;
      Iterate                     it;
      /** The velocity scale of phase 1, and whether it stopped early. */
      double w_scale = 0;
      bool   loose   = false;
    };
    std::optional<Pending> pending;
    /**
     * The nodal forces g (every node) and the nodes with a force of the
     * provisional solve before the pending one, if the pending one followed
     * another in the same step.
     */
    std::optional<
      std::pair<std::vector<Tensor<1, dim>>, std::vector<unsigned int>>>
      previous_pass;


    /** solve() and solve_provisional(). */
    Result
    solve(const Vector_t                    &rhs,
          const std::vector<Tensor<1, dim>> &u_old,
          const std::vector<Tensor<1, dim>> &w_old,
          const FrictionCoefficients        &mu,
          std::vector<Tensor<1, dim>>       &lambda,
          Vector_t                          &w,
          const bool                         provisional,
          const double                       velocity_accuracy = 0);

    /**
     * Phase 1 on the current solve's data from @p it, to the relative
     * residual max(Newton tolerance, @p tolerance).
     */
    void
    boundary_newton(Iterate     &it,
                    const double w_scale,
                    const double tolerance,
                    Result      &result);

    /**
     * From the phase-1 iterate @p it: w = K0'^{-1}(b - sum P^T g), then
     * phase 2 (the whole-system Newton iteration) on the data given, to
     * Solver/Newton tolerance. (The finishing solve of a loop of
     * provisional passes once took a Newton step even below the tolerance,
     * down to 0.1 of it, for a stick node of the critical-speed stress
     * scene; since the reduced dense step's refinement its start is as good
     * as any, and that step cost the paper's scene a quarter of its solves.)
     */
    void
    polish(const Iterate                     &it,
           const std::vector<Tensor<1, dim>> &u_old,
           const std::vector<Tensor<1, dim>> &w_old,
           const FrictionCoefficients        &mu,
           std::vector<Tensor<1, dim>>       &lambda,
           Vector_t                          &w,
           Result                            &result,
           Vector_t                          *previous = nullptr);

    /**
     * One Newton step on the active nodes for the right-hand side @p r (one
     * entry per active node): the increments dw, the new friction forces
     * (every node) and the new linearized forces (every node). One step
     * of iterative refinement on the unreduced system removes the
     * round-off of the reduction (a second reduced solve and one more
     * product with C on the active nodes); if @p far_from_solution, it is
     * left out where the reduced system has large_system unknowns or more.
     * Measured with the caller's rule (phase 1 refines below a residual of
     * 1e-3): the 3D rail 80 x 8 x 8, 32 steps, 3 to 7 % faster with the
     * same 445 Newton iterations, the rail 110 x 11 x 11, 4 steps, 3 %;
     * the paper's scene (systems below 512 unknowns) is unchanged. Left
     * out for every size, the paper's scene took 964 Newton iterations
     * instead of 948 and 465 solves with K0 instead of 443.
     */
    void
    dense_step(const Iterate                     &it,
               const std::vector<Tensor<1, dim>> &r,
               std::vector<Tensor<1, dim>>       &dw,
               std::vector<Tensor<1, dim>>       &lambda,
               std::vector<Tensor<1, dim>>       &new_forces,
               const bool far_from_solution = false) const;

    /**
     * Reduced systems of this many unknowns or more are factorized in
     * single precision (MixedPrecisionLU) and may skip the refinement of
     * dense_step(): below it the O(n^2) work of the refinements costs
     * about what they save.
     */
    static constexpr unsigned int large_system = 512;

    /**
     * The coupled linearization's limits of every node (WeakeningLimit),
     * for the K0 they were measured with.
     */
    std::vector<double> weakening_limits;
    TimeScheme          limits_scheme;
    /** Measure them if K0 changed (collective). */
    const std::vector<double> &
    coupled_limits(Result &result);

    /**
     * The last reduced matrix of the step, its factorization (possibly of
     * an earlier matrix of the same layout: MixedPrecisionLU::reuse_for())
     * and its layout (the active nodes, then the offsets of their
     * unknowns). Reset with a new step or a new C. Measured on the 3D rail
     * 80 x 8 x 8, 32 steps (systems of 600 to 1050 unknowns, whose matrices
     * change by 1e-4 to 1e-1 from one Newton iteration to the next): the
     * same Newton iterations to one (445, 446), the float LU's share of the
     * run 19 % -> 11 %, wall time ratios 0.90 and 0.94 against the build
     * without it (two series of alternating runs).
     */
    struct Reduced
    {
      LAPACKFullMatrix<double>          matrix;
      std::unique_ptr<MixedPrecisionLU> lu;
      std::vector<unsigned int>         layout;
    };
    mutable Reduced reduced;

    /** v += factor sum_i P_i^T f_i over the owned nodes (f at every node). */
    void
    add_nodal_forces(const std::vector<Tensor<1, dim>> &f,
                     const double                       factor,
                     Vector_t                          &v) const;

    /** The coefficients of the owned nodes at every node (collective). */
    FrictionCoefficients
    gather_coefficients(const FrictionCoefficients &mu) const
    {
      return {gathered.gather(mu.frozen),
              mu.law,
              mu.weakening_limit.empty() ?
                std::vector<double>() :
                gathered.gather(mu.weakening_limit)};
    }

    /** The nodal values of a vector at every node (collective). */
    std::vector<Tensor<1, dim>>
    gather_values(const Vector_t &v) const
    {
      return gathered.gather(problem.boundary.values(v));
    }

    /** Choose the spring nodes (once per mesh). */
    void
    choose_spring_nodes();

    /** Factorize K0' (or build AMG) if k changed; drop C if so. */
    void
    prepare(Result &result);

    /** x = K0'^{-1} b. */
    void
    solve_bulk(const Vector_t &b, Vector_t &x, Result &result);

    /** x_c = K0'^{-1} b_c, in one block solve where that is cheaper. */
    void
    solve_bulk(const std::vector<const Vector_t *> &b,
               const std::vector<Vector_t *>       &x,
               Result                              &result);

    /** Make sure C_:j exists for every j of @p nodes (one block solve). */
    void
    compute_columns(const std::vector<unsigned int> &nodes, Result &result);

    /**
     * The compliance of K0 itself (not of K0' = K0 + S) between nodes of
     * Gamma_3: @p v[a] = sum_b [K0^{-1}]_{nodes[a] nodes[b]} @p f[b], from
     * C' = K0'^{-1} (the table) and the springs removed by the Woodbury
     * identity, K0^{-1} = C' + C' P^T (S^{-1} - P C' P^T)^{-1} P C' (P the
     * springs' DoFs): what the uniqueness measures and the weakening limit
     * see, as the assembled solver does. Makes the columns it needs.
     */
    void
    apply_k0_compliance(const std::vector<unsigned int>   &nodes,
                        const std::vector<Tensor<1, dim>> &f,
                        std::vector<Tensor<1, dim>>       &v,
                        Result                            &result);
    /**
     * (S^{-1} - P C' P^T)^{-1} of apply_k0_compliance() and the springs'
     * (node, component) pairs, for the K0' they were made with.
     */
    FullMatrix<double>                                 spring_correction;
    std::vector<std::pair<unsigned int, unsigned int>> spring_dofs;
    TimeScheme                                         correction_scheme;

    /** w_i = w_free,i - sum_j C_ij f_j over the nodes with a force. */
    void
    compliance_response(const std::vector<Tensor<1, dim>> &w_free,
                        const std::vector<Tensor<1, dim>> &forces,
                        const std::vector<unsigned int>   &with_force,
                        std::vector<Tensor<1, dim>>       &w) const;

    /** w_i -= sum_j C_ij f_j over the nodes @p nodes. */
    void
    subtract_compliance(const std::vector<Tensor<1, dim>> &forces,
                        const std::vector<unsigned int>   &nodes,
                        std::vector<Tensor<1, dim>>       &w) const;
  };
} // namespace DynamicContact

#endif
