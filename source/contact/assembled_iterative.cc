#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/assembled_linear_solves.h>
#include <dynamic_contact/contact/assembled_node_dofs.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

// The assembled solver's Newton step with Linear solver = iterative: GMRES
// on the complement of the stick nodes' tangential components,
// preconditioned by the multigrid of K0.

namespace DynamicContact
{
  using namespace AssembledNodeDofs;

  namespace
  {
    /**
     * The projection of the whole-system Newton step onto the complement of
     * the stick nodes' tangential components (their increments are
     * prescribed): the projected operator and preconditioner act as the
     * identity scaled by K0's diagonal there. It acts on the owned entries
     * directly (the stick nodes' DoFs are owned).
     */
    template <int dim>
    class StickProjection
    {
    public:
      StickProjection(const std::vector<ContactNode<dim>> &nodes,
                      const std::vector<unsigned int>     &stick_nodes,
                      const std::vector<double>           &diagonal,
                      const IndexSet                      &locally_owned)
      {
        for (const unsigned int i : stick_nodes)
          {
            StickNode n;
            for (unsigned int c = 0; c < dim; ++c)
              n.local[c] = locally_owned.index_within_set(nodes[i].dofs[c]);
            n.normal   = nodes[i].normal;
            n.diagonal = diagonal[i];
            sticks.push_back(n);
          }
      }

      /** @p projected = @p v without the stick nodes' tangential parts. */
      void
      project(const Vector_t &v, Vector_t &projected) const
      {
        projected        = v;
        double       *p  = projected.trilinos_vector()[0];
        const double *vv = v.trilinos_vector()[0];
        for (const auto &n : sticks)
          {
            const Tensor<1, dim> t = nodal(vv, n);
            set_nodal(p, n, (t * n.normal) * n.normal);
          }
      }

      /** y = projection of y, plus diagonal^power times v's tangential part. */
      void
      add_tangential(const Vector_t &v, const double power, Vector_t &y) const
      {
        double       *yy = y.trilinos_vector()[0];
        const double *vv = v.trilinos_vector()[0];
        for (const auto &n : sticks)
          {
            const Tensor<1, dim> vi = nodal(vv, n), yi = nodal(yy, n);
            set_nodal(yy,
                      n,
                      (yi * n.normal) * n.normal +
                        std::pow(n.diagonal, power) *
                          (vi - (vi * n.normal) * n.normal));
          }
      }

    private:
      struct StickNode
      {
        std::array<unsigned int, dim> local; // indices into the owned entries
        Tensor<1, dim>                normal;
        double                        diagonal;
      };
      std::vector<StickNode> sticks;

      static Tensor<1, dim>
      nodal(const double *v, const StickNode &n)
      {
        Tensor<1, dim> t;
        for (unsigned int c = 0; c < dim; ++c)
          t[c] = v[n.local[c]];
        return t;
      }
      static void
      set_nodal(double *v, const StickNode &n, const Tensor<1, dim> &t)
      {
        for (unsigned int c = 0; c < dim; ++c)
          v[n.local[c]] = t[c];
      }
    };

    /** The GMRES restart length of the whole-system Newton step. */
    constexpr unsigned int gmres_restart = 100;


    /** A linear operator (vmult) from a function, for deal.II's solvers. */
    struct FunctionOperator
    {
      std::function<void(Vector_t &, const Vector_t &)> apply;
      void
      vmult(Vector_t &y, const Vector_t &v) const
      {
        apply(y, v);
      }
    };


    /**
     * The prescribed tangential increments of the stick nodes into @p dw0
     * (zero elsewhere): t . dw = -(t . w_e)/theta, so that the slip
     * velocity vanishes at the new iterate.
     */
    template <int dim>
    void
    prescribed_stick_increments(const std::vector<ContactNode<dim>> &nodes,
                                const std::vector<unsigned int> &stick_nodes,
                                const WholeSystemNewton<dim>    &newton,
                                const Vector_t                  &w,
                                Vector_t                        &dw0)
    {
      const double theta = newton.scheme.effective_derivative();
      for (const unsigned int i : stick_nodes)
        {
          const Tensor<1, dim> w_e =
            newton.effective_velocity(i, nodes[i].value(w));
          set_raw_values(nodes[i], -nodes[i].tangential(w_e) / theta, dw0);
        }
      dw0.compress(VectorOperation::insert);
    }


    /**
     * Inexact Newton: the Krylov tolerance (relative) follows the Newton
     * residual r: 1e-2 far from the solution, 0.1 r near it (superlinear
     * convergence), but no tighter than what takes r below the Newton
     * tolerance in one step (tol/(2 r)), nor than Solver/Linear tolerance.
     */
    double
    forcing_term(const double relative_residual, const Parameters::Solver &p)
    {
      const double r = std::max(relative_residual, 1e-300);
      return std::min(
        1e-2,
        std::max({p.linear_tolerance, 0.1 * r, 0.5 * p.newton_tolerance / r}));
    }
  } // namespace


  template <int dim>
  void
  AssembledIterativeSolve<dim>::apply_jacobian(
    const AssembledNodalSystem<dim> &system,
    const Vector_t                  &x,
    Vector_t                        &y) const
  {
    const auto     &nodes = problem.boundary.nodes();
    const IndexSet &owned = problem.discretization.locally_owned;
    problem.bulk.newton_vmult(y, x);
    double       *yy = y.trilinos_vector()[0];
    const double *xx = x.trilinos_vector()[0];
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (system.blocks[i].norm_square() > 0)
        {
          std::array<unsigned int, dim> local;
          Tensor<1, dim>                xi;
          for (unsigned int c = 0; c < dim; ++c)
            {
              local[c] = owned.index_within_set(nodes[i].dofs[c]);
              xi[c]    = xx[local[c]];
            }
          const Tensor<1, dim> add = system.blocks[i] * xi;
          for (unsigned int c = 0; c < dim; ++c)
            yy[local[c]] += add[c];
        }
  }


  template <int dim>
  void
  AssembledIterativeSolve<dim>::solve(const AssembledNewtonStep<dim> &step,
                                      const BulkPreconditioner &preconditioner,
                                      Vector_t                 &dw,
                                      ContactSolveResult       &result)
  {
    const auto  &nodes = problem.boundary.nodes();
    TimerSection t(problem.timer, "Newton: iterative solve");

    // dw = dw0 + delta: dw0 holds the prescribed tangential increments of
    // the stick nodes (t . dw = -(t . w_e)/theta), delta solves the system
    // on the complement (the stick nodes' tangential components removed).
    std::vector<unsigned int> stick_nodes;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (step.system.stick[i])
        stick_nodes.push_back(i);
    Vector_t dw0;
    problem.discretization.reinit_owned(dw0);
    prescribed_stick_increments(nodes, stick_nodes, step.newton, step.x.w, dw0);

    // f = -R - J dw0, projected.
    Vector_t f;
    problem.discretization.reinit_owned(f);
    apply_jacobian(step.system, dw0, f);
    f.sadd(-1., -1., step.base_residual);
    for (const unsigned int i : stick_nodes)
      set_raw_values(nodes[i],
                     normal_part(nodes[i], raw_values(nodes[i], f)),
                     f);
    f.compress(VectorOperation::insert);

    // The projected operator and preconditioner.
    const StickProjection<dim> sticks(nodes,
                                      stick_nodes,
                                      step.system.diagonal,
                                      problem.discretization.locally_owned);
    Vector_t                   projected;
    problem.discretization.reinit_owned(projected);
    const FunctionOperator A{[&](Vector_t &y, const Vector_t &v) {
      sticks.project(v, projected);
      apply_jacobian(step.system, projected, y);
      sticks.add_tangential(v, 1., y);
    }};
    const FunctionOperator projected_preconditioner{
      [&](Vector_t &y, const Vector_t &v) {
        sticks.project(v, projected);
        preconditioner.vmult(y, projected);
        sticks.add_tangential(v, -1., y);
      }};

    SolverControl         control(problem.parameters.max_linear_iterations,
                          forcing_term(step.x.relative_residual,
                                       problem.parameters) *
                            f.l2_norm());
    SolverGMRES<Vector_t> gmres(
      control,
      typename SolverGMRES<Vector_t>::AdditionalData(gmres_restart, true));
    Vector_t delta;
    problem.discretization.reinit_owned(delta);
    try
      {
        gmres.solve(A, delta, f, projected_preconditioner);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw StepFailure(
          "GMRES did not converge in Solver/Maximum linear iterations = " +
          std::to_string(problem.parameters.max_linear_iterations) +
          " iterations (relative residual " +
          scientific(e.last_residual / std::max(f.l2_norm(), 1e-300)) + ")");
      }
    result.linear_iterations += control.last_step();
    largest_basis =
      std::max(largest_basis, std::min(control.last_step(), gmres_restart) + 2);
    dw = dw0;
    dw += delta;
  }


  template <int dim>
  void
  AssembledIterativeSolve<dim>::memory_consumption(MemoryItems &items) const
  {
    items.push_back({"GMRES basis (the most a solve used)",
                     double(largest_basis) *
                       problem.discretization.locally_owned.n_elements() *
                       sizeof(double),
                     false});
  }


  template class AssembledIterativeSolve<2>;
  template class AssembledIterativeSolve<3>;
} // namespace DynamicContact
