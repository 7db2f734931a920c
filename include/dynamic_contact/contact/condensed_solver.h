#ifndef dynamic_contact_condensed_solver_h
#define dynamic_contact_condensed_solver_h

#include <dynamic_contact/contact/boundary_compliance.h>
#include <dynamic_contact/contact/condensed_boundary_newton.h>
#include <dynamic_contact/contact/condensed_whole_system.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/reduced_system.h>
#include <dynamic_contact/contact/whole_system_newton.h>

#include <optional>

namespace DynamicContact
{
  /**
   * Semismooth Newton by static condensation onto Gamma_3. Everything off
   * Gamma_3 is linear, so with w_free = K0^{-1} b and the compliance
   * (Delassus) matrix of the nodes, C_ij = P_i [K0^{-1}]_ij P_j^T,
   *   w_i = w_free,i - sum_j C_ij f_j(w_j, lambda_j)
   * is the whole nonlinear problem, of the size of the contact zone.
   * Nothing of the size of the mesh is factorized more than once per mesh
   * and time step. The solver has three parts:
   * - BoundaryCompliance: K0' (K0 with springs that hold its rigid
   *   motions) factorized, and the columns of C;
   * - ReducedSystem: the dense system of one Newton step on the active
   *   nodes (stick constraints as equations with the tangential forces as
   *   unknowns), reduced to the forces and factorized;
   * - this class: the iteration over them, in two phases, each a
   *   globalized_newton() iteration: on Gamma_3 alone (w_Gamma = w_free -
   *   C f, no solve with K0' but for new columns of C), which finds the
   *   active sets (CondensedBoundaryNewton), then on the whole system,
   *   whose Newton steps it solves by the same condensation (the
   *   LinearBackend role: a solve with K0', a dense solve and a solve with
   *   K0' or a sum of stored columns each), which polishes the solution
   *   where the cancellation in w_free - C f limits phase 1
   *   (CondensedWholeSystem, which also keeps w_free = K0'^{-1} b for the
   *   passes of a step); and the provisional passes of a convexification
   *   loop (solve_provisional(), finalize()).
   *
   * A step costs a solve with K0' for w_free, one for the velocity of each
   * convexification pass, and in the whole-system phase one plus one or
   * two per Newton step (newton_step()), plus the dense iterations.
   *
   * The dense tables couple every pair of nodes, so Gamma_3 is replicated on
   * every process (GatheredBoundary), and rank 0 holds the tables and does
   * the dense work (BoundaryCompliance::on_leader()): the right choice
   * while the contact boundary is small (the solver plan decides:
   * solver_plan.h).
   */
  template <int dim>
  class CondensedSolver : public ContactSolver<dim>
  {
  public:
    using Result = ContactSolveResult;

    explicit CondensedSolver(const ContactProblem<dim> &problem);

    void
    reinit() override;

    Result
    solve(const ContactStep<dim>      &step,
          std::vector<Tensor<1, dim>> &lambda,
          Vector_t                    &w) override;

    /**
     * Phase 1 only, stopped at the relative residual @p accuracy.velocity
     * / w_scale if that is larger than the Newton tolerance: the nodal
     * velocities w_free - C g of its iterate, no solve with K0' (w is left
     * as it was; finalize() computes the earlier pass's whole velocity, so
     * @p accuracy.relative is not needed).
     */
    Result
    solve_provisional(const ContactStep<dim>      &step,
                      std::vector<Tensor<1, dim>> &lambda,
                      Vector_t                    &w,
                      const PassAccuracy          &accuracy = {}) override;

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

    /**
     * From the dense compliance C of Gamma_3 (on rank 0), the upper bound
     * from C's entries (BoundaryCompliance::radius()).
     */
    SpectralEstimate
    compliance_radius(const std::vector<Tensor<2, dim>> &roots,
                      const bool                         certify) override;

    void
    memory_consumption(MemoryItems &items) const override;

  private:
    const ContactProblem<dim> problem;
    /** Gamma_3 on every process, in one order. */
    GatheredBoundary<dim> gathered;
    /** The compliance C of Gamma_3 and the factorized K0' it comes from. */
    BoundaryCompliance<dim> compliance;
    /** The dense system of a Newton step on the active nodes. */
    ReducedSystem<dim> reduced;
    /** The data of the current solve at every node. */
    BoundaryStepData<dim> data;
    /** Phase 1, on Gamma_3 alone. */
    CondensedBoundaryNewton<dim> boundary_newton;
    /** The free response and phase 2, on the whole body. */
    CondensedWholeSystem<dim> whole_system;

    /** The linearization of every node at an iterate. */
    using Iterate = BoundaryIterate<dim>;

    /**
     * What a provisional solve leaves for finalize(): its data (owned
     * nodes) and the phase-1 iterate (every node).
     */
    struct Pending
    {
      TimeScheme                  scheme;
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
    std::optional<typename CondensedWholeSystem<dim>::PassForces> previous_pass;

    /**
     * A pending provisional pass of the same step (@p same_rhs) is the
     * loop's last iterate: for a provisional pass, its nodal velocities are
     * returned (the start of this pass) and its friction forces and active
     * sets go into previous_pass. One of another step (a failed step) is
     * stale. Clears pending and previous_pass before.
     */
    std::vector<Tensor<1, dim>>
    take_pending_pass(const bool same_rhs, const bool provisional);

    /** solve() and solve_provisional(). */
    Result
    solve(const ContactStep<dim>      &step,
          std::vector<Tensor<1, dim>> &lambda,
          Vector_t                    &w,
          const bool                   provisional,
          const double                 velocity_accuracy = 0);

    /** The coefficients of the owned nodes at every node (collective). */
    FrictionCoefficients
    gather_coefficients(const FrictionCoefficients &mu) const
    {
      // (The states: decided by the same value on every process.)
      return {gathered.gather(mu.frozen),
              mu.law,
              mu.weakening_limit.empty() ? std::vector<double>() :
                                           gathered.gather(mu.weakening_limit),
              mu.coupled() && mu.slip_length.active() ?
                gathered.gather(mu.state) :
                std::vector<double>(),
              mu.slip_length};
    }
  };
} // namespace DynamicContact

#endif
