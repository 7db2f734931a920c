#ifndef dynamic_contact_assembled_solver_h
#define dynamic_contact_assembled_solver_h

#include <dynamic_contact/contact/assembled_linear_solves.h>
#include <dynamic_contact/contact/assembled_stiffness.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/whole_system_newton.h>

namespace DynamicContact
{
  /**
   * Semismooth Newton on the sparse system of the whole body
   * (Solver/Contact solver = assembled): each iteration solves
   *   (K0 + sum_i P_i^T B_i P_i) dw = -R
   * with B_i the nodal Newton blocks (compliance, damping, the slip
   * linearization) and, at stick nodes, the constraint t . w_e = 0 in place
   * of the tangential equations (the friction force then follows from the
   * tangential residual, as in deal.II's step-42). Everything is per owned
   * node and O(N): nothing of Gamma_3 is replicated.
   *
   * Linear solver = iterative (the scalable one): GMRES, matrix-free in the
   * nodal terms (a product with K0 plus the nodal blocks), with the stick
   * constraints imposed by projection: the tangential components of a stick
   * node are prescribed, the system is solved on the complement, and the
   * preconditioner is multigrid of K0 (BulkAMG, or the geometric one of
   * Solver/Preconditioner) built once per K0,
   * i.e. once per mesh and time step, and used for every Newton iteration,
   * convexification pass and step with that K0. The Krylov tolerance
   * follows the Newton residual (inexact Newton): 1e-2 far from the
   * solution, 0.1 times the relative residual near it, never below
   * Solver/Linear tolerance.
   *
   * Linear solver = direct: the Newton matrix (K0 copied, the nodal blocks
   * added, the stick rows replaced) is factorized when it changes and the
   * factorization reused while it does not.
   *
   * This class is the Newton iteration (the nodal blocks and the stick set
   * of an iterate, the friction forces of the step); its parts are K0
   * (AssembledStiffness: the multigrid, K0's nodal blocks, solves with K0)
   * and the two linear solves of a step (AssembledIterativeSolve,
   * AssembledDirectSolve: assembled_linear_solves.h).
   */
  template <int dim>
  class AssembledSolver : public ContactSolver<dim>, public LinearBackend<dim>
  {
  public:
    using Result = ContactSolveResult;

    explicit AssembledSolver(const ContactProblem<dim> &problem);

    void
    reinit() override;

    Result
    solve(const ContactStep<dim>      &step,
          std::vector<Tensor<1, dim>> &lambda,
          Vector_t                    &w) override;

    /**
     * A pass of the convexification loop that is probably not its last
     * (Solver/Assembled/Provisional passes): Newton stops short of its
     * tolerance once the nodal velocities are accurate to the smaller of
     * @p accuracy.velocity and @p accuracy.relative times the largest
     * nodal velocity at the pass's start. The error is estimated after a
     * full step that kept the active sets: the largest change of a nodal
     * velocity in that step times the factor by which the step lowered
     * the residual (near a solution Newton's error falls with its
     * residual). w is written; Result::inexact says a solve() from it must
     * finish the pass if the loop keeps it.
     */
    Result
    solve_provisional(const ContactStep<dim>      &step,
                      std::vector<Tensor<1, dim>> &lambda,
                      Vector_t                    &w,
                      const PassAccuracy          &accuracy) override;

    /**
     * By solves with K0 (CG, preconditioned with the AMG of K0); no upper
     * bound (the entries of C are not at hand).
     */
    SpectralEstimate
    compliance_radius(const std::vector<Tensor<2, dim>> &roots,
                      const bool                         certify) override;

    void
    memory_consumption(MemoryItems &items) const override;

    void
    newton_step(const WholeSystemNewton<dim>  &system,
                const WholeSystemIterate<dim> &x,
                WholeSystemIterate<dim>       &full,
                Result                        &result) override;

  private:
    const ContactProblem<dim> problem;

    using NodalSystem = AssembledNodalSystem<dim>;

    /** K0: its multigrid, its nodal blocks, solves with it. */
    AssembledStiffness<dim> stiffness;
    /** Solve for dw (iterative, projected): see the class documentation. */
    AssembledIterativeSolve<dim> iterative;
    /** Solve for dw (direct, assembled): see the class documentation. */
    AssembledDirectSolve<dim> direct;

    /** The residual with the linearized forces' constant part. */
    Vector_t base_residual;
    Vector_t increment, scratch;

    /**
     * solve() (@p velocity_accuracy 0) and solve_provisional() (the
     * nodal velocities to about @p velocity_accuracy).
     */
    Result
    solve_to(const ContactStep<dim>      &step,
             std::vector<Tensor<1, dim>> &lambda,
             Vector_t                    &w,
             const double                 velocity_accuracy);
  };
} // namespace DynamicContact

#endif
