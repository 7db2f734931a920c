#ifndef dynamic_contact_assembled_linear_solves_h
#define dynamic_contact_assembled_linear_solves_h

#include <deal.II/lac/trilinos_solver.h>

#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/whole_system_newton.h>

#include <memory>
#include <vector>

namespace DynamicContact
{
  /**
   * The Newton step of one iterate of the assembled solver: nodal blocks
   * and the stick set.
   */
  template <int dim>
  struct AssembledNodalSystem
  {
    std::vector<Tensor<2, dim>> blocks; // P^T B P, per owned node
    std::vector<bool>           stick;
    std::vector<double>         diagonal; // mean diagonal of K0 at a node
  };


  /**
   * What a linear solve of the assembled solver's Newton step reads: the
   * nodal system of the iterate @p x of @p newton, and @p base_residual,
   * the residual with the linearized forces' constant part (the
   * right-hand side is its negative).
   */
  template <int dim>
  struct AssembledNewtonStep
  {
    const AssembledNodalSystem<dim> &system;
    const WholeSystemNewton<dim>    &newton;
    const WholeSystemIterate<dim>   &x;
    const Vector_t                  &base_residual;
  };


  /**
   * The assembled solver's Newton step with Linear solver = iterative
   * (AssembledSolver): GMRES, matrix-free in the nodal terms (a product
   * with K0 plus the nodal blocks), with the stick constraints imposed by
   * projection (the tangential components of a stick node are prescribed,
   * the system is solved on the complement), preconditioned by the
   * multigrid of K0; the Krylov tolerance follows the Newton residual
   * (inexact Newton). It keeps the most GMRES basis vectors a solve used.
   */
  template <int dim>
  class AssembledIterativeSolve
  {
  public:
    /** On @p problem (which must outlive this). */
    explicit AssembledIterativeSolve(const ContactProblem<dim> &problem)
      : problem(problem)
    {}

    /**
     * Solve @p step for @p dw, preconditioned by @p preconditioner.
     */
    void
    solve(const AssembledNewtonStep<dim> &step,
          const BulkPreconditioner       &preconditioner,
          Vector_t                       &dw,
          ContactSolveResult             &result);

    /** The GMRES basis (the most a solve used). */
    void
    memory_consumption(MemoryItems &items) const;

  private:
    const ContactProblem<dim> &problem;

    /** y = (K0 + sum P^T B P) x, without the stick projection. */
    void
    apply_jacobian(const AssembledNodalSystem<dim> &system,
                   const Vector_t                  &x,
                   Vector_t                        &y) const;

    /** The most GMRES basis vectors a solve used. */
    unsigned int largest_basis = 0;
  };


  /**
   * The assembled solver's Newton step with Linear solver = direct
   * (AssembledSolver): the Newton matrix (K0 copied, the nodal blocks
   * added, each stick node's rows replaced by its normal equation and its
   * stick constraints) is factorized when it changes and the factorization
   * reused while it does not. It owns the matrix, the factorization and
   * what it was made of.
   */
  template <int dim>
  class AssembledDirectSolve
  {
  public:
    /** On @p problem (which must outlive this). */
    explicit AssembledDirectSolve(const ContactProblem<dim> &problem)
      : problem(problem)
    {}

    /** For a new mesh: the matrix's pattern (direct) or none (iterative). */
    void
    reinit();

    /**
     * Solve @p step for @p dw, with the stick nodes' rows of the
     * right-hand side replaced likewise.
     */
    void
    solve(const AssembledNewtonStep<dim> &step,
          Vector_t                       &dw,
          ContactSolveResult             &result);

    /** The Newton matrix and its factorization, if there is a matrix. */
    void
    memory_consumption(MemoryItems &items) const;

  private:
    const ContactProblem<dim> &problem;

    /**
     * The assembled Newton matrix of @p system: K0, the nodal blocks, and
     * each stick node's rows replaced by its normal equation and its
     * stick constraints.
     */
    void
    assemble_matrix(const AssembledNodalSystem<dim> &system);

    // The Newton matrix and its factorization, and what it was made of
    // (reused while unchanged).
    Matrix_t                                        system_matrix;
    SolverControl                                   direct_control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> direct;
    std::vector<Tensor<2, dim>>                     factorized_blocks;
    std::vector<bool>                               factorized_stick;
    TimeScheme                                      factorized_scheme;
    /** The largest growth of resident memory a factorization measured. */
    double factorization_bytes = 0;
    /** The right-hand side of the direct solve. */
    Vector_t right_hand_side;
  };
} // namespace DynamicContact

#endif
