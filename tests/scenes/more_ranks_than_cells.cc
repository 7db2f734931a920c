// More processes than cells: the small paper scene on 2 coarse cells (one
// contact node) on 3 processes, so that one process owns no cell, no DoF
// and no node of Gamma_3. Every collective step must still be taken by every
// process (it hung in the condensed solver's whole-system phase, where a
// process without DoFs stored empty whole columns and took another branch
// than the others). Both contact solvers must complete the run with the
// answers of one process (computed here on rank 0 alone) to 1e-8; so must
// the assembled solver with the matrix-free geometric multigrid on the 2
// cells (a mesh without levels: its coarsest level is the mesh, with a
// process that owns none of it), and with the geometric multigrid on the 2
// cells refined four times (the coarser meshes have fewer cells than
// processes, and p4est cannot coarsen a family split between processes:
// it crashed in making them).

#include "test_tools.h"

using namespace DynamicContact;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int               ranks =
    Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const std::vector<std::pair<std::string, std::vector<std::string>>> runs =
    {{"condensed", {"Solver/Contact solver=condensed"}},
     {"assembled", {"Solver/Contact solver=assembled"}},
     {"matrix-free GMG",
      {"Solver/Contact solver=assembled",
       "Solver/Linear solver=iterative",
       "Solver/Preconditioner=matrix-free GMG"}},
     {"GMG, refined 4 times",
      {"Solver/Contact solver=assembled",
       "Solver/Linear solver=iterative",
       "Solver/Preconditioner=GMG",
       "Geometry/Global refinements=4"}}};
  for (const auto &[solver, settings] : runs)
    {
      // Every process takes part (the scene's DoFs would call for one).
      std::vector<std::string> overrides = {
        "Geometry/Repetitions=2, 1",
        "Time/End time=0.25",
        "Solver/Minimum DoFs per process=0"};
      overrides.insert(overrides.end(), settings.begin(), settings.end());
      std::string directory = "output-" + solver;
      for (char &c : directory)
        if (c == ' ' || c == ',')
          c = '-';
      overrides.push_back("Output/Directory=" + directory);
      const auto parallel =
        test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                           overrides)
          ->time_series();
      if (rank != 0)
        continue;
      auto serial_overrides = overrides;
      serial_overrides.back() += "-serial";
      const auto serial =
        test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                           serial_overrides,
                           MPI_COMM_SELF)
          ->time_series();
      double worst = 0;
      for (unsigned int n = 1; n < std::min(serial.size(), parallel.size());
           ++n)
        for (const char *column :
             {"normal_force", "kinetic_energy", "elastic_energy"})
          {
            const auto   q = test_tools::quantity<2>(column);
            const double a = q.of(parallel[n]), b = q.of(serial[n]);
            worst          = std::max(worst,
                             std::abs(a - b) /
                               std::max(serial[n].terms.energy.total() +
                                          std::abs(serial[n].normal_force),
                                        1.));
          }
      test_tools::check(parallel.size() == 33 && serial.size() == 33,
                        solver + ": 32 steps on " + std::to_string(ranks) +
                          " processes (2 cells) and on one");
      test_tools::check(worst < 1e-8,
                        solver + ": the answers of one process to 1e-8");
    }
}
