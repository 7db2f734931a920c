// More processes than cells: the small paper scene on 2 coarse cells (one
// contact node) on 3 processes, so that one process owns no cell, no DoF
// and no node of Gamma_3. Every collective step must still be taken by every
// process (it hung in the condensed solver's whole-system phase, where a
// process without DoFs stored empty whole columns and took another branch
// than the others). Both contact solvers must complete the run with the
// answers of one process (computed here on rank 0 alone) to 1e-8.

#include "test_tools.h"

using namespace DynamicContact;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int               ranks =
    Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  for (const std::string solver : {"condensed", "assembled"})
    {
      const std::vector<std::string> overrides = {
        "Geometry/Repetitions=2, 1",
        "Time/End time=0.25",
        "Solver/Contact solver=" + solver,
        "Output/Directory=output-" + solver};
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
