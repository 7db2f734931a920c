// Which sparse direct solver factorizes and solves with the bulk matrix
// fastest on one process?
//
// Builds K0 = (rho/k) M + k B with the program's own Discretization and
// BulkOperator (backward Euler, the paper's elastic constants, clamped
// ends) on the paper's 2D domain (2 m x 0.1 m, nx x ny cells of degree p)
// and times, for each direct solver Debian's deal.II/Trilinos/SuiteSparse
// offers: the factorization (symbolic + numeric), one solve with one
// right-hand side (the mean of 20), and one solve with a block of 64
// right-hand sides (what the compliance columns of the condensed contact
// solver are made of). Solvers: Trilinos Amesos MUMPS (what
// dynamic-contact used before) and KLU, SuiteSparse UMFPACK (the library
// behind deal.II's SparseDirectUMFPACK) and CHOLMOD (supernodal Cholesky;
// K0 is symmetric positive definite). The relative residual of each
// single solve is printed as a check.
//
//   build/direct-comparison nx ny degree time_step
//   (cmake --build build --target direct-comparison)

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/bulk/cholmod_views.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/parameters/parameters.h>

#include "benchmark_material.h"

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <suitesparse/umfpack.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>

using namespace dealii;
using namespace DynamicContact;

namespace
{
  struct Csr
  {
    SuiteSparse_long              n = 0;
    std::vector<SuiteSparse_long> start, column;
    std::vector<double>           value;
  };

  Csr
  to_csr(const Epetra_CrsMatrix &A)
  {
    Csr c;
    c.n = A.NumMyRows();
    c.start.push_back(0);
    std::vector<std::pair<SuiteSparse_long, double>> row;
    for (int r = 0; r < A.NumMyRows(); ++r)
      {
        sorted_row(A, r, std::numeric_limits<SuiteSparse_long>::max(), row);
        for (const auto &[j, v] : row)
          {
            c.column.push_back(j);
            c.value.push_back(v);
          }
        c.start.push_back(c.column.size());
      }
    return c;
  }

  constexpr unsigned int n_rhs = 64, repeats = 20;

  /**
   * The right-hand sides, one (b) and a block of n_rhs (B, column by
   * column), and their solutions x and X.
   */
  struct Vectors
  {
    explicit Vectors(const unsigned int n)
      : b(n)
      , x(n)
      , B(n * n_rhs)
      , X(n * n_rhs)
    {
      for (unsigned int i = 0; i < n; ++i)
        b[i] = std::sin(1.0 * i);
      for (unsigned int c = 0; c < n_rhs; ++c)
        for (unsigned int i = 0; i < n; ++i)
          B[c * n + i] = std::cos(0.37 * i + c);
    }

    std::vector<double> b, x, B, X;
  };

  /** max |A @p solution - b| / max |b|. */
  double
  relative_residual(const Epetra_CrsMatrix    &A,
                    const std::vector<double> &b,
                    const std::vector<double> &solution)
  {
    Epetra_Vector xv(View,
                     A.DomainMap(),
                     const_cast<double *>(solution.data()));
    Epetra_Vector y(A.RangeMap());
    A.Multiply(false, xv, y);
    double r = 0, s = 0;
    for (unsigned int i = 0; i < b.size(); ++i)
      {
        r = std::max(r, std::abs(y[i] - b[i]));
        s = std::max(s, std::abs(b[i]));
      }
    return r / s;
  }

  /** One row of the table. */
  void
  report(const std::string &name,
         const double       factor,
         const double       solve,
         const double       block,
         const double       check)
  {
    std::cout << "  " << std::left << std::setw(22) << name << std::right
              << std::fixed << std::setprecision(4) << " factorization "
              << factor << " s, one solve " << solve * 1e3 << " ms, 64 at once "
              << block * 1e3 << " ms (" << block * 1e3 / n_rhs
              << " ms each), residual " << std::scientific
              << std::setprecision(1) << check << std::defaultfloat
              << std::endl;
  }

  /** Trilinos Amesos with the solver @p package. */
  void
  run_amesos(const Epetra_CrsMatrix &A, const std::string &package, Vectors &v)
  {
    const unsigned int   n = A.NumMyRows();
    Epetra_LinearProblem problem;
    problem.SetOperator(const_cast<Epetra_CrsMatrix *>(&A));
    Amesos                             factory;
    std::unique_ptr<Amesos_BaseSolver> solver(
      factory.Create(package.c_str(), problem));
    Timer timer;
    solver->SymbolicFactorization();
    solver->NumericFactorization();
    const double  factor = timer.wall_time();
    Epetra_Vector bv(View, A.RangeMap(), v.b.data()),
      xv(View, A.DomainMap(), v.x.data());
    problem.SetLHS(&xv);
    problem.SetRHS(&bv);
    timer.restart();
    for (unsigned int r = 0; r < repeats; ++r)
      solver->Solve();
    const double       solve = timer.wall_time() / repeats;
    const double       check = relative_residual(A, v.b, v.x);
    Epetra_MultiVector Bv(View, A.RangeMap(), v.B.data(), n, n_rhs),
      Xv(View, A.DomainMap(), v.X.data(), n, n_rhs);
    problem.SetLHS(&Xv);
    problem.SetRHS(&Bv);
    timer.restart();
    solver->Solve();
    report(package, factor, solve, timer.wall_time(), check);
  }

  /**
   * UMFPACK: the CSR arrays are the CSC arrays of A^T; solve A^T' x = b.
   */
  void
  run_umfpack(const Epetra_CrsMatrix &A, const Csr &csr, Vectors &v)
  {
    const unsigned int n = A.NumMyRows();
    void              *symbolic, *numeric;
    double             control[UMFPACK_CONTROL], info[UMFPACK_INFO];
    umfpack_dl_defaults(control);
    Timer timer;
    umfpack_dl_symbolic(csr.n,
                        csr.n,
                        csr.start.data(),
                        csr.column.data(),
                        csr.value.data(),
                        &symbolic,
                        control,
                        info);
    umfpack_dl_numeric(csr.start.data(),
                       csr.column.data(),
                       csr.value.data(),
                       symbolic,
                       &numeric,
                       control,
                       info);
    const double factor = timer.wall_time();
    // The solution of A x = rhs into x.
    const auto solve_into = [&](double *x, const double *rhs) {
      umfpack_dl_solve(UMFPACK_At,
                       csr.start.data(),
                       csr.column.data(),
                       csr.value.data(),
                       x,
                       rhs,
                       numeric,
                       control,
                       info);
    };
    timer.restart();
    for (unsigned int r = 0; r < repeats; ++r)
      solve_into(v.x.data(), v.b.data());
    const double solve = timer.wall_time() / repeats;
    const double check = relative_residual(A, v.b, v.x);
    timer.restart();
    for (unsigned int c = 0; c < n_rhs; ++c)
      solve_into(v.X.data() + c * n, v.B.data() + c * n);
    report("UMFPACK", factor, solve, timer.wall_time(), check);
    umfpack_dl_free_symbolic(&symbolic);
    umfpack_dl_free_numeric(&numeric);
  }

  /**
   * CHOLMOD of the @p kind (supernodal or simplicial) with the @p ordering
   * (-1: its default choice).
   */
  void
  run_cholmod(const Epetra_CrsMatrix &A,
              const Csr              &csr,
              const int               kind,
              const int               ordering,
              Vectors                &v)
  {
    const unsigned int n = A.NumMyRows();
    cholmod_common     c;
    cholmod_l_start(&c);
    c.supernodal = kind;
    if (ordering >= 0)
      {
        c.nmethods           = 1;
        c.method[0].ordering = ordering;
      }
    cholmod_sparse  S = upper_triangle_view(csr.n,
                                           csr.start.data(),
                                           csr.column.data(),
                                           csr.value.data());
    Timer           timer;
    cholmod_factor *L = cholmod_l_analyze(&S, &c);
    cholmod_l_factorize(&S, L, &c);
    const double   factor = timer.wall_time();
    cholmod_dense  bd     = dense_view(n, 1, v.b.data());
    cholmod_dense *xd     = nullptr;
    timer.restart();
    for (unsigned int r = 0; r < repeats; ++r)
      {
        if (xd != nullptr)
          cholmod_l_free_dense(&xd, &c);
        xd = cholmod_l_solve(CHOLMOD_A, L, &bd, &c);
      }
    const double solve = timer.wall_time() / repeats;
    std::copy_n(static_cast<double *>(xd->x), n, v.x.begin());
    cholmod_l_free_dense(&xd, &c);
    const double  check = relative_residual(A, v.b, v.x);
    cholmod_dense Bd    = dense_view(n, n_rhs, v.B.data());
    timer.restart();
    cholmod_dense *Xd    = cholmod_l_solve(CHOLMOD_A, L, &Bd, &c);
    const double   block = timer.wall_time();
    cholmod_l_free_dense(&Xd, &c);
    report(std::string(kind == CHOLMOD_SUPERNODAL ? "CHOLMOD supernodal" :
                                                    "CHOLMOD simplicial") +
             (ordering == CHOLMOD_METIS ? ", METIS" : ""),
           factor,
           solve,
           block,
           check);
    std::cout << "    (" << c.lnz << " entries in L, ordering "
              << (c.method[c.selected].ordering == CHOLMOD_AMD   ? "AMD" :
                  c.method[c.selected].ordering == CHOLMOD_METIS ? "METIS" :
                                                                   "other")
              << ")" << std::endl;
    cholmod_l_free_factor(&L, &c);
    cholmod_l_finish(&c);
  }
} // namespace


template <int dim>
void
compare(const std::vector<unsigned int> &repetitions,
        const Point<dim>                &corner,
        const unsigned int               degree,
        const double                     k)
{
  const MPI_Comm comm = MPI_COMM_WORLD;

  Discretization<dim> discretization(comm, degree);
  GridGenerator::subdivided_hyper_rectangle(
    discretization.triangulation, repetitions, Point<dim>(), corner, true);
  Parameters::BoundaryConditions boundary_conditions;
  boundary_conditions.clamped = {0, 1};
  discretization.setup_dofs(boundary_conditions);

  const KelvinVoigtMaterial<dim> material(benchmark_material());
  BulkOperator<dim>              bulk(discretization, material);
  bulk.reinit(true);
  bulk.set_time_step(k);
  const TrilinosWrappers::SparseMatrix &K0 = bulk.newton_matrix();
  const Epetra_CrsMatrix               &A  = K0.trilinos_matrix();
  const unsigned int                    n  = A.NumMyRows();
  std::cout << dim << "D Q" << degree << " " << repetitions[0] << " x "
            << repetitions[1] << ", k = " << k << ": " << n << " DoFs, "
            << A.NumMyNonzeros() << " nonzeros" << std::endl;

  Vectors v(n);
  // Trilinos Amesos.
  for (const std::string package : {"Amesos_Mumps", "Amesos_Klu"})
    run_amesos(A, package, v);

  const Csr csr = to_csr(A);
  run_umfpack(A, csr, v);

  // CHOLMOD, supernodal and simplicial, with its default choice of the
  // ordering (AMD here) and with nested dissection (METIS).
  for (const auto &[kind, ordering] :
       std::vector<std::pair<int, int>>{{CHOLMOD_SUPERNODAL, -1},
                                        {CHOLMOD_SUPERNODAL, CHOLMOD_METIS},
                                        {CHOLMOD_SIMPLICIAL, -1}})
    run_cholmod(A, csr, kind, ordering, v);
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  AssertThrow(argc == 5,
              ExcMessage("usage: direct-comparison nx ny degree time_step"));
  const unsigned int nx = std::stoi(argv[1]), ny = std::stoi(argv[2]),
                     degree = std::stoi(argv[3]);
  const double k            = std::stod(argv[4]);
  compare<2>({nx, ny}, Point<2>(2, 0.1), degree, k);
}
