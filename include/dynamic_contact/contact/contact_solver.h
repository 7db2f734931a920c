#ifndef dynamic_contact_contact_solver_h
#define dynamic_contact_contact_solver_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>
#include <dynamic_contact/laws/contact_law.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/parameters/parameters.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * The Newton iteration's stopping rule on failure, shared by both
   * implementations: throw StepFailure once @p iterations reach
   * Solver/Maximum Newton iterations or the relative @p residual is not
   * finite.
   */
  inline void
  check_newton_cap(const unsigned int        iterations,
                   const double              residual,
                   const Parameters::Solver &parameters)
  {
    if (iterations >= parameters.max_newton_iterations ||
        !std::isfinite(residual))
      throw StepFailure(
        "the semismooth Newton iteration did not converge in Solver/Maximum "
        "Newton iterations = " +
          std::to_string(parameters.max_newton_iterations) +
          " iterations (relative residual " + scientific(residual) + ")",
        iterations);
  }

  /** What a Newton solver for one step needs to know. */
  template <int dim>
  struct ContactProblem
  {
    const Discretization<dim>  &discretization;
    const BulkOperator<dim>    &bulk;
    const ContactBoundary<dim> &boundary;
    const Foundation           &foundation;
    const Parameters::Solver   &parameters;
    TimerOutput                &timer;
    /** Per-iteration diagnostics (Output/Solver details), rank 0 only. */
    const ConditionalOStream &details;
    /** Friction is on (a law other than none). */
    bool friction;
    /**
     * The complementarity constant c_t of friction (Pa/m, like E/h); the
     * nodal laws use c = c_t k.
     */
    double c_t;
    /**
     * How accurately the convexification loop needs the slip rates:
     * Friction/Coefficient tolerance over the law's one-sided Lipschitz
     * constant (a velocity; infinite without a slip-rate dependent law).
     * The condensed solver's whole-system phase takes a step where the
     * solve left the nodal velocities of its boundary phase by more.
     */
    double slip_rate_accuracy = std::numeric_limits<double>::infinity();
  };


  /**
   * The data of one pass of a step, as a contact solver is given it: the
   * step's time scheme (k, theta; bulk's K0 must be formed for it:
   * BulkOperator::set_time_step()), the right-hand side b, u_{n-1} and
   * w_{n-1} at the nodes this process owns (aligned with
   * ContactBoundary::nodes()), and the friction coefficients (frozen, or
   * coupled: mu(|w_e,tau|) of the iterate, linearized too). The laws act on
   * u_n and w_e = theta w_n + (1 - theta) w_{n-1} (TimeScheme).
   */
  template <int dim>
  struct ContactStep
  {
    const TimeScheme                  &scheme;
    const Vector_t                    &rhs;
    const std::vector<Tensor<1, dim>> &u_old;
    const std::vector<Tensor<1, dim>> &w_old;
    const FrictionCoefficients        &mu;
  };


  /**
   * How accurately a pass of the convexification loop that is probably not
   * its last must be solved (ContactSolver::solve_provisional()).
   */
  struct PassAccuracy
  {
    /**
     * The nodal velocities to about this (the scene's velocity unit): what
     * the loop's next coefficients need (the loop's smallest coefficient
     * residual so far over the friction law's Lipschitz constant). 0: to
     * the Newton tolerance.
     */
    double velocity = 0;
    /**
     * Relative to the largest nodal velocity: the tolerance of rule (85),
     * which compares the pass after this one with it (a solver that
     * writes w keeps its error below it; one that finishes the earlier
     * pass in finalize() need not).
     */
    double relative = 0;
  };


  /** What one Newton solve did (summed into the step's statistics). */
  struct ContactSolveResult
  {
    unsigned int iterations     = 0;
    unsigned int factorizations = 0;
    unsigned int bulk_solves    = 0;
    /** Krylov iterations of the iterative linear solver. */
    unsigned int linear_iterations = 0;
    double       residual          = 0;
    /** Iterations whose active sets had been seen before (cycling). */
    unsigned int cycles = 0;
    /** Damped trial steps of the line search. */
    unsigned int line_search_steps = 0;
    /**
     * The solve was provisional (the condensed solver's boundary iteration
     * without its whole-system polish): w is left as it was, the nodal
     * velocities are provisional_velocities(), and finalize() must follow
     * before w is used as the step's solution.
     */
    bool provisional = false;
    /**
     * The solve stopped at the velocity accuracy a provisional pass asked
     * for (ContactSolver::solve_provisional()), short of the Newton
     * tolerance, and wrote w: a solve() of the same step from that w
     * finishes it.
     */
    bool inexact = false;
  };


  /**
   * The primal-dual active set / semismooth Newton iteration of
   * doc/theory.md section 5 for frozen friction coefficients: find w and the
   * friction forces lambda with K0 w + sum_i P_i^T (N_i(w) nu_i + lambda_i) =
   * b, lambda_i = P_B(0, mu_i N_i)(lambda_i + c_t w_tau,i)  at every node. Two
   * implementations share one globalized Newton driver (globalized_newton(),
   * newton_driver.h) and differ in the linear algebra: CondensedSolver (static
   * condensation onto Gamma_3: K0 factorized once, dense systems on the active
   * nodes; replicates Gamma_3 on every process) and AssembledSolver (the sparse
   * Newton system of the whole body, by a direct factorization or by GMRES
   * preconditioned with algebraic multigrid of K0; O(N) per iteration, nothing
   * replicated).
   */
  template <int dim>
  class ContactSolver
  {
  public:
    using Result = ContactSolveResult;

    virtual ~ContactSolver() = default;

    /** The mesh (or the boundary) changed. */
    virtual void
    reinit() = 0;

    /**
     * Solve one pass @p step of a step: @p lambda the friction forces of
     * the owned nodes (in: initial guess, out: result); @p w the initial
     * guess and the result (master form). Throws StepFailure if the
     * iteration does not converge.
     */
    virtual Result
    solve(const ContactStep<dim>      &step,
          std::vector<Tensor<1, dim>> &lambda,
          Vector_t                    &w) = 0;

    /**
     * The same, where the caller may accept a provisional answer (a pass
     * of the convexification loop that is probably not the last): a solver
     * that finds the velocities at the nodes more cheaply than the whole w
     * does so, leaves @p w as it was and sets Result::provisional; it may
     * stop once its nodal velocities are accurate to about @p accuracy if
     * that is coarser than the Newton tolerance (finalize() then iterates
     * on to the Newton tolerance). A solver that writes w may stop there
     * too and set Result::inexact (a solve() from w then finishes the
     * pass). The default solves.
     */
    virtual Result
    solve_provisional(const ContactStep<dim>      &step,
                      std::vector<Tensor<1, dim>> &lambda,
                      Vector_t                    &w,
                      const PassAccuracy & /*accuracy*/ = {})
    {
      return solve(step, lambda, w);
    }

    /**
     * After a provisional solve: the solution itself, from the same data
     * (the last solve's). With @p previous given (only if the provisional
     * solve followed another one of the same step): also the whole
     * velocity of that earlier pass into @p previous (what rule (85)
     * compares the finished pass with). The default has nothing to do.
     */
    virtual Result
    finalize(Vector_t & /*w*/,
             std::vector<Tensor<1, dim>> & /*lambda*/,
             Vector_t * /*previous*/ = nullptr)
    {
      return Result();
    }

    /**
     * The largest eigenvalue of S C S: C the compliance of the nodes of
     * Gamma_3 under K0 (the response of the nodal velocities to nodal
     * forces, C_ij = P_i [K0^{-1}]_ij P_j^T: inertia, viscosity and
     * elasticity in it, the contact laws not), S the block diagonal of the
     * symmetric @p roots of the owned nodes (zero leaves a node out). The
     * uniqueness measures of a step (doc/theory.md section 5.2) are of this
     * form. Lanczos (largest_eigenvalue()); collective. Where @p certify
     * and the Lanczos value is below 1, a solver that holds C's entries
     * adds an upper bound of the eigenvalue (SpectralEstimate::upper; -1
     * where it cannot).
     */
    virtual SpectralEstimate
    compliance_radius(const std::vector<Tensor<2, dim>> &roots,
                      const bool                         certify) = 0;

    /**
     * What the solver holds on this process beyond the bulk operator
     * (factorizations, preconditioners, dense tables, its own matrices).
     */
    virtual void
    memory_consumption(MemoryItems &items) const = 0;

    /**
     * After a provisional solve: its velocities at the nodes this process
     * owns (aligned with ContactBoundary::nodes()). A provisional solve
     * leaves the whole w untouched; the nodes are what the
     * convexification loop measures of a pass.
     */
    virtual std::vector<Tensor<1, dim>>
    provisional_velocities() const
    {
      Assert(false, ExcInternalError());
      return {};
    }
  };
} // namespace DynamicContact

#endif
