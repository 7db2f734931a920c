#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/assembled_node_dofs.h>
#include <dynamic_contact/contact/assembled_solver.h>

#include <algorithm>

namespace DynamicContact
{
  using namespace AssembledNodeDofs;


  template <int dim>
  AssembledSolver<dim>::AssembledSolver(const ContactProblem<dim> &problem)
    : problem(problem)
    , stiffness(this->problem)
    , iterative(this->problem)
    , direct(this->problem)
  {}


  template <int dim>
  void
  AssembledSolver<dim>::reinit()
  {
    for (auto *v : {&increment, &scratch, &base_residual})
      problem.discretization.reinit_owned(*v);
    stiffness.reinit();
    direct.reinit();
  }


  template <int dim>
  typename AssembledSolver<dim>::Result
  AssembledSolver<dim>::solve(const ContactStep<dim>      &step,
                              std::vector<Tensor<1, dim>> &lambda,
                              Vector_t                    &w)
  {
    return solve_to(step, lambda, w, 0);
  }


  template <int dim>
  typename AssembledSolver<dim>::Result
  AssembledSolver<dim>::solve_provisional(const ContactStep<dim>      &step,
                                          std::vector<Tensor<1, dim>> &lambda,
                                          Vector_t                    &w,
                                          const PassAccuracy          &accuracy)
  {
    double speed = 0;
    for (const auto &v : problem.boundary.values(w))
      speed = std::max(speed, v.norm());
    speed = Utilities::MPI::max(speed, problem.discretization.comm);
    return solve_to(step,
                    lambda,
                    w,
                    std::min(accuracy.velocity, accuracy.relative * speed));
  }


  template <int dim>
  typename AssembledSolver<dim>::Result
  AssembledSolver<dim>::solve_to(const ContactStep<dim>      &step,
                                 std::vector<Tensor<1, dim>> &lambda,
                                 Vector_t                    &w,
                                 const double                 velocity_accuracy)
  {
    Assert(step.scheme == problem.bulk.scheme(),
           ExcMessage("K0 is not formed for the step's time scheme."));
    Result               result;
    FrictionCoefficients coefficients = step.mu;
    if (step.mu.coupled())
      coefficients.weakening_limit = stiffness.weakening_limits();
    WholeSystemNewton<dim> system(
      problem,
      {step.scheme, step.rhs, step.u_old, step.w_old, coefficients},
      *this,
      result);
    WholeSystemIterate<dim> x;
    x.w      = w;
    x.lambda = lambda;
    // The active sets are found here, on the whole system: full steps first
    // (set changes may raise the residual while Newton converges), then
    // non-monotone Armijo (doc/algorithms.md, "Globalization").
    NewtonPolicy policy; // non-monotone
    policy.stagnation_factor = 0.5;
    policy.name              = "whole system";
    // The last step was a full one: its increment is that of the last
    // newton_step() (collective: every process decides alike).
    if (velocity_accuracy > 0)
      policy.accurate_enough = [&](const double residual_factor) {
        double nodal_step = 0;
        for (const auto &node : problem.boundary.nodes())
          nodal_step = std::max(nodal_step, node.value(increment).norm());
        nodal_step =
          Utilities::MPI::max(nodal_step, problem.discretization.comm);
        return nodal_step * residual_factor <= velocity_accuracy;
      };
    {
      TimerSection t(problem.timer, "Contact: sparse Newton");
      globalized_newton(
        system, x, policy, problem.parameters, problem.details, result);
    }
    w      = x.w;
    lambda = x.lambda;
    return result;
  }


  template <int dim>
  void
  AssembledSolver<dim>::newton_step(const WholeSystemNewton<dim>  &newton,
                                    const WholeSystemIterate<dim> &x,
                                    WholeSystemIterate<dim>       &full,
                                    Result                        &result)
  {
    const auto        &nodes = problem.boundary.nodes();
    const unsigned int n     = nodes.size();
    const auto        &K0    = stiffness.nodal_blocks();

    NodalSystem system;
    system.blocks.resize(n);
    system.stick.resize(n);
    system.diagonal.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        const Tensor<2, dim> &P = nodes[i].constraint_map;
        system.blocks[i]        = transpose(P) * x.lin[i].block * P;
        system.stick[i]    = (x.lin[i].friction.state == FrictionState::stick);
        system.diagonal[i] = trace(K0[i]) / dim;
      }

    // The residual of the linearization's constant part: the slip force by
    // its value g t (its dependence on w is in the blocks), no stick force
    // (the tangential equations of stick nodes are replaced).
    base_residual = x.residual;
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return x.base[i] - x.forces[i]; },
      1.,
      base_residual);
    if (problem.parameters.linear_solver ==
        Parameters::Solver::LinearSolver::iterative)
      iterative.solve({system, newton, x, base_residual},
                      stiffness.preconditioner(),
                      increment,
                      result);
    else
      direct.solve({system, newton, x, base_residual}, increment, result);
    problem.discretization.constraints.set_zero(increment);

    full.w = x.w;
    full.w += increment;

    // The friction forces the linearized laws give at the new velocity:
    // slip nodes from the linearization, stick nodes (multipliers) from the
    // tangential residual of the linearized system without friction.
    full.lambda.assign(n, Tensor<1, dim>());
    if (!problem.friction)
      return;
    std::vector<Tensor<1, dim>> new_base(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        const Tensor<1, dim> dw = nodes[i].value(increment);
        const auto          &l  = x.lin[i];
        new_base[i] = l.normal.pressure * nodes[i].weight * nodes[i].normal +
                      (l.block - l.friction.jacobian) * dw;
        if (l.friction.state == FrictionState::slip)
          {
            full.lambda[i] = l.friction.value + l.friction.jacobian * dw;
            new_base[i] += full.lambda[i];
          }
      }
    newton.residual_of(full.w, new_base, scratch);
    for (unsigned int i = 0; i < n; ++i)
      if (system.stick[i])
        full.lambda[i] = -nodes[i].tangential(raw_values(nodes[i], scratch));
  }


  template <int dim>
  SpectralEstimate
  AssembledSolver<dim>::compliance_radius(
    const std::vector<Tensor<2, dim>> &roots,
    const bool)
  {
    return stiffness.compliance_radius(roots);
  }


  template <int dim>
  void
  AssembledSolver<dim>::memory_consumption(MemoryItems &items) const
  {
    stiffness.memory_consumption(items);
    if (problem.parameters.linear_solver ==
        Parameters::Solver::LinearSolver::iterative)
      iterative.memory_consumption(items);
    direct.memory_consumption(items);
  }


  template class AssembledSolver<2>;
  template class AssembledSolver<3>;
} // namespace DynamicContact
