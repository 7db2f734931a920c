// Which algebraic multigrid preconditions the bulk matrix best?
//
// Builds K0 = (rho/k) M + k B with the program's own Discretization and
// BulkOperator (backward Euler, the paper's elastic constants, k = 1/128 s,
// clamped ends) on the paper's 2D domain (2 m x 0.1 m, nx x ny
// cells) or on the 3D rail (2 m x 0.1 m x 0.1 m, nx x n x n cells) and
// solves K0 x = b by CG to a relative residual of 1e-10 with each AMG that
// Debian's deal.II 9.4 offers: Trilinos ML (what dynamic-contact uses, with
// the translations only and with the rigid-body modes as near null space),
// PETSc GAMG (plain and with the rigid-body modes) and hypre BoomerAMG
// through PETSc (default and nodal/systems settings). MueLu is not in
// Debian's deal.II build. Prints setup time, CG iterations, solve time and
// the heap memory the preconditioner holds (the Krylov solver's vectors
// included, which are the same for all).
//
//   benchmarks/amg-comparison   (builds this as the target amg-comparison)
//   build/amg-comparison 3d 320 32 ml-rbm,gamg-rbm   (only the ones named:
//     ml, ml-rbm, gamg, gamg-rbm, gamg-rbm-threshold, gamg-rbm-unsquared,
//     hypre, hypre-nodal)

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/parameters/parameters.h>

#include "benchmark_material.h"

#include <petscksp.h>

#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

using namespace dealii;
using namespace DynamicContact;

namespace
{
  /** Where the table goes, and which AMGs it has (all if none is named). */
  struct AmgTable
  {
    MPI_Comm                     comm;
    ConditionalOStream           out;
    const std::set<std::string> &only;

    bool
    wanted(const std::string &key) const
    {
      return only.empty() || only.count(key) > 0;
    }

    /**
     * One row: setup time, CG iterations, solve time, and the heap memory a
     * preconditioner holds after its set-up (glibc's count of the bytes in
     * use beyond @p heap_before, which a freed and reused block does not
     * blur as the resident size does), summed over the processes, in MB.
     */
    void
    row(const std::string &name,
        const double       setup,
        const double       heap_before,
        const unsigned int iterations,
        const double       solve) const
    {
      const double mb =
        Utilities::MPI::sum(heap_in_use() - heap_before, comm) / 1048576.;
      out << "  " << std::left << std::setw(34) << name << std::right
          << " setup " << std::fixed << std::setprecision(3) << setup
          << " s, CG iterations " << std::setw(4) << iterations << ", solve "
          << solve << " s, setup memory " << std::setprecision(0) << mb << " MB"
          << std::defaultfloat << std::endl;
    }
  };


  /** Trilinos ML with the settings of dynamic-contact (BulkAMG), in CG. */
  template <int dim>
  void
  run_ml(const AmgTable                       &table,
         const Discretization<dim>            &discretization,
         const TrilinosWrappers::SparseMatrix &K0,
         const TrilinosWrappers::MPI::Vector  &b,
         TrilinosWrappers::MPI::Vector        &x)
  {
    Timer timer;
    for (const bool rigid : {false, true})
      if (table.wanted(rigid ? "ml-rbm" : "ml"))
        {
          const double heap_before = heap_in_use();
          BulkAMG      amg;
          timer.restart();
          amg.initialize(K0, discretization, rigid);
          const double  setup = timer.wall_time();
          SolverControl control(3000, 1e-10 * b.l2_norm());
          SolverCG<TrilinosWrappers::MPI::Vector> solver(control);
          x = 0;
          timer.restart();
          solver.solve(K0, x, b, amg);
          table.row(rigid ? "ML, rigid-body modes (used)" : "ML, translations",
                    setup,
                    heap_before,
                    control.last_step(),
                    timer.wall_time());
        }
  }


  /**
   * @p P = @p K0 with K0's own pattern (with the constrained rows' diagonal
   * entries): PETSc preallocates it exactly. (Epetra's row views: deal.II's
   * row iterators cost O(rows) each.)
   */
  void
  copy_to_petsc(const TrilinosWrappers::SparseMatrix &K0,
                const IndexSet                       &owned,
                const IndexSet                       &relevant,
                const MPI_Comm                        comm,
                PETScWrappers::MPI::SparseMatrix     &P)
  {
    const Epetra_CrsMatrix &E            = K0.trilinos_matrix();
    const auto              for_each_row = [&](const auto &f) {
      for (int r = 0; r < E.NumMyRows(); ++r)
        {
          int     length;
          double *values;
          int    *local_columns;
          E.ExtractMyRowView(r, length, values, local_columns);
          std::vector<types::global_dof_index> columns(length);
          for (int j = 0; j < length; ++j)
            columns[j] = E.ColMap().GID(local_columns[j]);
          f(E.RowMap().GID(r),
            columns,
            std::vector<double>(values, values + length));
        }
    };
    DynamicSparsityPattern dsp(relevant);
    for_each_row([&](const types::global_dof_index               row,
                     const std::vector<types::global_dof_index> &columns,
                     const std::vector<double> &) {
      dsp.add_entries(row, columns.begin(), columns.end());
    });
    SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
    P.reinit(owned, owned, dsp, comm);
    for_each_row(
      [&](const types::global_dof_index               row,
          const std::vector<types::global_dof_index> &columns,
          const std::vector<double> &values) { P.set(row, columns, values); });
    P.compress(VectorOperation::insert);
  }


  /**
   * K0 x = b in PETSc's terms, with the rigid-body modes of the owned DoFs'
   * nodes as a near null space, and CG on the true residual with a PETSc
   * or hypre AMG.
   */
  template <int dim>
  struct PetscSystem
  {
    /**
     * K0 x = b0 on @p comm; the rigid-body modes from the coordinate of each
     * owned DoF's node in the DoF's direction.
     */
    PetscSystem(const MPI_Comm                        comm,
                const Discretization<dim>            &discretization,
                const TrilinosWrappers::SparseMatrix &K0,
                const TrilinosWrappers::MPI::Vector  &b0,
                const std::vector<double>            &node_coordinates)
      : comm(comm)
    {
      const IndexSet &owned = discretization.locally_owned;
      copy_to_petsc(K0, owned, discretization.locally_relevant, comm, P);
      b.reinit(owned, comm);
      x.reinit(owned, comm);
      for (const auto i : owned)
        b(i) = b0(i);
      b.compress(VectorOperation::insert);
      MatSetBlockSize(P.petsc_matrix(), dim);
      const unsigned int n = owned.n_elements();
      VecCreateMPI(comm, n, PETSC_DETERMINE, &coordinates);
      VecSetBlockSize(coordinates, dim);
      PetscScalar *a;
      VecGetArray(coordinates, &a);
      for (unsigned int r = 0; r < n; ++r)
        a[r] = node_coordinates[r];
      VecRestoreArray(coordinates, &a);
      MatNullSpaceCreateRigidBody(coordinates, &rigid);
    }

    PetscSystem(const PetscSystem &) = delete;
    PetscSystem &
    operator=(const PetscSystem &) = delete;

    ~PetscSystem()
    {
      MatNullSpaceDestroy(&rigid);
      VecDestroy(&coordinates);
    }

    /** A row of @p table: the preconditioner @p type with @p options. */
    void
    run(const AmgTable                                         &table,
        const std::string                                      &key,
        const std::string                                      &name,
        const std::string                                      &type,
        const std::vector<std::pair<std::string, std::string>> &options,
        const bool                                              near_null_space)
    {
      if (!table.wanted(key))
        return;
      PetscOptionsClear(nullptr);
      for (const auto &[option, value] : options)
        PetscOptionsSetValue(nullptr, option.c_str(), value.c_str());
      MatSetNearNullSpace(P.petsc_matrix(), near_null_space ? rigid : nullptr);
      KSP ksp;
      KSPCreate(comm, &ksp);
      KSPSetOperators(ksp, P.petsc_matrix(), P.petsc_matrix());
      KSPSetType(ksp, KSPCG);
      KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED);
      PC pc;
      KSPGetPC(ksp, &pc);
      PCSetType(pc, type.c_str());
      if (type == "hypre")
        PCHYPRESetType(pc, "boomeramg");
      KSPSetTolerances(ksp, 1e-10, 1e-300, 1e10, 3000);
      KSPSetFromOptions(ksp);
      PCSetFromOptions(pc);
      const double heap_before = heap_in_use();
      Timer        timer;
      KSPSetUp(ksp);
      PCSetUp(pc);
      const double setup = timer.wall_time();
      x                  = 0;
      timer.restart();
      KSPSolve(ksp, b, x);
      PetscInt iterations;
      KSPGetIterationNumber(ksp, &iterations);
      table.row(name, setup, heap_before, iterations, timer.wall_time());
      KSPDestroy(&ksp);
    }

    MPI_Comm                         comm;
    PETScWrappers::MPI::SparseMatrix P;
    PETScWrappers::MPI::Vector       b, x;
    Vec                              coordinates;
    MatNullSpace                     rigid;
  };


  /** PETSc GAMG and hypre BoomerAMG, plain and with the rigid-body modes. */
  template <int dim>
  void
  run_petsc(const AmgTable &table, PetscSystem<dim> &petsc)
  {
    const std::string threshold = (dim == 2 ? "0.25" : "0.5");
    petsc.run(table, "gamg", "PETSc GAMG", "gamg", {}, false);
    petsc.run(
      table, "gamg-rbm", "PETSc GAMG, rigid-body modes", "gamg", {}, true);
    // Weak couplings dropped from the aggregation graph.
    petsc.run(table,
              "gamg-rbm-threshold",
              "PETSc GAMG, rigid-body modes, threshold 0.01",
              "gamg",
              {{"-pc_gamg_threshold", "0.01"}},
              true);
    // No squared graph on the first level: smaller aggregates, more levels.
    petsc.run(table,
              "gamg-rbm-unsquared",
              "PETSc GAMG, rigid-body modes, graph not squared",
              "gamg",
              {{"-pc_gamg_square_graph", "0"}, {"-pc_gamg_threshold", "0.01"}},
              true);
    petsc.run(table, "hypre", "hypre BoomerAMG", "hypre", {}, false);
    petsc.run(table,
              "hypre-nodal",
              "hypre BoomerAMG, nodal",
              "hypre",
              {{"-pc_hypre_boomeramg_nodal_coarsen", "6"},
               {"-pc_hypre_boomeramg_vec_interp_variant", "3"},
               {"-pc_hypre_boomeramg_strong_threshold", threshold}},
              false);
  }
} // namespace


template <int dim>
void
compare(const std::vector<unsigned int> &repetitions,
        const Point<dim>                &corner,
        const std::set<std::string>     &only)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const AmgTable table{
    comm,
    ConditionalOStream(std::cout, Utilities::MPI::this_mpi_process(comm) == 0),
    only};

  // The program's own discretization and bulk operator: Q1, the ends
  // (boundary ids 0 and 1) clamped.
  Discretization<dim> discretization(comm, 1);
  GridGenerator::subdivided_hyper_rectangle(
    discretization.triangulation, repetitions, Point<dim>(), corner, true);
  Parameters::BoundaryConditions boundary_conditions;
  boundary_conditions.clamped = {0, 1};
  discretization.setup_dofs(boundary_conditions);
  const DoFHandler<dim>           &dof_handler = discretization.dof_handler;
  const IndexSet                  &owned       = discretization.locally_owned;
  const AffineConstraints<double> &constraints = discretization.constraints;

  // K0 = (rho/k) M + k B: E = 1e11, nu = 0.3, rho = 1000, no viscosity,
  // k = 1/128 s (backward Euler).
  const KelvinVoigtMaterial<dim> material(benchmark_material());
  BulkOperator<dim>              bulk(discretization, material);
  bulk.reinit(true);
  bulk.set_time_step(1. / 128);
  const TrilinosWrappers::SparseMatrix &K0 = bulk.newton_matrix();
  table.out << dim << "D, " << dof_handler.n_dofs() << " DoFs, "
            << Utilities::MPI::n_mpi_processes(comm) << " process(es)"
            << std::endl;

  TrilinosWrappers::MPI::Vector b(owned, comm), x(owned, comm);
  for (const auto i : owned)
    b(i) = std::sin(1.0 * i);
  b.compress(VectorOperation::insert);
  constraints.set_zero(b);

  // The coordinate of each owned DoF's node in the DoF's direction, for
  // PETSc's rigid-body modes.
  std::vector<double> node_coordinates;
  rigid_body_modes(discretization, &node_coordinates);

  run_ml(table, discretization, K0, b, x);
  if (!only.empty() && only.count("ml") + only.count("ml-rbm") == only.size())
    return;

  // PETSc: the same matrix, CG on the true residual.
  PetscSystem<dim> petsc(comm, discretization, K0, b, node_coordinates);
  run_petsc(table, petsc);
}


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc != 4 && argc != 5)
    {
      std::cerr << "usage: amg-comparison 2d NX NY | 3d NX N [NAME,NAME...]\n";
      return 2;
    }
  const std::string     which = argv[1];
  const unsigned int    a = std::stoi(argv[2]), b = std::stoi(argv[3]);
  std::set<std::string> only;
  if (argc == 5)
    {
      std::istringstream names(argv[4]);
      for (std::string name; std::getline(names, name, ',');)
        only.insert(name);
    }
  if (which == "2d")
    compare<2>({a, b}, Point<2>(2, 0.1), only);
  else
    compare<3>({a, b, b}, Point<3>(2, 0.1, 0.1), only);
}
