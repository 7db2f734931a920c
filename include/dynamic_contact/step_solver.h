#ifndef dynamic_contact_step_solver_h
#define dynamic_contact_step_solver_h

#include <deal.II/base/timer.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <dynamic_contact/bulk_operator.h>
#include <dynamic_contact/contact_boundary.h>
#include <dynamic_contact/contact_law.h>
#include <dynamic_contact/foundation.h>
#include <dynamic_contact/friction_law.h>

#include <memory>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /** What the solver knows about one node of Gamma_3 after a solve. */
  template <int dim>
  struct ContactNodeState
  {
    NormalResponse normal{};
    /** Friction force lambda_i (a nodal force: m_i times the traction). */
    Tensor<1, dim> friction_force;
    /** The frozen friction coefficient mu_i of the last iterate. */
    double       mu    = 0;
    ContactState state = ContactState::free;

    /** Normal nodal force N_i = m_i (p + q). */
    double
    normal_force(const double weight) const
    {
      return weight * normal.pressure;
    }
  };


  /**
   * One time step of the scheme (model.md sections 4 and 5): given the
   * bulk operator K0 for the current k, the right-hand side
   *   b = (rho/k) M w_{n-1} - B u_{n-1} + f_n
   * and u_{n-1}, find w_n with
   *   K0 w_n + sum_i P_i^T F_i(w_n) = b,
   * F_i the contact force of node i, by semismooth Newton on the nodal
   * laws. Only the Gamma_3 terms change between iterations: the Newton
   * matrix is K0 plus nodal dim x dim blocks, copied (not reassembled) from
   * K0, and its factorization is reused for as long as the blocks do not
   * change.
   */
  template <int dim>
  class StepSolver
  {
  public:
    struct Statistics
    {
      unsigned int newton_iterations          = 0;
      unsigned int convexification_iterations = 0;
      bool         convexification_converged  = true;
      unsigned int factorizations             = 0;
      double       residual                   = 0;
      unsigned int n_contact                  = 0;
      unsigned int n_stick                    = 0;
      unsigned int n_slip                     = 0;
    };

    StepSolver(const Discretization<dim> &   discretization,
               const BulkOperator<dim> &     bulk,
               const ContactBoundary<dim> &  contact_boundary,
               const Foundation &            foundation,
               const FrictionLaw *           friction_law,
               const Parameters::Solver &    solver_parameters,
               const Parameters::Friction &  friction_parameters,
               TimerOutput &                 timer);

    /** After a change of the mesh (or of Gamma_3): size the node data. */
    void
    reinit();

    /**
     * Solve one step. @p w holds the initial guess (usually w_{n-1}) and
     * returns w_n, in master form. Throws if Newton does not converge.
     */
    Statistics
    solve(const Vector_t &rhs, const Vector_t &u_old, Vector_t &w);

    /** Node data of the last solve, aligned with contact_boundary.nodes(). */
    const std::vector<ContactNodeState<dim>> &
    node_states() const
    {
      return states;
    }

    /** Set the friction forces and coefficients (e.g. after a restart). */
    std::vector<ContactNodeState<dim>> &
    node_states()
    {
      return states;
    }

  private:
    const Discretization<dim> &  discretization;
    const BulkOperator<dim> &    bulk;
    const ContactBoundary<dim> & contact_boundary;
    const Foundation &           foundation;
    const FrictionLaw *          friction_law;
    const Parameters::Solver     parameters;
    const Parameters::Friction   friction_parameters;
    TimerOutput &                timer;

    std::vector<ContactNodeState<dim>> states;

    Matrix_t system_matrix;
    Vector_t residual;
    Vector_t increment;
    Vector_t scratch;

    /** The linear solvers, kept so that a factorization can be reused. */
    SolverControl                                  direct_control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> direct_solver;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    /** The nodal blocks and K0's time step the current factorization has. */
    std::vector<Tensor<2, dim>> factorized_blocks;
    double                      factorized_k = 0;
    bool                        factorized   = false;
    double                      amg_k        = 0;

    /** Evaluate the nodal laws at (u_old, w); fill states. */
    void
    evaluate_nodes(const Vector_t &u_old, const Vector_t &w, const double k);

    /** residual = K0 w - rhs + sum_i P_i^T F_i; returns its l2 norm. */
    double
    compute_residual(const Vector_t &rhs, const Vector_t &w);

    /** The nodal Jacobian blocks P^T dF_i/dw_i P at the current states. */
    std::vector<Tensor<2, dim>>
    nodal_blocks(const double k) const;

    /** Solve (K0 + blocks) increment = -residual. Returns true if refactored. */
    bool
    solve_linear_system(const std::vector<Tensor<2, dim>> &blocks,
                        const double                       k);

    /** The semismooth Newton iteration for frozen friction coefficients. */
    unsigned int
    newton(const Vector_t &rhs,
           const Vector_t &u_old,
           Vector_t &      w,
           Statistics &    statistics);
  };
} // namespace DynamicContact

#endif
