// The bulk forms applied from the cells (CellOperators, matrix-free)
// against the matrices assembled and condensed with the mesh's constraints,
// as the program stored them before: x^T F y and F x for fields in master
// form, F the mass, elasticity (E = 2e11, nu = 0.3, plane stress in 2D),
// viscosity (Lame constants 3 and 5) and strain forms, on a distributed
// mesh with hanging nodes, clamped and roller boundaries, Q1 and Q2, 2D and
// 3D. And against an exact value: a
// linear field (which the hanging-node constraints keep exactly) has
// (eps(u), eps(u)) = |eps|^2 |Omega|.

#include <deal.II/base/function_lib.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>

#include <dynamic_contact/bulk/cell_operators.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/laws/material.h>

#include "test_tools.h"

using namespace DynamicContact;

namespace
{
  /** The matrix of @p form, assembled as BulkOperator assembled M, B, A. */
  template <int dim>
  void
  assemble(const Discretization<dim>              &d,
           const KelvinVoigtMaterial<dim>         &material,
           const typename CellOperators<dim>::Form form,
           Matrix_t                               &F)
  {
    using Form = typename CellOperators<dim>::Form;
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
    F.reinit(pattern);
    const QGauss<dim>                    quadrature(d.fe.degree + 1);
    FEValues<dim>                        fe_values =
      d.cell_values(quadrature,
                    update_values | update_gradients | update_JxW_values);
    const unsigned int                   n = d.fe.n_dofs_per_cell();
    FullMatrix<double>                   local(n, n);
    std::vector<types::global_dof_index> dofs(n);
    const FEValuesExtractors::Vector     u(0);
    SymmetricTensor<4, dim>              T = identity_tensor<dim>();
    if (form == Form::elasticity)
      T = material.elasticity();
    else if (form == Form::viscosity)
      T = material.viscosity();
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          local = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                local(i, j) +=
                  (form == Form::mass ?
                     fe_values[u].value(i, q) * fe_values[u].value(j, q) :
                     (T * fe_values[u].symmetric_gradient(i, q)) *
                       fe_values[u].symmetric_gradient(j, q)) *
                  fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          d.constraints.distribute_local_to_global(local, dofs, F);
        }
    F.compress(VectorOperation::add);
  }


  /** The box of 4 cells across, the cells of its left half refined. */
  template <int dim>
  void
  make_mesh(Discretization<dim> &d)
  {
    test_tools::make_box(d.triangulation, 4);
    test_tools::refine_left_half(d.triangulation);
  }


  /**
   * x^T F y and F x from the cells against the assembled F, for each form;
   * clamped on the left (id 0), rollers at the bottom (id 2).
   */
  template <int dim>
  void
  check_forms(const unsigned int degree, const std::string &name)
  {
    Discretization<dim> d(MPI_COMM_WORLD, degree);
    make_mesh(d);
    Parameters::BoundaryConditions bc;
    bc.clamped = {0};
    bc.roller  = {2};
    d.setup_dofs(bc);
    const auto         m = test_tools::steel<dim>(3, 5);
    CellOperators<dim> forms(d, m);
    forms.reinit();

    Vector_t x = test_tools::cosine_field(d), y, Fy, cells_Fy;
    d.reinit_owned(y);
    d.reinit_owned(Fy);
    d.reinit_owned(cells_Fy);
    VectorTools::interpolate(d.mapping,
                             d.dof_handler,
                             Functions::SquareFunction<dim>(),
                             y);
    d.constraints.set_zero(y);
    using Form = typename CellOperators<dim>::Form;
    for (const auto &[form, form_name] :
         {std::make_pair(Form::mass, "mass"),
          std::make_pair(Form::elasticity, "elasticity"),
          std::make_pair(Form::viscosity, "viscosity"),
          std::make_pair(Form::strain, "strain")})
      {
        Matrix_t F;
        assemble(d, m, form, F);
        double worst_product = 0, worst_vmult = 0;
        for (const auto &[a, b] : {std::make_pair(&x, &x),
                                   std::make_pair(&x, &y),
                                   std::make_pair(&y, &y)})
          {
            F.vmult(Fy, *b);
            const double assembled = *a * Fy;
            worst_product =
              std::max(worst_product,
                       std::abs(forms.product(form, *a, *b) - assembled) /
                         std::abs(assembled));
            forms.vmult(form, cells_Fy, *b);
            cells_Fy -= Fy;
            worst_vmult =
              std::max(worst_vmult, cells_Fy.linfty_norm() / Fy.linfty_norm());
          }
        test_tools::check(worst_product < 1e-12 && worst_vmult < 1e-12,
                          name + form_name +
                            ": x^T F y and F x as assembled, to 1e-12 "
                            "(clamped, rollers, hanging nodes)");
      }
  }


  /** u = (x_1, x_0 / 2, 0). */
  template <int dim>
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


  /**
   * No boundary condition, u = (x_1, x_0 / 2, 0): eps_01 = eps_10 = 3/4,
   * the other entries 0, |eps|^2 = 2 (3/4)^2; |Omega| = 2.
   */
  template <int dim>
  void
  check_linear_field(const unsigned int degree, const std::string &name)
  {
    Discretization<dim> d(MPI_COMM_WORLD, degree);
    make_mesh(d);
    d.setup_dofs(Parameters::BoundaryConditions());
    const auto         m = test_tools::steel<dim>(3, 5);
    CellOperators<dim> forms(d, m);
    forms.reinit();
    Vector_t u;
    d.reinit_owned(u);
    VectorTools::interpolate(d.mapping, d.dof_handler, Linear<dim>(), u);
    d.constraints.set_zero(u);
    const double exact = 2 * 0.5625 * 2.;
    const double cells = forms.product(CellOperators<dim>::Form::strain, u, u);
    test_tools::check(std::abs(cells - exact) < 1e-12 * exact,
                      name + "a linear field: |eps|^2 |Omega| to 1e-12");
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  test_tools::for_each_element({{2, 1}, {2, 2}, {3, 1}},
                               [](const auto dim, const unsigned int degree) {
                                 constexpr int     d = decltype(dim)::value;
                                 const std::string name =
                                   std::to_string(d) + "D Q" +
                                   std::to_string(degree) + ": ";
                                 check_forms<d>(degree, name);
                                 check_linear_field<d>(degree, name);
                               });
}
