#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <dynamic_contact/assembled_newton.h>
#include <dynamic_contact/bulk_solver.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  template <int dim>
  AssembledNewton<dim>::AssembledNewton(const ContactProblem<dim> &problem)
    : problem(problem)
  {}


  template <int dim>
  void
  AssembledNewton<dim>::reinit()
  {
    system_matrix.reinit(problem.bulk.sparsity_pattern());
    for (auto *v : {&residual, &increment, &scratch})
      problem.discretization.reinit_owned(*v);
    direct.reset();
    amg.reset();
    amg_k        = 0;
    factorized_k = -1;
    factorized_blocks.clear();
    factorized_stick.clear();
  }


  template <int dim>
  double
  AssembledNewton<dim>::compute_residual(
    const Vector_t &                    rhs,
    const Vector_t &                    w,
    const std::vector<Tensor<1, dim>> &owned_forces)
  {
    problem.bulk.newton_matrix().vmult(residual, w);
    residual -= rhs;
    problem.boundary.add_nodal_forces(
      [&](const unsigned int i) { return owned_forces[i]; }, 1., residual);
    return residual.l2_norm();
  }


  template <int dim>
  bool
  AssembledNewton<dim>::solve_linear_system(
    const std::vector<Tensor<2, dim>> &blocks,
    const std::vector<bool> &          stick,
    const std::vector<Tensor<1, dim>> &w_effective)
  {
    const auto & nodes = problem.boundary.nodes();
    const double k     = problem.bulk.time_step();

    // The Newton matrix changes only through the nodal blocks, the stick
    // set and K0's k: reuse the factorization if none of them changed.
    bool same = (factorized_k == k && factorized_blocks == blocks &&
                 factorized_stick == stick);
    same      = Utilities::MPI::min(same ? 1 : 0,
                               problem.discretization.comm) == 1;

    // The host row of each stick node's normal equation: the component
    // with the largest normal entry; the others carry t_s . w = 0.
    auto host_component = [](const ContactNode<dim> &node) {
      unsigned int host = 0;
      for (unsigned int c = 1; c < dim; ++c)
        if (std::abs(node.normal[c]) > std::abs(node.normal[host]))
          host = c;
      return host;
    };

    if (!same)
      {
        TimerOutput::Scope t(problem.timer, "Newton: matrix update");
        system_matrix.copy_from(problem.bulk.newton_matrix());
        for (unsigned int i = 0; i < nodes.size(); ++i)
          for (unsigned int r = 0; r < dim; ++r)
            for (unsigned int c = 0; c < dim; ++c)
              if (blocks[i][r][c] != 0)
                system_matrix.add(nodes[i].dofs[r],
                                  nodes[i].dofs[c],
                                  blocks[i][r][c]);
        system_matrix.compress(VectorOperation::add);

        for (unsigned int i = 0; i < nodes.size(); ++i)
          if (stick[i])
            {
              const auto &node = nodes[i];
              // Rows of one vertex have the same columns (FESystem).
              std::vector<types::global_dof_index> columns;
              std::vector<double>                  combined;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  unsigned int e = 0;
                  for (auto it = system_matrix.begin(node.dofs[c]);
                       it != system_matrix.end(node.dofs[c]);
                       ++it, ++e)
                    {
                      if (c == 0)
                        {
                          columns.push_back(it->column());
                          combined.push_back(0);
                        }
                      Assert(columns[e] == it->column(), ExcInternalError());
                      combined[e] += node.normal[c] * it->value();
                    }
                }
              const unsigned int host = host_component(node);
              system_matrix.set(node.dofs[host], columns, combined);
              unsigned int s = 0;
              for (unsigned int c = 0; c < dim; ++c)
                if (c != host)
                  {
                    std::vector<double> row(columns.size(), 0.);
                    for (unsigned int e = 0; e < columns.size(); ++e)
                      for (unsigned int q = 0; q < dim; ++q)
                        if (columns[e] == node.dofs[q])
                          row[e] = node.tangents[s][q];
                    system_matrix.set(node.dofs[c], columns, row);
                    ++s;
                  }
            }
        system_matrix.compress(VectorOperation::insert);
      }

    // Right-hand side: -R, with the stick nodes' rows replaced likewise.
    scratch = residual;
    scratch *= -1.;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (stick[i])
        {
          const auto &   node = nodes[i];
          Tensor<1, dim> r;
          for (unsigned int c = 0; c < dim; ++c)
            r[c] = scratch[node.dofs[c]];
          // t_s . w_e = 0 at the new iterate: t_s . dw = -(t_s . w_e)/theta.
          const Tensor<1, dim> &w_e  = w_effective[i];
          const unsigned int    host = host_component(node);
          scratch(node.dofs[host])   = node.normal * r;
          unsigned int s             = 0;
          for (unsigned int c = 0; c < dim; ++c)
            if (c != host)
              scratch(node.dofs[c]) =
                -(node.tangents[s++] * w_e) / problem.theta;
        }
    scratch.compress(VectorOperation::insert);

    if (problem.parameters.linear_solver ==
        Parameters::Solver::LinearSolver::direct)
      {
        if (!same)
          {
            TimerOutput::Scope t(problem.timer, "Newton: factorization");
            direct = std::make_unique<TrilinosWrappers::SolverDirect>(
              direct_control,
              TrilinosWrappers::SolverDirect::AdditionalData(
                false, problem.parameters.direct_solver_package));
            direct->initialize(system_matrix);
          }
        TimerOutput::Scope t(problem.timer, "Newton: triangular solves");
        direct->solve(increment, scratch);
      }
    else
      {
        if (!amg || amg_k != k)
          {
            // Algebraic multigrid built once per K0 (mesh and k): the contact
            // rows are a low-rank change that GMRES absorbs.
            TimerOutput::Scope t(problem.timer, "Newton: AMG setup");
            std::vector<std::vector<bool>> constant_modes;
            DoFTools::extract_constant_modes(
              problem.discretization.dof_handler,
              ComponentMask(),
              constant_modes);
            amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
            amg->initialize(
              problem.bulk.newton_matrix(),
              bulk_amg_data(constant_modes,
                            problem.discretization.fe.degree > 1));
            amg_k = k;
          }
        TimerOutput::Scope    t(problem.timer, "Newton: iterative solve");
        SolverControl         control(problem.parameters.max_linear_iterations,
                              problem.parameters.linear_tolerance *
                                scratch.l2_norm());
        SolverGMRES<Vector_t> gmres(control,
                                    SolverGMRES<Vector_t>::AdditionalData(100));
        increment = 0;
        gmres.solve(system_matrix, increment, scratch, *amg);
      }
    problem.discretization.constraints.set_zero(increment);

    if (!same)
      {
        factorized_blocks = blocks;
        factorized_stick  = stick;
        factorized_k      = k;
      }
    return !same;
  }


  template <int dim>
  typename AssembledNewton<dim>::Result
  AssembledNewton<dim>::solve(const Vector_t &                    rhs,
                              const std::vector<Tensor<1, dim>> &u_old,
                              const std::vector<Tensor<1, dim>> &w_old,
                              const std::vector<double> &         mu,
                              std::vector<Tensor<1, dim>> &       lambda,
                              Vector_t &                          w)
  {
    Result       result;
    const auto & nodes  = problem.boundary.nodes();
    const auto & global = problem.boundary.global_indices();
    const double k      = problem.bulk.time_step();
    const MPI_Comm comm = problem.discretization.comm;

    std::vector<NodeLinearization<dim>> lin(nodes.size());
    std::vector<Tensor<1, dim>>         forces(nodes.size());
    std::vector<Tensor<2, dim>>         blocks(nodes.size());
    std::vector<bool>                   stick(nodes.size());

    for (unsigned int iteration = 0;; ++iteration)
      {
        double law_residual = 0, f_scale = 1e-300, residual_norm;
        {
          TimerOutput::Scope t(problem.timer, "Newton: residual");
          for (unsigned int i = 0; i < nodes.size(); ++i)
            {
              const unsigned int   g   = global[i];
              const Tensor<1, dim> wi  = nodes[i].value(w);
              const double         th  = problem.theta;
              const Tensor<1, dim> w_e = th * wi + (1 - th) * w_old[g];
              lin[i]    = linearize_node(problem.foundation,
                                      nodes[i],
                                      u_old[g],
                                      w_old[g],
                                      wi,
                                      k,
                                      th,
                                      problem.friction,
                                      lambda[g],
                                      problem.friction ? mu[g] : 0.,
                                      problem.c_t * k);
              forces[i] = lin[i].normal.pressure * nodes[i].weight *
                            nodes[i].normal +
                          lambda[g];
              f_scale   = std::max(f_scale, forces[i].norm());
              if (problem.friction)
                law_residual =
                  std::max(law_residual,
                           (lambda[g] -
                            projected_friction_force(nodes[i],
                                                     lin[i].friction.threshold,
                                                     w_e,
                                                     lambda[g],
                                                     problem.c_t * k))
                             .norm());
            }
          residual_norm = compute_residual(rhs, w, forces);
        }
        problem.bulk.newton_matrix().vmult(scratch, w);
        const double scale =
          std::max({rhs.l2_norm(), scratch.l2_norm(), 1e-300});
        law_residual = Utilities::MPI::max(law_residual, comm);
        f_scale      = Utilities::MPI::max(f_scale, comm);
        result.residual =
          std::max(residual_norm / scale, law_residual / f_scale);
        problem.details << "    Newton " << iteration << ": residual "
                        << result.residual << " (equilibrium "
                        << residual_norm / scale << ", law "
                        << law_residual / f_scale << ")" << std::endl;
        if (result.residual <= problem.parameters.newton_tolerance)
          break;
        check_newton_cap(iteration, result.residual, problem.parameters);

        // The linearized forces: normal law and slip values; at stick
        // nodes the tangential force is what the solve determines.
        std::vector<Tensor<1, dim>> base(nodes.size());
        for (unsigned int i = 0; i < nodes.size(); ++i)
          {
            base[i] = lin[i].normal.pressure * nodes[i].weight * nodes[i].normal;
            if (lin[i].friction.state == ContactState::slip)
              base[i] += lin[i].friction.value;
            const Tensor<2, dim> &P = nodes[i].constraint_map;
            blocks[i]               = transpose(P) * lin[i].block * P;
            stick[i] = (lin[i].friction.state == ContactState::stick);
          }
        std::vector<Tensor<1, dim>> w_effective(nodes.size());
        for (unsigned int i = 0; i < nodes.size(); ++i)
          w_effective[i] = problem.theta * nodes[i].value(w) +
                           (1 - problem.theta) * w_old[global[i]];
        compute_residual(rhs, w, base);
        if (solve_linear_system(blocks, stick, w_effective))
          ++result.factorizations;
        w += increment;
        ++result.iterations;

        // Friction forces at the new iterate.
        if (problem.friction)
          {
            std::vector<Tensor<1, dim>> owned_lambda(nodes.size());
            std::vector<Tensor<1, dim>> new_base(nodes.size());
            for (unsigned int i = 0; i < nodes.size(); ++i)
              {
                const Tensor<1, dim> dw = nodes[i].value(increment);
                const auto &         l  = lin[i];
                new_base[i] = l.normal.pressure * nodes[i].weight *
                                nodes[i].normal +
                              (l.block - l.friction.jacobian) * dw;
                if (l.friction.state == ContactState::slip)
                  {
                    owned_lambda[i] = l.friction.value + l.friction.jacobian * dw;
                    new_base[i] += owned_lambda[i];
                  }
              }
            // Stick: lambda = -(tangential residual without friction).
            compute_residual(rhs, w, new_base);
            for (unsigned int i = 0; i < nodes.size(); ++i)
              if (stick[i])
                {
                  Tensor<1, dim> r;
                  for (unsigned int c = 0; c < dim; ++c)
                    r[c] = residual[nodes[i].dofs[c]];
                  owned_lambda[i] = -nodes[i].tangential(r);
                }
            // Every process gets every node's friction force.
            std::vector<double> packed;
            for (unsigned int i = 0; i < nodes.size(); ++i)
              {
                packed.push_back(global[i]);
                for (unsigned int d = 0; d < dim; ++d)
                  packed.push_back(owned_lambda[i][d]);
              }
            for (auto &l : lambda)
              l = Tensor<1, dim>();
            for (const auto &part : Utilities::MPI::all_gather(comm, packed))
              for (std::size_t p = 0; p < part.size(); p += dim + 1)
                for (unsigned int d = 0; d < dim; ++d)
                  lambda[static_cast<unsigned int>(part[p])][d] =
                    part[p + 1 + d];
          }
      }
    return result;
  }


  template class AssembledNewton<2>;
  template class AssembledNewton<3>;
} // namespace DynamicContact
