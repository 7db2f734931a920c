// The geometric multigrid of K0 (Solver/Preconditioner = GMG).
//
// 1. As a preconditioner of CG on K0 = (rho/k) M + k B alone, on a box
//    clamped on the left and on rollers at the bottom, refined globally
//    one and two times and then once more on its left half (hanging nodes,
//    which every coarser level of the hierarchy has too), Q1 and Q2, 2D and
//    3D: the solution of K0 x = K0 x_exact is x_exact to 1e-8, within 30
//    iterations, and the finer mesh takes at most a third more iterations
//    plus two than the coarser (multigrid's iterations do not grow with
//    the mesh; the AMG's own count is not what is checked).
// 2. In the program: the assembled solver with GMRES and GMG agrees with
//    the condensed solver (direct) to 1e-8 on the paper's small scene (its
//    mesh as 4 x 1 cells refined three times; its first quarter second,
//    as of the next scene), on its adaptive variant
//    (hanging nodes, the hierarchy changes with the mesh) and on the
//    rail's small scene (10 x 1 x 1 cells refined once); the memory table
//    shows the GMG, not the AMG. The same with the matrix-free GMG, whose
//    memory table has no K0. Preconditioner = auto with Solver/Memory per
//    process = 0.001 (1 MB: nothing fits) takes the matrix-free GMG, its
//    solver plan says so, and it gives the matrix-free run's answers
//    exactly. The .mpirun=2 variant runs everything on two processes and
//    must print the same.
// 3. The finest level set up on the bulk forms' cell data (as the program
//    does) gives the V-cycle of its own cell data exactly.

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <dynamic_contact/bulk/bulk_multigrid.h>
#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/laws/material.h>

#include <set>

#include "test_tools.h"

using namespace DynamicContact;

namespace
{
  /** A BulkPreconditioner as deal.II's solvers take it. */
  struct Preconditioner
  {
    const BulkPreconditioner &p;
    void
    vmult(Vector_t &dst, const Vector_t &src) const
    {
      p.vmult(dst, src);
    }
  };


  /**
   * The box of 2 cells across, refined @p refinements times and then once
   * more on its left half; clamped on the left, rollers at the bottom.
   */
  template <int dim>
  void
  make_mesh(Discretization<dim> &d, const unsigned int refinements)
  {
    test_tools::make_box(d.triangulation, 2);
    d.triangulation.refine_global(refinements);
    test_tools::refine_left_half(d.triangulation);
    Parameters::BoundaryConditions bc;
    bc.clamped = {0};
    bc.roller  = {2};
    d.setup_dofs(bc);
  }


  /** The locally owned nodes whose dofs are owned and unconstrained. */
  template <int dim>
  std::vector<std::array<types::global_dof_index, dim>>
  free_nodes(const Discretization<dim> &d)
  {
    std::vector<std::array<types::global_dof_index, dim>> nodes;
    std::set<types::global_dof_index>                     seen;
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            std::array<types::global_dof_index, dim> node;
            bool                                     free = true;
            for (unsigned int c = 0; c < dim; ++c)
              {
                node[c] = cell->vertex_dof_index(v, c);
                free    = free && d.locally_owned.is_element(node[c]) &&
                       !d.constraints.is_constrained(node[c]);
              }
            if (free && seen.insert(node[0]).second)
              nodes.push_back(node);
          }
    return nodes;
  }


  /**
   * K0 not stored (@p cells): its product and its nodal blocks from the
   * cells against the stored K0 of @p bulk.
   */
  template <int dim>
  void
  check_cells_as_stored(const Discretization<dim> &d,
                        const BulkOperator<dim>   &bulk,
                        const BulkOperator<dim>   &cells,
                        const Vector_t            &exact,
                        const Vector_t            &b,
                        const std::string         &name)
  {
    Vector_t cells_b;
    d.reinit_owned(cells_b);
    cells.newton_vmult(cells_b, exact);
    cells_b -= b;
    test_tools::check(cells_b.linfty_norm() <= 1e-12 * b.linfty_norm(),
                      name + ": K0 x from the cells as stored, to 1e-12");
    const auto nodes         = free_nodes(d);
    const auto stored_blocks = bulk.newton_blocks(nodes);
    const auto cell_blocks   = cells.newton_blocks(nodes);
    double     worst = 0, scale = 0;
    for (unsigned int p = 0; p < nodes.size(); ++p)
      {
        worst = std::max(worst, (stored_blocks[p] - cell_blocks[p]).norm());
        scale = std::max(scale, stored_blocks[p].norm());
      }
    worst = Utilities::MPI::max(worst, d.comm);
    scale = Utilities::MPI::max(scale, d.comm);
    test_tools::check(Utilities::MPI::sum(nodes.size(), d.comm) > 0 &&
                        worst <= 1e-12 * scale,
                      name + ": K0's nodal blocks from the cells as stored, "
                             "to 1e-12 (hanging nodes resolved)");
  }


  /**
   * CG with the matrix-free GMG on K0 from the cells; and its finest level
   * on the bulk forms' cell data instead of its own: the same V-cycle, bit
   * for bit.
   */
  template <int dim>
  void
  check_matrix_free(const Discretization<dim>      &d,
                    const KelvinVoigtMaterial<dim> &m,
                    const TimeScheme               &scheme,
                    const BulkOperator<dim>        &cells,
                    const Vector_t                 &exact,
                    const Vector_t                 &b,
                    const std::string              &name)
  {
    const auto matrix_free = create_bulk_multigrid(d, m, scheme, nullptr);
    const Preconditioner          cell_preconditioner{*matrix_free};
    const BulkMatrixOperator<dim> cells_K0{cells};
    SolverControl                 cell_control(200, 1e-12 * b.l2_norm());
    SolverCG<Vector_t>            cell_cg(cell_control);
    Vector_t                      x;
    d.reinit_owned(x);
    cell_cg.solve(cells_K0, x, b, cell_preconditioner);
    d.constraints.set_zero(x);
    x -= exact;
    test_tools::check(x.linfty_norm() <= 1e-8 * exact.linfty_norm() &&
                        cell_control.last_step() <= 30,
                      name + ": CG with the matrix-free GMG, too");

    test_tools::check(cells.cell_data() != nullptr,
                      name + ": the cell-by-cell forms have cell data");
    const auto shared =
      create_bulk_multigrid(d, m, scheme, nullptr, cells.cell_data());
    Vector_t own_cycle, shared_cycle;
    d.reinit_owned(own_cycle);
    d.reinit_owned(shared_cycle);
    matrix_free->vmult(own_cycle, b);
    shared->vmult(shared_cycle, b);
    shared_cycle -= own_cycle;
    test_tools::check(own_cycle.linfty_norm() > 0 &&
                        shared_cycle.linfty_norm() == 0,
                      name + ": the finest level on the forms' cell data "
                             "gives the same V-cycle exactly");
  }


  /**
   * CG iterations of K0 x = K0 x_exact with the GMG; checks the answer, and
   * K0 from the cells against the stored one.
   */
  template <int dim>
  unsigned int
  solve(const unsigned int degree,
        const unsigned int refinements,
        const std::string &name)
  {
    Discretization<dim> d(MPI_COMM_WORLD, degree);
    make_mesh(d, refinements);

    const auto        m = test_tools::steel<dim>();
    BulkOperator<dim> bulk(d, m, false);
    bulk.reinit(/*stored=*/false);
    const TimeScheme scheme(1e-4);
    bulk.set_time_step(scheme);
    const Matrix_t &K0  = bulk.newton_matrix();
    const auto      gmg = create_bulk_multigrid(d, m, scheme, &K0);

    const Vector_t exact = test_tools::cosine_field(d);
    Vector_t       b, x;
    d.reinit_owned(b);
    d.reinit_owned(x);
    K0.vmult(b, exact);

    const Preconditioner preconditioner{*gmg};
    SolverControl        control(200, 1e-12 * b.l2_norm());
    SolverCG<Vector_t>   cg(control);
    cg.solve(K0, x, b, preconditioner);
    d.constraints.set_zero(x);
    x -= exact;
    test_tools::check(x.linfty_norm() <= 1e-8 * exact.linfty_norm(),
                      name + ": CG with GMG solves K0 x = b to 1e-8");
    test_tools::check(control.last_step() <= 30,
                      name + ": within 30 iterations");

    BulkOperator<dim> cells(d, m, false);
    cells.reinit(/*stored=*/false, /*store_newton_matrix=*/false);
    cells.set_time_step(scheme);
    check_cells_as_stored(d, bulk, cells, exact, b, name);
    check_matrix_free(d, m, scheme, cells, exact, b, name);
    return control.last_step();
  }


  template <int dim>
  void
  check_preconditioner(const unsigned int degree)
  {
    const std::string name =
      std::to_string(dim) + "D Q" + std::to_string(degree);
    const unsigned int coarse = solve<dim>(degree, 1, name + ", 1 refinement");
    const unsigned int fine   = solve<dim>(degree, 2, name + ", 2 refinements");
    test_tools::check(3 * fine <= 4 * coarse + 6,
                      name + ": the finer mesh takes at most 4/3 the "
                             "iterations + 2");
  }


  template <int dim>
  void
  check_scene(const std::string              &prm,
              const std::string              &name,
              const std::vector<std::string> &overrides)
  {
    auto with = [&](const std::vector<std::string> &more,
                    const std::string              &directory) {
      std::vector<std::string> all = overrides;
      all.insert(all.end(), more.begin(), more.end());
      all.push_back("Output/Directory=output-" + name + "-" + directory);
      return test_tools::run<dim>(test_tools::scene(prm), all);
    };
    const auto reference =
      with({"Solver/Contact solver=condensed", "Solver/Linear solver=direct"},
           "condensed");
    const auto                  &a = reference->time_series();
    std::vector<StepRecord<dim>> matrix_free_series;
    for (const std::string preconditioner : {"GMG", "matrix-free GMG"})
      {
        const bool        matrix_free = preconditioner != "GMG";
        const auto        gmg         = with({"Solver/Contact solver=assembled",
                                              "Solver/Linear solver=iterative",
                                              "Solver/Preconditioner=" + preconditioner},
                              matrix_free ? "matrix-free" : "gmg");
        const auto       &b           = gmg->time_series();
        const std::string what        = name + ", " + preconditioner;
        test_tools::check(a.size() == b.size(),
                          what + ": same number of steps");
        if (a.size() == b.size())
          test_tools::check(test_tools::largest_difference(a, b) < 1e-8,
                            what + ": GMRES with it agrees with "
                                   "condensed/direct to 1e-8");
        const std::string table = gmg->simulator().memory_table();
        test_tools::check(table.find("GMG of K0") != std::string::npos &&
                            table.find("AMG of K0") == std::string::npos,
                          what + ": the GMG served, not the AMG");
        test_tools::check((table.find("bulk matrix K0") == std::string::npos) ==
                            matrix_free,
                          what +
                            (matrix_free ? ": K0 not stored" : ": K0 stored"));
        if (matrix_free)
          matrix_free_series = b;
      }
    // Preconditioner = auto where not even the matrix-free GMG fits into
    // Solver/Memory per process: it, the same run.
    const auto chosen = with({"Solver/Contact solver=assembled",
                              "Solver/Linear solver=iterative",
                              "Solver/Preconditioner=auto",
                              "Solver/Memory per process=0.001"},
                             "auto");
    test_tools::check(
      chosen->simulator().solver().solver_plan().description().find(
        "preconditioner matrix-free GMG (peak predicted") !=
          std::string::npos &&
        chosen->simulator().memory_table().find("bulk matrix K0") ==
          std::string::npos &&
        test_tools::largest_difference(matrix_free_series,
                                       chosen->time_series()) == 0,
      name + ", Preconditioner = auto within 1 MB per process: the "
             "matrix-free GMG, the plan says why, the same answers");
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  test_tools::for_each_element({{2, 1}, {2, 2}, {3, 1}, {3, 2}},
                               [](const auto dim, const unsigned int degree) {
                                 check_preconditioner<decltype(dim)::value>(
                                   degree);
                               });

  // The scenes' first quarter second: the load comes in, contact and
  // friction start, the adaptive mesh changes.
  check_scene<2>("barboteu_danan_2016_small.prm",
                 "paper_small",
                 {"Geometry/Repetitions=4, 1",
                  "Geometry/Global refinements=3",
                  "Time/End time=0.25"});
  check_scene<2>("barboteu_danan_2016_adaptive_small.prm",
                 "paper_adaptive_small",
                 {"Time/End time=0.25"});
  check_scene<3>("rail_3d_small.prm",
                 "rail_small",
                 {"Geometry/Repetitions=10, 1, 1",
                  "Geometry/Global refinements=1"});
}
