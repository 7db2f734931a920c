#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/bulk/preconditioners.h>
#include <dynamic_contact/contact/assembled_stiffness.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>
#include <dynamic_contact/contact/weakening_limit.h>

#include <array>

namespace DynamicContact
{
  template <int dim>
  void
  AssembledStiffness<dim>::reinit()
  {
    multigrid.reset();
    multigrid_scheme = TimeScheme();
    bulk_blocks.clear();
    blocks_scheme = TimeScheme();
    limits_scheme = TimeScheme();
    limits.clear();
  }


  template <int dim>
  const std::vector<Tensor<2, dim>> &
  AssembledStiffness<dim>::nodal_blocks()
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
  const BulkPreconditioner &
  AssembledStiffness<dim>::preconditioner()
  {
    prepare_preconditioner();
    return *multigrid;
  }


  template <int dim>
  void
  AssembledStiffness<dim>::prepare_preconditioner()
  {
    if (multigrid && multigrid_scheme == problem.bulk.scheme())
      return;
    TimerSection t(problem.timer, "Newton: AMG setup");
    multigrid.reset();
    const bool stored = problem.bulk.stores_newton_matrix();
    multigrid         = create_preconditioner(
      problem.parameters,
      problem.parameters.preconditioner,
      PreconditionerInput<dim>{problem.discretization,
                               stored ? &problem.bulk.newton_matrix() : nullptr,
                                       &problem.bulk.material_law(),
                                       &problem.bulk.scheme(),
                                       problem.bulk.cell_data()});
    multigrid_scheme = problem.bulk.scheme();
  }


  template <int dim>
  void
  AssembledStiffness<dim>::solve(const Vector_t &b,
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
        cg.solve(K0, x, b, *multigrid);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw_cg_failure(e, problem.parameters.max_linear_iterations, b);
      }
    problem.discretization.constraints.set_zero(x);
  }


  template <int dim>
  const std::vector<double> &
  AssembledStiffness<dim>::weakening_limits()
  {
    if (limits_scheme == problem.bulk.scheme() && !limits.empty())
      return limits;
    const auto         &nodes = problem.boundary.nodes();
    const auto         &K0    = nodal_blocks();
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
          solve(load, response, 1e-10);
          if (j >= 0)
            C += outer_product(nodes[j].value(response), nodes[j].tangents[a]);
        }
      return j >= 0 ? WeakeningLimit::tangential_compliance(nodes[j], C) : 0.;
    };
    limits        = WeakeningLimit::limits(nodes,
                                    stiffness,
                                    compliance,
                                    problem.discretization.comm);
    limits_scheme = problem.bulk.scheme();
    return limits;
  }


  template <int dim>
  SpectralEstimate
  AssembledStiffness<dim>::compliance_radius(
    const std::vector<Tensor<2, dim>> &roots)
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
      solve(load, response, 1e-8);
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
  AssembledStiffness<dim>::memory_consumption(MemoryItems &items) const
  {
    if (multigrid)
      items.push_back({dynamic_cast<const BulkAMG *>(multigrid.get()) ?
                         "AMG of K0" :
                         "GMG of K0",
                       multigrid->memory_consumption(),
                       multigrid->memory_measured()});
  }


  template class AssembledStiffness<2>;
  template class AssembledStiffness<3>;
} // namespace DynamicContact
