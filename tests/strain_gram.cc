// The inner product of V evaluated from the cells (StrainGram, matrix-free)
// against the Gram matrix of (eps(u), eps(v)) assembled and condensed with
// the mesh's constraints, as the program stored it before: x^T S y for
// fields in master form, on a distributed mesh with hanging nodes, clamped
// and roller boundaries, Q1 and Q2, 2D and 3D. And against an exact value:
// a linear field (which the hanging-node constraints keep exactly) has
// (eps(u), eps(u)) = |eps|^2 |Omega|.

#include <deal.II/base/function_lib.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/strain_gram.h>

#include "test_tools.h"

using namespace DynamicContact;

namespace
{
  /** S, assembled as BulkOperator assembled it. */
  template <int dim>
  void
  assemble_gram(const Discretization<dim> &d, Matrix_t &S)
  {
    TrilinosWrappers::SparsityPattern pattern(d.locally_owned,
                                              d.locally_owned,
                                              d.locally_relevant,
                                              d.comm);
    DoFTools::make_sparsity_pattern(d.dof_handler,
                                    pattern,
                                    d.constraints,
                                    false,
                                    Utilities::MPI::this_mpi_process(d.comm));
    pattern.compress();
    S.reinit(pattern);
    const QGauss<dim>  quadrature(d.fe.degree + 1);
    FEValues<dim>      fe_values(d.mapping,
                            d.fe,
                            quadrature,
                            update_gradients | update_JxW_values);
    const unsigned int n = d.fe.n_dofs_per_cell();
    FullMatrix<double> local(n, n);
    std::vector<types::global_dof_index> dofs(n);
    const FEValuesExtractors::Vector     u(0);
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          local = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                local(i, j) += (fe_values[u].symmetric_gradient(i, q) *
                                fe_values[u].symmetric_gradient(j, q)) *
                               fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          d.constraints.distribute_local_to_global(local, dofs, S);
        }
    S.compress(VectorOperation::add);
  }


  /** Refine the cells of the left half: hanging nodes. */
  template <int dim>
  Discretization<dim> &
  make_mesh(Discretization<dim> &d)
  {
    GridGenerator::subdivided_hyper_rectangle(d.triangulation,
                                              std::vector<unsigned int>(dim,
                                                                        4),
                                              Point<dim>(),
                                              dim == 2 ?
                                                Point<dim>(2., 1.) :
                                                Point<dim>(2., 1., 1.),
                                              true);
    for (const auto &cell : d.triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && cell->center()[0] < 1.)
        cell->set_refine_flag();
    d.triangulation.execute_coarsening_and_refinement();
    return d;
  }
} // namespace


template <int dim>
void
check(const unsigned int degree)
{
  const std::string name =
    std::to_string(dim) + "D Q" + std::to_string(degree) + ": ";

  // Clamped on the left (id 0), rollers at the bottom (id 2).
  {
    Discretization<dim> d(MPI_COMM_WORLD, degree);
    make_mesh(d);
    Parameters::BoundaryConditions bc;
    bc.clamped = {0};
    bc.roller  = {2};
    d.setup_dofs(bc);
    Matrix_t S;
    assemble_gram(d, S);
    StrainGram<dim> gram(d);
    gram.reinit();

    Vector_t x, y, Sy;
    d.reinit_owned(x);
    d.reinit_owned(y);
    d.reinit_owned(Sy);
    VectorTools::interpolate(d.mapping,
                             d.dof_handler,
                             Functions::CosineFunction<dim>(dim),
                             x);
    VectorTools::interpolate(d.mapping,
                             d.dof_handler,
                             Functions::SquareFunction<dim>(),
                             y);
    for (Vector_t *v : {&x, &y})
      d.constraints.set_zero(*v);
    double worst = 0;
    for (const auto &[a, b] : {std::make_pair(&x, &x),
                               std::make_pair(&x, &y),
                               std::make_pair(&y, &y)})
      {
        S.vmult(Sy, *b);
        const double assembled = *a * Sy;
        const double cells     = gram.product(*a, *b);
        worst =
          std::max(worst,
                   std::abs(cells - assembled) / std::abs(assembled));
      }
    test_tools::check(worst < 1e-12,
                      name + "(eps(x), eps(y)) equals x^T S y to 1e-12 "
                             "(clamped, rollers, hanging nodes)");
  }

  // No boundary condition, u = (x_1, x_0 / 2, 0): eps_01 = eps_10 = 3/4,
  // the other entries 0, |eps|^2 = 2 (3/4)^2; |Omega| = 2.
  {
    Discretization<dim> d(MPI_COMM_WORLD, degree);
    make_mesh(d);
    d.setup_dofs(Parameters::BoundaryConditions());
    StrainGram<dim> gram(d);
    gram.reinit();
    Vector_t u;
    d.reinit_owned(u);
    struct Linear : public Function<dim>
    {
      Linear()
        : Function<dim>(dim)
      {}
      double
      value(const Point<dim> &p, const unsigned int c) const override
      {
        return c == 0 ? p[1] : c == 1 ? 0.5 * p[0] : 0.;
      }
    };
    VectorTools::interpolate(d.mapping, d.dof_handler, Linear(), u);
    d.constraints.set_zero(u);
    const double exact = 2 * 0.5625 * 2.;
    const double cells = gram.product(u, u);
    test_tools::check(std::abs(cells - exact) < 1e-12 * exact,
                      name + "a linear field: |eps|^2 |Omega| to 1e-12");
  }
}


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>(1);
  check<2>(2);
  check<3>(1);
}
