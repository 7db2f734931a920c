#ifndef dynamic_contact_assembled_newton_h
#define dynamic_contact_assembled_newton_h

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <dynamic_contact/contact_newton.h>

#include <memory>

namespace DynamicContact
{
  /**
   * Semismooth Newton on the assembled sparse system, as deal.II's step-42
   * does it: the Newton matrix is K0 (copied, not reassembled) plus the
   * nodal blocks of the active nodes; at stick nodes the constraint
   * w_tau = 0 is imposed by replacing the node's rows with the normal
   * equation nu . R_i = 0 and the constraint rows t . w_i = 0 (exactly the
   * equations that condensing the constraint would give), and the friction
   * force is read from the residual of the tangential equations. The
   * factorization is reused for as long as the matrix does not change.
   * For problems whose contact zone is too large for CondensedNewton.
   */
  template <int dim>
  class AssembledNewton : public ContactNewton<dim>
  {
  public:
    using Result = typename ContactNewton<dim>::Result;

    explicit AssembledNewton(const ContactProblem<dim> &problem);

    void
    reinit() override;

    Result
    solve(const Vector_t &                    rhs,
          const std::vector<Tensor<1, dim>> &u_old,
          const std::vector<Tensor<1, dim>> &w_old,
          const std::vector<double> &         mu,
          std::vector<Tensor<1, dim>> &       lambda,
          Vector_t &                          w) override;

  private:
    const ContactProblem<dim> problem;

    Matrix_t system_matrix;
    Vector_t residual, increment, scratch;

    SolverControl                                      direct_control;
    std::unique_ptr<TrilinosWrappers::SolverDirect>    direct;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    double                                             amg_k = 0;

    /** What the current factorization was made of. */
    std::vector<Tensor<2, dim>> factorized_blocks;
    std::vector<bool>           factorized_stick;
    double                      factorized_k = -1;

    /**
     * residual = K0 w - b + sum_i P_i^T f_i, the f_i given per owned node;
     * returns the l2 norm.
     */
    double
    compute_residual(const Vector_t &                    rhs,
                     const Vector_t &                    w,
                     const std::vector<Tensor<1, dim>> &owned_forces);

    /** Build (if changed) and solve the Newton system for the increment. */
    bool
    solve_linear_system(const std::vector<Tensor<2, dim>> &blocks,
                        const std::vector<bool> &          stick,
                        const std::vector<Tensor<1, dim>> &w_effective);
  };
} // namespace DynamicContact

#endif
