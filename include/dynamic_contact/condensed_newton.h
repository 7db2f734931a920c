#ifndef dynamic_contact_condensed_newton_h
#define dynamic_contact_condensed_newton_h

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <dynamic_contact/contact_newton.h>

#include <memory>

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
   * time step. The columns of C are computed when a node first becomes
   * active (dim solves with the factorized K0 each) and kept while K0 is
   * unchanged. A step costs two solves with K0 plus the dense iterations.
   */
  template <int dim>
  class CondensedNewton : public ContactNewton<dim>
  {
  public:
    using Result = typename ContactNewton<dim>::Result;

    explicit CondensedNewton(const ContactProblem<dim> &problem);

    void
    reinit() override;

    Result
    solve(const Vector_t &                    rhs,
          const std::vector<Tensor<1, dim>> &u_old,
          const std::vector<double> &         mu,
          std::vector<Tensor<1, dim>> &       lambda,
          Vector_t &                          w) override;

    /** Columns of C computed since the last change of K0 (for reports). */
    unsigned int
    n_columns() const;

  private:
    const ContactProblem<dim> problem;

    /** Solver for K0: a factorization, or CG with AMG. */
    SolverControl                                      direct_control;
    std::unique_ptr<TrilinosWrappers::SolverDirect>    direct;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    double                                             prepared_k = 0;

    /** columns[j][i] = C_ij, empty until node j was first active. */
    std::vector<std::vector<Tensor<2, dim>>> columns;
    /** For each node of all_nodes(): its index among the owned nodes, or -1. */
    std::vector<int> owned_index;

    Vector_t solution, right_hand_side;

    /** Factorize K0 (or build AMG) if k changed; drop C if so. */
    void
    prepare(Result &result);

    /** x = K0^{-1} b. */
    void
    solve_bulk(const Vector_t &b, Vector_t &x, Result &result);

    /** Make sure C_:j exists. */
    void
    compute_column(const unsigned int j, Result &result);

    /** w_i = w_free,i - sum_j C_ij f_j over the nodes with a force. */
    void
    compliance_response(const std::vector<Tensor<1, dim>> &w_free,
                        const std::vector<Tensor<1, dim>> &forces,
                        const std::vector<unsigned int> &   with_force,
                        std::vector<Tensor<1, dim>> &       w) const;
  };
} // namespace DynamicContact

#endif
