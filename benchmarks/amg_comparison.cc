// Which algebraic multigrid preconditions the bulk matrix best?
//
// Builds K0 = (rho/k) M + k B (backward Euler, the paper's material, k =
// 1/128 s, clamped ends) on the paper's 2D domain (2 m x 0.1 m, nx x ny
// cells) or on the 3D rail (2 m x 0.1 m x 0.1 m, nx x n x n cells) and
// solves K0 x = b by CG to a relative residual of 1e-10 with each AMG that
// Debian's deal.II 9.4 offers: Trilinos ML (what dynamic-contact uses, with
// the translations only and with the rigid-body modes as near null space),
// PETSc GAMG (plain and with the rigid-body modes) and hypre BoomerAMG
// through PETSc (default and nodal/systems settings). MueLu is not in
// Debian's deal.II build. Prints setup time, CG iterations and solve time.
//
//   benchmarks/amg-comparison   (builds this as the target amg-comparison)

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <Teuchos_ParameterList.hpp>
#include <petscksp.h>

#include <iomanip>
#include <iostream>

using namespace dealii;

template <int dim>
void
compare(const std::vector<unsigned int> &repetitions, const Point<dim> &corner)
{
  const MPI_Comm     comm = MPI_COMM_WORLD;
  ConditionalOStream out(std::cout,
                         Utilities::MPI::this_mpi_process(comm) == 0);

  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_rectangle(
    tria, repetitions, Point<dim>(), corner, true);
  FESystem<dim>   fe(FE_Q<dim>(1), dim);
  DoFHandler<dim> dof_handler(tria);
  dof_handler.distribute_dofs(fe);
  const IndexSet owned = dof_handler.locally_owned_dofs();
  IndexSet       relevant;
  DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);

  AffineConstraints<double> constraints(relevant);
  for (const types::boundary_id id : {0, 1}) // the clamped ends
    VectorTools::interpolate_boundary_values(
      dof_handler, id, Functions::ZeroFunction<dim>(dim), constraints);
  constraints.close();

  // K0 = (rho/k) M + k B: E = 1e11, nu = 0.3, rho = 1000, k = 1/128.
  const double k = 1. / 128, rho = 1000, lambda = 5.76923e10, mu = 3.84615e10;
  TrilinosWrappers::SparsityPattern pattern(owned, comm);
  DoFTools::make_sparsity_pattern(dof_handler, pattern, constraints, false);
  pattern.compress();
  TrilinosWrappers::SparseMatrix K0;
  K0.reinit(pattern);
  {
    QGauss<dim>        quadrature(2);
    FEValues<dim>      fe_values(fe,
                            quadrature,
                            update_gradients | update_values |
                              update_JxW_values);
    FullMatrix<double> cell_matrix(fe.n_dofs_per_cell(), fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < cell_matrix.m(); ++i)
              for (unsigned int j = 0; j < cell_matrix.n(); ++j)
                {
                  const unsigned int ci = fe.system_to_component_index(i).first;
                  const unsigned int cj = fe.system_to_component_index(j).first;
                  const auto gi = fe_values.shape_grad(i, q);
                  const auto gj = fe_values.shape_grad(j, q);
                  const double stiffness =
                    lambda * gi[ci] * gj[cj] + mu * gi[cj] * gj[ci] +
                    (ci == cj ? mu * (gi * gj) : 0.);
                  const double mass =
                    (ci == cj ? fe_values.shape_value(i, q) *
                                  fe_values.shape_value(j, q) :
                                0.);
                  cell_matrix(i, j) +=
                    (k * stiffness + rho / k * mass) * fe_values.JxW(q);
                }
          cell->get_dof_indices(dofs);
          constraints.distribute_local_to_global(cell_matrix, dofs, K0);
        }
    K0.compress(VectorOperation::add);
  }
  out << dim << "D, " << dof_handler.n_dofs() << " DoFs, "
      << Utilities::MPI::n_mpi_processes(comm) << " process(es)" << std::endl;

  TrilinosWrappers::MPI::Vector b(owned, comm), x(owned, comm);
  for (const auto i : owned)
    b(i) = std::sin(1.0 * i);
  b.compress(VectorOperation::insert);
  constraints.set_zero(b);

  Timer timer;
  auto  report = [&](const std::string &name,
                    const double       setup,
                    const unsigned int iterations,
                    const double       solve) {
    out << "  " << std::left << std::setw(32) << name << std::right
        << " setup " << std::fixed << std::setprecision(3) << setup
        << " s, CG iterations " << std::setw(4) << iterations << ", solve "
        << solve << " s" << std::defaultfloat << std::endl;
  };
  auto cg = [&](const auto &preconditioner, const std::string &name,
                const double setup) {
    SolverControl control(3000, 1e-10 * b.l2_norm());
    SolverCG<TrilinosWrappers::MPI::Vector> solver(control);
    x = 0;
    timer.restart();
    solver.solve(K0, x, b, preconditioner);
    report(name, setup, control.last_step(), timer.wall_time());
  };

  // The rigid-body modes at the owned DoFs (translations, rotations).
  const unsigned int  n_modes = (dim == 2 ? 3 : 6), n = owned.n_elements();
  std::vector<double> modes(n_modes * n, 0.);
  // The node coordinate of each owned DoF's component (PETSc's rigid-body
  // modes want them node by node: Q1 numbers a node's DoFs consecutively).
  std::vector<double> node_coordinates(n);
  {
    const MappingQ1<dim> mapping; // FEValues keeps a pointer to it
    FEValues<dim>        fe_values(mapping,
                            fe,
                            Quadrature<dim>(fe.get_unit_support_points()),
                            update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (owned.is_element(dofs[i]))
              {
                const unsigned int r = owned.index_within_set(dofs[i]);
                const unsigned int c = fe.system_to_component_index(i).first;
                const Point<dim> & p = fe_values.quadrature_point(i);
                modes[c * n + r]     = 1;
                node_coordinates[r]  = p[c];
                if (dim == 2)
                  modes[2 * n + r] = (c == 0 ? -p[1] : p[0]);
                else
                  {
                    modes[3 * n + r] = (c == 1 ? -p[dim - 1] : c == 2 ? p[1] : 0);
                    modes[4 * n + r] = (c == 0 ? p[dim - 1] : c == 2 ? -p[0] : 0);
                    modes[5 * n + r] = (c == 0 ? -p[1] : c == 1 ? p[0] : 0);
                  }
              }
        }
  }

  // Trilinos ML, the settings of dynamic-contact (BulkAMG).
  TrilinosWrappers::PreconditionAMG::AdditionalData data;
  data.elliptic              = true;
  data.smoother_sweeps       = 2;
  data.aggregation_threshold = 0.02;
  {
    DoFTools::extract_constant_modes(dof_handler,
                                     ComponentMask(),
                                     data.constant_modes);
    TrilinosWrappers::PreconditionAMG amg;
    timer.restart();
    amg.initialize(K0, data);
    cg(amg, "ML, translations", timer.wall_time());
  }
  {
    data.constant_modes.clear();
    Teuchos::ParameterList              list;
    std::unique_ptr<Epetra_MultiVector> unused;
    data.set_parameters(list, unused, K0);
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", static_cast<int>(n_modes));
    list.set("null space: vectors", modes.data());
    TrilinosWrappers::PreconditionAMG amg;
    timer.restart();
    amg.initialize(K0, list);
    cg(amg, "ML, rigid-body modes (used)", timer.wall_time());
  }

  // PETSc: the same matrix, CG on the true residual.
  DynamicSparsityPattern dsp(relevant);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
  SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
  PETScWrappers::MPI::SparseMatrix P;
  P.reinit(owned, owned, dsp, comm);
  for (const auto i : owned)
    for (auto it = K0.begin(i); it != K0.end(i); ++it)
      P.set(i, it->column(), it->value());
  P.compress(VectorOperation::insert);
  PETScWrappers::MPI::Vector pb(owned, comm), px(owned, comm);
  for (const auto i : owned)
    pb(i) = b(i);
  pb.compress(VectorOperation::insert);
  MatSetBlockSize(P.petsc_matrix(), dim);
  Vec coordinates;
  VecCreateMPI(comm, n, PETSC_DETERMINE, &coordinates);
  VecSetBlockSize(coordinates, dim);
  {
    PetscScalar *a;
    VecGetArray(coordinates, &a);
    for (unsigned int r = 0; r < n; ++r)
      a[r] = node_coordinates[r];
    VecRestoreArray(coordinates, &a);
  }
  MatNullSpace rigid;
  MatNullSpaceCreateRigidBody(coordinates, &rigid);
  auto petsc = [&](const std::string &                                 name,
                   const std::string &                                 type,
                   const std::vector<std::pair<std::string, std::string>> &options,
                   const bool near_null_space) {
    PetscOptionsClear(nullptr);
    for (const auto &[key, value] : options)
      PetscOptionsSetValue(nullptr, key.c_str(), value.c_str());
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
    timer.restart();
    KSPSetUp(ksp);
    PCSetUp(pc);
    const double setup = timer.wall_time();
    px                 = 0;
    timer.restart();
    KSPSolve(ksp, pb, px);
    PetscInt iterations;
    KSPGetIterationNumber(ksp, &iterations);
    report(name, setup, iterations, timer.wall_time());
    KSPDestroy(&ksp);
  };
  const std::string threshold = (dim == 2 ? "0.25" : "0.5");
  petsc("PETSc GAMG", "gamg", {}, false);
  petsc("PETSc GAMG, rigid-body modes", "gamg", {}, true);
  petsc("hypre BoomerAMG", "hypre", {}, false);
  petsc("hypre BoomerAMG, nodal",
        "hypre",
        {{"-pc_hypre_boomeramg_nodal_coarsen", "6"},
         {"-pc_hypre_boomeramg_vec_interp_variant", "3"},
         {"-pc_hypre_boomeramg_strong_threshold", threshold}},
        false);
  MatNullSpaceDestroy(&rigid);
  VecDestroy(&coordinates);
}


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc != 4)
    {
      std::cerr << "usage: amg-comparison 2d NX NY | 3d NX N\n";
      return 2;
    }
  const std::string  which = argv[1];
  const unsigned int a = std::stoi(argv[2]), b = std::stoi(argv[3]);
  if (which == "2d")
    compare<2>({a, b}, Point<2>(2, 0.1));
  else
    compare<3>({a, b, b}, Point<3>(2, 0.1, 0.1));
}
