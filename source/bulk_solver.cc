#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <dynamic_contact/bulk_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>

namespace DynamicContact
{
  using namespace dealii;

  template <int dim>
  std::vector<double>
  rigid_body_modes(const Discretization<dim> &discretization,
                   std::vector<double>       *coordinates)
  {
    // From each owned DoF's component and support point (every owned DoF
    // lies on an owned cell).
    const IndexSet     &owned   = discretization.locally_owned;
    const unsigned int  n       = owned.n_elements();
    const unsigned int  n_modes = (dim == 2 ? 3 : 6);
    std::vector<double> modes(n_modes * n, 0.);
    if (coordinates != nullptr)
      coordinates->assign(n, 0.);
    const auto                          &fe = discretization.fe;
    FEValues<dim>                        fe_values(discretization.mapping,
                            fe,
                            Quadrature<dim>(fe.get_unit_support_points()),
                            update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (owned.is_element(dofs[i]))
              {
                const unsigned int r = owned.index_within_set(dofs[i]);
                const unsigned int c = fe.system_to_component_index(i).first;
                const Point<dim>  &x = fe_values.quadrature_point(i);
                modes[c * n + r]     = 1;
                if (coordinates != nullptr)
                  (*coordinates)[r] = x[c];
                if constexpr (dim == 2)
                  modes[2 * n + r] = (c == 0 ? -x[1] : x[0]);
                else
                  {
                    // Rotations about the x, y and z axes.
                    modes[3 * n + r] = (c == 1 ? -x[2] : c == 2 ? x[1] : 0);
                    modes[4 * n + r] = (c == 0 ? x[2] : c == 2 ? -x[0] : 0);
                    modes[5 * n + r] = (c == 0 ? -x[1] : c == 1 ? x[0] : 0);
                  }
              }
        }
    return modes;
  }


  template <int dim>
  void
  BulkAMG::initialize(const Matrix_t            &matrix,
                      const Discretization<dim> &discretization,
                      const bool                 with_rotations)
  {
    modes = rigid_body_modes(discretization);
    // The translations are the first dim columns.
    const unsigned int n_modes = (with_rotations ? (dim == 2 ? 3 : 6) : dim);
    const auto        &fe      = discretization.fe;

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = fe.degree > 1;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    Teuchos::ParameterList              list;
    std::unique_ptr<Epetra_MultiVector> unused;
    data.set_parameters(list, unused, matrix);
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", static_cast<int>(n_modes));
    list.set("null space: vectors", modes.data());
    amg.initialize(matrix, list);
  }


  template std::vector<double>
  rigid_body_modes(const Discretization<2> &, std::vector<double> *);
  template std::vector<double>
  rigid_body_modes(const Discretization<3> &, std::vector<double> *);
  template void
  BulkAMG::initialize(const Matrix_t &, const Discretization<2> &, bool);
  template void
  BulkAMG::initialize(const Matrix_t &, const Discretization<3> &, bool);


  BulkSolver::BulkSolver(const Parameters::Solver &parameters)
    : parameters(parameters)
  {}


  BulkSolver::~BulkSolver() = default;


  template <int dim>
  void
  BulkSolver::initialize(const Matrix_t            &A,
                         const Discretization<dim> &discretization)
  {
    matrix = &A;
    direct.reset();
    amg.reset();
    problem.reset();
    if (parameters.linear_solver == Parameters::Solver::LinearSolver::direct)
      {
        problem = std::make_unique<Epetra_LinearProblem>();
        problem->SetOperator(
          const_cast<Epetra_CrsMatrix *>(&A.trilinos_matrix()));
        Amesos factory;
        direct.reset(
          factory.Create(parameters.direct_solver_package.c_str(), *problem));
        AssertThrow(direct != nullptr,
                    ExcMessage("Solver/Direct solver package: '" +
                               parameters.direct_solver_package +
                               "' is not available in this Trilinos."));
        AssertThrow(direct->SymbolicFactorization() == 0 &&
                      direct->NumericFactorization() == 0,
                    ExcMessage("The factorization of the bulk matrix failed."));
      }
    else
      {
        amg = std::make_unique<BulkAMG>();
        amg->initialize(A, discretization);
      }
  }


  template void
  BulkSolver::initialize(const Matrix_t &, const Discretization<2> &);
  template void
  BulkSolver::initialize(const Matrix_t &, const Discretization<3> &);


  void
  BulkSolver::solve(const Vector_t &b, Vector_t &x)
  {
    Assert(matrix != nullptr, ExcNotInitialized());
    if (direct)
      {
        problem->SetLHS(&x.trilinos_vector());
        problem->SetRHS(const_cast<Epetra_MultiVector *>(
          static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
        AssertThrow(direct->Solve() == 0,
                    ExcMessage("A solve with the bulk matrix failed."));
      }
    else
      {
        SolverControl      control(parameters.max_linear_iterations,
                              parameters.linear_tolerance * b.l2_norm());
        SolverCG<Vector_t> cg(control);
        x = 0;
        cg.solve(*matrix, x, b, *amg);
      }
  }


  void
  BulkSolver::solve_columns(
    const std::vector<SparseColumn>                         &columns,
    const std::vector<types::global_dof_index>              &rows,
    std::vector<std::vector<double>>                        &values,
    const std::function<void(unsigned int, const double *)> &store)
  {
    Assert(matrix != nullptr, ExcNotInitialized());
    values.assign(columns.size(), std::vector<double>(rows.size()));
    if (columns.empty())
      return;
    const Epetra_Map &map = matrix->trilinos_matrix().DomainMap();
    if (direct)
      {
        // Blocks of at most 64 right-hand sides bound the memory.
        constexpr unsigned int block = 64;
        for (unsigned int first = 0; first < columns.size(); first += block)
          {
            const unsigned int n =
              std::min<unsigned int>(block, columns.size() - first);
            Epetra_MultiVector B(map, n), X(map, n);
            for (unsigned int c = 0; c < n; ++c)
              for (const auto &[row, value] : columns[first + c])
                if (map.MyGID(static_cast<int>(row)))
                  B.ReplaceGlobalValue(static_cast<int>(row), c, value);
            problem->SetLHS(&X);
            problem->SetRHS(&B);
            AssertThrow(direct->Solve() == 0,
                        ExcMessage("A solve with the bulk matrix failed."));
            for (unsigned int c = 0; c < n; ++c)
              {
                for (unsigned int i = 0; i < rows.size(); ++i)
                  values[first + c][i] =
                    X[c][map.LID(static_cast<int>(rows[i]))];
                if (store)
                  store(first + c, X[c]);
              }
          }
      }
    else
      {
        Vector_t rhs, x;
        rhs.reinit(matrix->locally_owned_domain_indices(),
                   matrix->get_mpi_communicator());
        x.reinit(rhs);
        for (unsigned int c = 0; c < columns.size(); ++c)
          {
            rhs = 0;
            for (const auto &[row, value] : columns[c])
              if (rhs.locally_owned_elements().is_element(row))
                rhs(row) = value;
            rhs.compress(VectorOperation::insert);
            solve(rhs, x);
            for (unsigned int i = 0; i < rows.size(); ++i)
              values[c][i] = x[rows[i]];
            if (store)
              store(c, x.trilinos_vector()[0]);
          }
      }
  }
} // namespace DynamicContact
