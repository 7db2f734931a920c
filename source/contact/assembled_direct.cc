#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/assembled_linear_solves.h>
#include <dynamic_contact/contact/assembled_node_dofs.h>

// The assembled solver's Newton step with Linear solver = direct: the
// Newton matrix assembled and factorized when it changes.

namespace DynamicContact
{
  using namespace AssembledNodeDofs;


  template <int dim>
  void
  AssembledDirectSolve<dim>::reinit()
  {
    problem.discretization.reinit_owned(right_hand_side);
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
  void
  AssembledDirectSolve<dim>::assemble_matrix(
    const AssembledNodalSystem<dim> &system)
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
  AssembledDirectSolve<dim>::solve(const AssembledNewtonStep<dim> &step,
                                   Vector_t                       &dw,
                                   ContactSolveResult             &result)
  {
    const auto &nodes = problem.boundary.nodes();

    // The Newton matrix changes only through the nodal blocks, the stick
    // set and K0's k: reuse the factorization if none of them changed.
    bool same = (factorized_scheme == step.newton.scheme &&
                 factorized_blocks == step.system.blocks &&
                 factorized_stick == step.system.stick);
    same = Utilities::MPI::min(same ? 1 : 0, problem.discretization.comm) == 1;

    if (!same)
      assemble_matrix(step.system);

    // Right-hand side: -R, with the stick nodes' rows replaced likewise.
    right_hand_side = step.base_residual;
    right_hand_side *= -1.;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (step.system.stick[i])
        {
          const auto          &node = nodes[i];
          const Tensor<1, dim> r    = raw_values(node, right_hand_side);
          // t_s . w_e = 0 at the new iterate: t_s . dw = -(t_s . w_e)/theta.
          const Tensor<1, dim> w_e =
            step.newton.effective_velocity(i, node.value(step.x.w));
          const unsigned int host          = host_component(node);
          right_hand_side(node.dofs[host]) = node.normal * r;
          unsigned int s                   = 0;
          for (unsigned int c = 0; c < dim; ++c)
            if (c != host)
              right_hand_side(node.dofs[c]) =
                -(node.tangents[s++] * w_e) /
                step.newton.scheme.effective_derivative();
        }
    right_hand_side.compress(VectorOperation::insert);

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
        factorized_blocks = step.system.blocks;
        factorized_stick  = step.system.stick;
        factorized_scheme = step.newton.scheme;
      }
    TimerSection t(problem.timer, "Newton: triangular solves");
    direct->solve(dw, right_hand_side);
  }


  template <int dim>
  void
  AssembledDirectSolve<dim>::memory_consumption(MemoryItems &items) const
  {
    if (system_matrix.m() > 0)
      {
        items.push_back({"Newton matrix (values)",
                         stored_values_bytes(system_matrix),
                         false});
        items.push_back(
          {"factorization of the Newton matrix", factorization_bytes, true});
      }
  }


  template class AssembledDirectSolve<2>;
  template class AssembledDirectSolve<3>;
} // namespace DynamicContact
