#ifndef dynamic_contact_assembled_solver_h
#define dynamic_contact_assembled_solver_h

#include <deal.II/lac/trilinos_solver.h>

#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/whole_system_newton.h>

#include <memory>

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

    /** The Newton step of one iterate: nodal blocks and the stick set. */
    struct NodalSystem
    {
      std::vector<Tensor<2, dim>> blocks; // P^T B P, per owned node
      std::vector<bool>           stick;
      std::vector<double>         diagonal; // mean diagonal of K0 at a node
    };

    /** Solve for dw (iterative, projected): see the class documentation. */
    void
    solve_iterative(const NodalSystem             &system,
                    const WholeSystemNewton<dim>  &newton,
                    const WholeSystemIterate<dim> &x,
                    Vector_t                      &dw,
                    Result                        &result);

    /**
     * The assembled Newton matrix of @p system: K0, the nodal blocks, and
     * each stick node's rows replaced by its normal equation and its
     * stick constraints.
     */
    void
    assemble_direct_matrix(const NodalSystem &system);

    /** Solve for dw (direct, assembled): see the class documentation. */
    void
    solve_direct(const NodalSystem             &system,
                 const WholeSystemNewton<dim>  &newton,
                 const WholeSystemIterate<dim> &x,
                 Vector_t                      &dw,
                 Result                        &result);

    /** y = (K0 + sum P^T B P) x, without the stick projection. */
    void
    apply_jacobian(const NodalSystem &system,
                   const Vector_t    &x,
                   Vector_t          &y) const;

    // Iterative: the multigrid of K0 (algebraic or geometric), for the time
    // step it was built for.
    std::unique_ptr<BulkPreconditioner> preconditioner;
    TimeScheme                          preconditioner_scheme;
    /** K0's blocks at the owned nodes, for the K0 they were taken from. */
    std::vector<Tensor<2, dim>> bulk_blocks;
    TimeScheme                  blocks_scheme;
    /** BulkOperator::newton_blocks() at the nodes, unless K0 is unchanged. */
    const std::vector<Tensor<2, dim>> &
    nodal_bulk_blocks();

    /** Build the AMG of the current K0 unless it is built. */
    void
    prepare_preconditioner();
    /**
     * x = K0^{-1} b by CG with the AMG of K0, to @p tolerance relative to
     * |b| (constrained entries zero).
     */
    void
    solve_bulk(const Vector_t &b, Vector_t &x, const double tolerance);

    /**
     * The coupled linearization's limits of the owned nodes
     * (WeakeningLimit), for the K0 they were measured with.
     */
    std::vector<double> weakening_limits;
    TimeScheme          limits_scheme;
    /** Measure them if K0 changed (collective). */
    const std::vector<double> &
    coupled_limits();

    // Direct: the Newton matrix and its factorization, and what it was made
    // of (reused while unchanged).
    Matrix_t                                        system_matrix;
    SolverControl                                   direct_control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> direct;
    std::vector<Tensor<2, dim>>                     factorized_blocks;
    std::vector<bool>                               factorized_stick;
    TimeScheme                                      factorized_scheme;
    /** The largest growth of resident memory a factorization measured. */
    double factorization_bytes = 0;
    /** The most GMRES basis vectors a solve used. */
    unsigned int largest_basis = 0;

    /** The residual with the linearized forces' constant part. */
    Vector_t base_residual;
    Vector_t increment, scratch, scratch2;
  };
} // namespace DynamicContact

#endif
