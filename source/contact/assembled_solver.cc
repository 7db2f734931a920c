#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/bulk/preconditioners.h>
#include <dynamic_contact/contact/assembled_node_dofs.h>
#include <dynamic_contact/contact/assembled_solver.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>
#include <dynamic_contact/contact/weakening_limit.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace DynamicContact
{
  using namespace AssembledNodeDofs;


  template <int dim>
  AssembledSolver<dim>::AssembledSolver(const ContactProblem<dim> &problem)
    : problem(problem)
  {}


  template <int dim>
  void
  AssembledSolver<dim>::reinit()
  {
    for (auto *v : {&increment, &scratch, &scratch2, &base_residual})
      problem.discretization.reinit_owned(*v);
    preconditioner.reset();
    preconditioner_scheme = TimeScheme();
    bulk_blocks.clear();
    blocks_scheme = TimeScheme();
    limits_scheme = TimeScheme();
    weakening_limits.clear();
    direct.reset();
    factorized_scheme = TimeScheme();
    factorized_blocks.clear();
    factorized_stick.clear();
    if (problem.parameters.linear_solver ==
        Parameters::Solver::LinearSolver::direct)
      system_matrix.reinit(problem.bulk.sparsity_pattern());
    else
      system_matrix.clear();
  }


  template <int dim>
  typename AssembledSolver<dim>::Result
  AssembledSolver<dim>::solve(const ContactStep<dim>      &step,
                              std::vector<Tensor<1, dim>> &lambda,
                              Vector_t                    &w)
  {
    Assert(step.scheme == problem.bulk.scheme(),
           ExcMessage("K0 is not formed for the step's time scheme."));
    Result               result;
    FrictionCoefficients coefficients = step.mu;
    if (step.mu.coupled())
      coefficients.weakening_limit = coupled_limits();
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
    const auto        &K0    = nodal_bulk_blocks();

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
      solve_iterative(system, newton, x, increment, result);
    else
      solve_direct(system, newton, x, increment, result);
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
  void
  AssembledSolver<dim>::apply_jacobian(const NodalSystem &system,
                                       const Vector_t    &x,
                                       Vector_t          &y) const
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
  const std::vector<Tensor<2, dim>> &
  AssembledSolver<dim>::nodal_bulk_blocks()
  {
    if (blocks_scheme == problem.bulk.scheme() &&
        bulk_blocks.size() == problem.boundary.nodes().size())
      return bulk_blocks;
    std::vector<std::array<types::global_dof_index, dim>> dofs;
    for (const auto &node : problem.boundary.nodes())
      dofs.push_back(node.dofs);
    bulk_blocks   = problem.bulk.newton_blocks(dofs);
    blocks_scheme = problem.bulk.scheme();
    return bulk_blocks;
  }


  template <int dim>
  void
  AssembledSolver<dim>::prepare_preconditioner()
  {
    if (preconditioner && preconditioner_scheme == problem.bulk.scheme())
      return;
    TimerSection t(problem.timer, "Newton: AMG setup");
    preconditioner.reset();
    const bool stored = problem.bulk.stores_newton_matrix();
    preconditioner    = create_preconditioner(
      problem.parameters,
      problem.parameters.preconditioner,
      PreconditionerInput<dim>{problem.discretization,
                               stored ? &problem.bulk.newton_matrix() : nullptr,
                                  &problem.bulk.material_law(),
                                  &problem.bulk.scheme(),
                                  problem.bulk.cell_data()});
    preconditioner_scheme = problem.bulk.scheme();
  }


  template <int dim>
  void
  AssembledSolver<dim>::solve_bulk(const Vector_t &b,
                                   Vector_t       &x,
                                   const double    tolerance)
  {
    prepare_preconditioner();
    if (x.size() != b.size())
      problem.discretization.reinit_owned(x);
    x                 = 0;
    const double norm = b.l2_norm();
    if (norm == 0)
      return;
    SolverControl      control(problem.parameters.max_linear_iterations,
                          tolerance * norm);
    SolverCG<Vector_t> cg(control);
    try
      {
        const BulkMatrixOperator<dim> K0{problem.bulk};
        cg.solve(K0, x, b, *preconditioner);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw_cg_failure(e, problem.parameters.max_linear_iterations, b);
      }
    problem.discretization.constraints.set_zero(x);
  }


  template <int dim>
  const std::vector<double> &
  AssembledSolver<dim>::coupled_limits()
  {
    if (limits_scheme == problem.bulk.scheme() && !weakening_limits.empty())
      return weakening_limits;
    const auto         &nodes = problem.boundary.nodes();
    const auto         &K0    = nodal_bulk_blocks();
    std::vector<double> stiffness(nodes.size(), 0.);
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (nodes[i].unconstrained)
        stiffness[i] = WeakeningLimit::tangential_stiffness(nodes[i], K0[i]);
    Vector_t load, response;
    problem.discretization.reinit_owned(load);
    // The compliance of sample node j: K0^{-1} P_j^T t for its tangents t.
    const auto compliance = [&](const int j) {
      Tensor<2, dim> C;
      for (unsigned int a = 0; a < dim - 1; ++a)
        {
          load = 0;
          problem.boundary.add_nodal_forces(
            [&](const unsigned int i) {
              return static_cast<int>(i) == j ? nodes[i].tangents[a] :
                                                Tensor<1, dim>();
            },
            1.,
            load);
          solve_bulk(load, response, 1e-10);
          if (j >= 0)
            C += outer_product(nodes[j].value(response), nodes[j].tangents[a]);
        }
      return j >= 0 ? WeakeningLimit::tangential_compliance(nodes[j], C) : 0.;
    };
    weakening_limits = WeakeningLimit::limits(nodes,
                                              stiffness,
                                              compliance,
                                              problem.discretization.comm);
    limits_scheme    = problem.bulk.scheme();
    return weakening_limits;
  }


  template <int dim>
  SpectralEstimate
  AssembledSolver<dim>::compliance_radius(
    const std::vector<Tensor<2, dim>> &roots,
    const bool)
  {
    const auto        &nodes = problem.boundary.nodes();
    const unsigned int n     = nodes.size();
    const MPI_Comm     comm  = problem.discretization.comm;
    Vector_t           load, response;
    problem.discretization.reinit_owned(load);
    // y = S P K0^{-1} P^T S x; the CG tolerance is well below the
    // eigenvalue's.
    const auto apply = [&](const std::vector<double> &x,
                           std::vector<double>       &y) {
      load = 0;
      problem.boundary.add_nodal_forces(
        [&](const unsigned int i) {
          return roots[i] * nodal_entries<dim>(x, i);
        },
        1.,
        load);
      solve_bulk(load, response, 1e-8);
      for (unsigned int i = 0; i < n; ++i)
        set_nodal_entries<dim>(roots[i] * nodes[i].value(response), i, y);
    };
    std::vector<double> start(dim * n);
    for (unsigned int i = 0; i < n; ++i)
      set_nodal_entries<dim>(roots[i] * lanczos_start(nodes[i]), i, start);
    return SpectralEstimate{largest_eigenvalue(apply,
                                               start,
                                               [comm](const double v) {
                                                 return Utilities::MPI::sum(
                                                   v, comm);
                                               }),
                            -1.};
  }


  template <int dim>
  void
  AssembledSolver<dim>::assemble_direct_matrix(const NodalSystem &system)
  {
    const auto  &nodes = problem.boundary.nodes();
    TimerSection t(problem.timer, "Newton: matrix update");
    system_matrix.copy_from(problem.bulk.newton_matrix());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      for (unsigned int r = 0; r < dim; ++r)
        for (unsigned int c = 0; c < dim; ++c)
          if (system.blocks[i][r][c] != 0)
            system_matrix.add(nodes[i].dofs[r],
                              nodes[i].dofs[c],
                              system.blocks[i][r][c]);
    system_matrix.compress(VectorOperation::add);

    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (system.stick[i])
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


  template <int dim>
  void
  AssembledSolver<dim>::solve_direct(const NodalSystem             &system,
                                     const WholeSystemNewton<dim>  &newton,
                                     const WholeSystemIterate<dim> &x,
                                     Vector_t                      &dw,
                                     Result                        &result)
  {
    const auto &nodes = problem.boundary.nodes();

    // The Newton matrix changes only through the nodal blocks, the stick
    // set and K0's k: reuse the factorization if none of them changed.
    bool same =
      (factorized_scheme == newton.scheme &&
       factorized_blocks == system.blocks && factorized_stick == system.stick);
    same = Utilities::MPI::min(same ? 1 : 0, problem.discretization.comm) == 1;

    if (!same)
      assemble_direct_matrix(system);

    // Right-hand side: -R, with the stick nodes' rows replaced likewise.
    scratch2 = base_residual;
    scratch2 *= -1.;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (system.stick[i])
        {
          const auto          &node = nodes[i];
          const Tensor<1, dim> r    = raw_values(node, scratch2);
          // t_s . w_e = 0 at the new iterate: t_s . dw = -(t_s . w_e)/theta.
          const Tensor<1, dim> w_e =
            newton.effective_velocity(i, node.value(x.w));
          const unsigned int host   = host_component(node);
          scratch2(node.dofs[host]) = node.normal * r;
          unsigned int s            = 0;
          for (unsigned int c = 0; c < dim; ++c)
            if (c != host)
              scratch2(node.dofs[c]) = -(node.tangents[s++] * w_e) /
                                       newton.scheme.effective_derivative();
        }
    scratch2.compress(VectorOperation::insert);

    if (!same)
      {
        TimerSection t(problem.timer, "Newton: factorization");
        direct = std::make_unique<TrilinosWrappers::SolverDirect>(
          direct_control,
          TrilinosWrappers::SolverDirect::AdditionalData(
            false, amesos_package(problem.parameters)));
        const HeapGrowth growth;
        direct->initialize(system_matrix);
        growth.keep_largest(factorization_bytes);
        return_free_memory();
        ++result.factorizations;
        factorized_blocks = system.blocks;
        factorized_stick  = system.stick;
        factorized_scheme = newton.scheme;
      }
    TimerSection t(problem.timer, "Newton: triangular solves");
    direct->solve(dw, scratch2);
  }


  template <int dim>
  void
  AssembledSolver<dim>::memory_consumption(MemoryItems &items) const
  {
    if (preconditioner)
      items.push_back({dynamic_cast<const BulkAMG *>(preconditioner.get()) ?
                         "AMG of K0" :
                         "GMG of K0",
                       preconditioner->memory_consumption(),
                       preconditioner->memory_measured()});
    if (problem.parameters.linear_solver ==
        Parameters::Solver::LinearSolver::iterative)
      items.push_back({"GMRES basis (the most a solve used)",
                       double(largest_basis) *
                         problem.discretization.locally_owned.n_elements() *
                         sizeof(double),
                       false});
    if (system_matrix.m() > 0)
      {
        items.push_back({"Newton matrix (values)",
                         stored_values_bytes(system_matrix),
                         false});
        items.push_back(
          {"factorization of the Newton matrix", factorization_bytes, true});
      }
  }


  template class AssembledSolver<2>;
  template class AssembledSolver<3>;
} // namespace DynamicContact
