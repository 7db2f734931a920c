#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <dynamic_contact/error_messages.h>
#include <dynamic_contact/step_solver.h>

#include <cmath>

namespace DynamicContact
{
  template <int dim>
  StepSolver<dim>::StepSolver(const Discretization<dim> &  discretization,
                              const BulkOperator<dim> &    bulk,
                              const ContactBoundary<dim> & contact_boundary,
                              const Foundation &           foundation,
                              const FrictionLaw *          friction_law,
                              const Parameters::Solver &   solver_parameters,
                              const Parameters::Friction & friction_parameters,
                              TimerOutput &                timer)
    : discretization(discretization)
    , bulk(bulk)
    , contact_boundary(contact_boundary)
    , foundation(foundation)
    , friction_law(friction_law)
    , parameters(solver_parameters)
    , friction_parameters(friction_parameters)
    , timer(timer)
  {}


  template <int dim>
  void
  StepSolver<dim>::reinit()
  {
    states.assign(contact_boundary.nodes().size(), ContactNodeState<dim>());
    system_matrix.reinit(bulk.sparsity_pattern());
    discretization.reinit_owned(residual);
    discretization.reinit_owned(increment);
    discretization.reinit_owned(scratch);
    direct_solver.reset();
    amg.reset();
    factorized = false;
    amg_k      = 0;
  }


  template <int dim>
  void
  StepSolver<dim>::evaluate_nodes(const Vector_t &u_old,
                                  const Vector_t &w,
                                  const double    k)
  {
    const auto &nodes = contact_boundary.nodes();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      states[i].normal = normal_response(
        foundation, nodes[i], nodes[i].value(u_old), nodes[i].value(w), k);
  }


  template <int dim>
  double
  StepSolver<dim>::compute_residual(const Vector_t &rhs, const Vector_t &w)
  {
    bulk.newton_matrix().vmult(residual, w);
    residual -= rhs;

    const auto &                         nodes = contact_boundary.nodes();
    std::vector<types::global_dof_index> indices;
    std::vector<double>                  values;
    indices.reserve(dim * nodes.size());
    values.reserve(dim * nodes.size());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const Tensor<1, dim> force =
          states[i].normal_force(nodes[i].weight) * nodes[i].normal +
          states[i].friction_force;
        const Tensor<1, dim> condensed =
          transpose(nodes[i].constraint_map) * force;
        for (unsigned int c = 0; c < dim; ++c)
          {
            indices.push_back(nodes[i].dofs[c]);
            values.push_back(condensed[c]);
          }
      }
    residual.add(indices, values);
    residual.compress(VectorOperation::add);
    return residual.l2_norm();
  }


  template <int dim>
  std::vector<Tensor<2, dim>>
  StepSolver<dim>::nodal_blocks(const double) const
  {
    const auto &                nodes = contact_boundary.nodes();
    std::vector<Tensor<2, dim>> blocks(nodes.size());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        // d(N_i nu_i)/dw_i = m_i (k p' + q') nu_i (x) nu_i.
        const Tensor<2, dim> normal_block =
          nodes[i].weight * states[i].normal.dpressure_dw *
          outer_product(nodes[i].normal, nodes[i].normal);
        const Tensor<2, dim> &P = nodes[i].constraint_map;
        blocks[i]               = transpose(P) * normal_block * P;
      }
    return blocks;
  }


  template <int dim>
  bool
  StepSolver<dim>::solve_linear_system(
    const std::vector<Tensor<2, dim>> &blocks,
    const double                       k)
  {
    const auto &nodes = contact_boundary.nodes();
    // The Newton matrix only changes through the nodal blocks (and K0's k):
    // reuse the last factorization if they are all as they were.
    bool same = factorized && factorized_k == k &&
                factorized_blocks.size() == blocks.size();
    for (unsigned int i = 0; same && i < blocks.size(); ++i)
      same = (blocks[i] == factorized_blocks[i]);
    same = (Utilities::MPI::min(same ? 1 : 0, discretization.comm) == 1);

    if (!same)
      {
        TimerOutput::Scope t(timer, "Newton: matrix update");
        system_matrix.copy_from(bulk.newton_matrix());
        for (unsigned int i = 0; i < nodes.size(); ++i)
          for (unsigned int r = 0; r < dim; ++r)
            for (unsigned int c = 0; c < dim; ++c)
              if (blocks[i][r][c] != 0)
                system_matrix.add(nodes[i].dofs[r],
                                  nodes[i].dofs[c],
                                  blocks[i][r][c]);
        system_matrix.compress(VectorOperation::add);
      }

    scratch = residual;
    scratch *= -1.;
    if (parameters.linear_solver == Parameters::Solver::LinearSolver::direct)
      {
        if (!same)
          {
            TimerOutput::Scope t(timer, "Newton: factorization");
            direct_solver = std::make_unique<TrilinosWrappers::SolverDirect>(
              direct_control,
              TrilinosWrappers::SolverDirect::AdditionalData(
                false, parameters.direct_solver_package));
            direct_solver->initialize(system_matrix);
          }
        TimerOutput::Scope t(timer, "Newton: triangular solves");
        direct_solver->solve(increment, scratch);
      }
    else
      {
        if (!amg || amg_k != bulk.time_step())
          {
            // Algebraic multigrid built once per K0 (mesh and k): the contact
            // blocks are a low-rank change that GMRES absorbs.
            TimerOutput::Scope t(timer, "Newton: AMG setup");
            TrilinosWrappers::PreconditionAMG::AdditionalData data;
            data.elliptic              = true;
            data.higher_order_elements = discretization.fe.degree > 1;
            data.smoother_sweeps       = 2;
            data.aggregation_threshold = 0.02;
            // Translations as near-null space (deal.II 9.4 has no rotations).
            DoFTools::extract_constant_modes(discretization.dof_handler,
                                             ComponentMask(),
                                             data.constant_modes);
            amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
            amg->initialize(bulk.newton_matrix(), data);
            amg_k = bulk.time_step();
          }
        TimerOutput::Scope t(timer, "Newton: iterative solve");
        SolverControl      control(parameters.max_linear_iterations,
                              parameters.linear_tolerance * scratch.l2_norm());
        SolverGMRES<Vector_t> gmres(
          control, SolverGMRES<Vector_t>::AdditionalData(100));
        increment = 0;
        gmres.solve(system_matrix, increment, scratch, *amg);
      }
    discretization.constraints.set_zero(increment);

    if (!same)
      {
        factorized_blocks = blocks;
        factorized_k      = k;
        factorized        = true;
      }
    return !same;
  }


  template <int dim>
  unsigned int
  StepSolver<dim>::newton(const Vector_t &rhs,
                          const Vector_t &u_old,
                          Vector_t &      w,
                          Statistics &    statistics)
  {
    const double k = bulk.time_step();
    for (unsigned int iteration = 0;; ++iteration)
      {
        double residual_norm;
        {
          TimerOutput::Scope t(timer, "Newton: residual");
          evaluate_nodes(u_old, w, k);
          residual_norm = compute_residual(rhs, w);
        }
        // The residual is that of the nonlinear law itself, so a small one
        // means a solution, whatever the sets; relative to the size of the
        // terms that balance in it.
        bulk.newton_matrix().vmult(scratch, w);
        const double scale =
          std::max({rhs.l2_norm(), scratch.l2_norm(), 1e-300});
        statistics.residual = residual_norm / scale;
        if (residual_norm <= parameters.newton_tolerance * scale)
          return iteration;

        AssertThrow(iteration < parameters.max_newton_iterations,
                    ExcMessage("The semismooth Newton iteration did not "
                               "converge in Solver/Maximum Newton iterations "
                               "= " +
                               std::to_string(
                                 parameters.max_newton_iterations) +
                               " iterations (relative residual " +
                               std::to_string(residual_norm / scale) + ")."));

        const auto blocks = nodal_blocks(k);
        if (solve_linear_system(blocks, k))
          ++statistics.factorizations;
        w += increment;
        ++statistics.newton_iterations;
      }
  }


  template <int dim>
  typename StepSolver<dim>::Statistics
  StepSolver<dim>::solve(const Vector_t &rhs, const Vector_t &u_old, Vector_t &w)
  {
    Statistics statistics;
    newton(rhs, u_old, w, statistics);
    statistics.convexification_iterations = 1;

    unsigned int n_contact = 0;
    for (const auto &s : states)
      if (s.normal.pressure > 0)
        ++n_contact;
    statistics.n_contact = Utilities::MPI::sum(n_contact, discretization.comm);
    return statistics;
  }


  template class StepSolver<2>;
  template class StepSolver<3>;
} // namespace DynamicContact
