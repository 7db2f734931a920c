#include <deal.II/base/mpi.h>

#include <dynamic_contact/contact/whole_system_newton.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  template <int dim>
  WholeSystemNewton<dim>::WholeSystemNewton(const ContactProblem<dim> &problem,
                                            const ContactStep<dim>    &step,
                                            LinearBackend<dim>        &backend,
                                            ContactSolveResult        &result)
    : problem(problem)
    , scheme(step.scheme)
    , rhs(step.rhs)
    , u_old(step.u_old)
    , w_old(step.w_old)
    , mu(step.mu)
    , force_scale(resolvable_force(step.rhs.linfty_norm(),
                                   problem.parameters.newton_tolerance))
    , backend(backend)
    , result(result)
  {}


  template <int dim>
  double
  WholeSystemNewton<dim>::residual_of(const Vector_t                    &w,
                                      const std::vector<Tensor<1, dim>> &forces,
                                      Vector_t &residual) const
  {
    if (residual.size() != w.size())
      problem.discretization.reinit_owned(residual);
    problem.bulk.newton_vmult(residual, w);
    residual -= rhs;
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return forces[i]; }, 1., residual);
    return residual.l2_norm();
  }


  template <int dim>
  NewtonMeasure
  WholeSystemNewton<dim>::evaluate(Iterate &x) const
  {
    const auto        &nodes = problem.boundary.nodes();
    const unsigned int n     = nodes.size();
    x.lin.resize(n);
    x.forces.resize(n);
    x.base.resize(n);
    double law_residual = 0, law_squares = 0, f_scale = 1e-300, stick_rate = 0,
           stick_squares    = 0;
    std::uint64_t signature = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const NodeEvaluation<dim> e = evaluate_node(problem,
                                                    scheme,
                                                    nodes[i],
                                                    u_old[i],
                                                    w_old[i],
                                                    nodes[i].value(x.w),
                                                    x.lambda[i],
                                                    mu,
                                                    i);
        x.lin[i]                    = e.lin;
        x.forces[i]                 = e.force;
        x.base[i]                   = e.base;
        f_scale                     = std::max(f_scale, e.force.norm());
        // Where the stick condition is measured in velocity units
        // (velocity_scale), a stick node's law residual, c m_i |w_e,tau|
        // exactly, is left to that measure: c m_i is stiff (c = c_t k, c_t
        // = E/h), and the nodal velocities that the solve starting this
        // phase gives again only to its round-off would make the law
        // residual of a start that phase 1 left at 1e-13 of the
        // velocities 1.1e-10 or 1.9e-10 of the forces (the small paper
        // scene), a step more or less as the round-off of the units fell.
        const bool by_velocity =
          velocity_scale > 0 && e.lin.friction.state == FrictionState::stick;
        const double law = by_velocity ? 0. : e.law_residual;
        law_residual     = std::max(law_residual, law);
        law_squares += law * law;
        stick_rate = std::max(stick_rate, e.stick_rate);
        stick_squares += e.stick_rate * e.stick_rate;
        signature += e.signature;
      }

    if (x.residual.size() != x.w.size())
      problem.discretization.reinit_owned(x.residual);
    problem.bulk.newton_vmult(x.residual, x.w);
    const MPI_Comm comm = problem.discretization.comm;
    x.scale = std::max({rhs.l2_norm(), x.residual.l2_norm(), 1e-300});
    x.residual -= rhs;
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return x.forces[i]; }, 1., x.residual);
    x.law_residual  = Utilities::MPI::max(law_residual, comm);
    x.law_squares   = Utilities::MPI::sum(law_squares, comm);
    x.stick_squares = velocity_scale > 0 ?
                        Utilities::MPI::sum(stick_squares, comm) /
                          (velocity_scale * velocity_scale) :
                        0.;
    x.f_scale       = std::max(Utilities::MPI::max(f_scale, comm), force_scale);

    NewtonMeasure m;
    x.residual_norm = x.residual.l2_norm();
    x.relative_residual =
      std::max(x.residual_norm / x.scale, x.law_residual / x.f_scale);
    if (velocity_scale > 0)
      {
        x.relative_residual =
          std::max(x.relative_residual,
                   Utilities::MPI::max(stick_rate, comm) / velocity_scale);
      }
    m.residual                     = x.relative_residual;
    m.merit                        = merit(x, x);
    std::uint64_t global_signature = 0;
    MPI_Allreduce(
      &signature, &global_signature, 1, MPI_UINT64_T, MPI_SUM, comm);
    m.signature = global_signature;
    return m;
  }


  template <int dim>
  void
  WholeSystemNewton<dim>::combine(const Iterate &x,
                                  const Iterate &full,
                                  const double   alpha,
                                  Iterate       &trial) const
  {
    trial.w = full.w;
    trial.w.sadd(alpha, 1 - alpha, x.w);
    trial.lambda.resize(x.lambda.size());
    for (unsigned int i = 0; i < x.lambda.size(); ++i)
      trial.lambda[i] = x.lambda[i] + alpha * (full.lambda[i] - x.lambda[i]);
  }


  template <int dim>
  bool
  WholeSystemNewton<dim>::safeguarded(const Iterate &x) const
  {
    bool limited = false;
    for (const auto &l : x.lin)
      limited = limited || l.friction.limited;
    return Utilities::MPI::max(limited ? 1 : 0, problem.discretization.comm) ==
           1;
  }


  template class WholeSystemNewton<2>;
  template class WholeSystemNewton<3>;
} // namespace DynamicContact
