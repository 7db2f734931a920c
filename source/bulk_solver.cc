#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <dynamic_contact/bulk_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>

#include <algorithm>

namespace DynamicContact
{
  TrilinosWrappers::PreconditionAMG::AdditionalData
  bulk_amg_data(const std::vector<std::vector<bool>> &constant_modes,
                const bool                             higher_order_elements)
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = higher_order_elements;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    data.constant_modes        = constant_modes;
    return data;
  }


  using namespace dealii;

  BulkSolver::BulkSolver(const Parameters::Solver &parameters)
    : parameters(parameters)
  {}


  BulkSolver::~BulkSolver() = default;


  void
  BulkSolver::initialize(const Matrix_t &                        A,
                         const std::vector<std::vector<bool>> &constant_modes,
                         const bool higher_order_elements)
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
        amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        amg->initialize(A,
                        bulk_amg_data(constant_modes, higher_order_elements));
      }
  }


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
        SolverControl control(parameters.max_linear_iterations,
                              parameters.linear_tolerance * b.l2_norm());
        SolverCG<Vector_t> cg(control);
        x = 0;
        cg.solve(*matrix, x, b, *amg);
      }
  }


  void
  BulkSolver::solve_columns(const std::vector<SparseColumn> &           columns,
                            const std::vector<types::global_dof_index> &rows,
                            std::vector<std::vector<double>> &          values)
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
              for (unsigned int i = 0; i < rows.size(); ++i)
                values[first + c][i] = X[c][map.LID(static_cast<int>(rows[i]))];
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
          }
      }
  }
} // namespace DynamicContact
