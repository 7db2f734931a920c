// The adaptive paper scene (prm/barboteu_danan_2016_adaptive_small.prm):
// at t = 0.2, 0.4, 0.6, 0.8 s the finest cells sit under the load (at
// x = c t, through the whole thickness), the cells 0.8 m behind it (beyond
// the load window and the families p4est keeps whole) have been coarsened
// back to the minimum level, and the number of cells stays below 70 % of
// that of the uniform mesh of the finest level.

#include "test_tools.h"

using namespace DynamicContact;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             simulator =
    test_tools::make<2>(test_tools::scene(
                          "barboteu_danan_2016_adaptive_small.prm"),
                        {"Output/Directory=output-following"});
  simulator->initialize();
  const unsigned int min_level = 1, max_level = 2;
  const double       c = 2., uniform_cells = 8 * 8 * 16;
  double             most_cells = 0;
  for (const double t_check : {0.2, 0.4, 0.6, 0.8})
    {
      while (simulator->time() < t_check - 1e-12 && simulator->advance())
        most_cells =
          std::max(most_cells,
                   static_cast<double>(simulator->time_series().back().cells));
      const double t               = simulator->time();
      const double x               = c * t;
      bool         fine_under_load = true;
      for (const double y : {0.001, 0.05, 0.099})
        fine_under_load =
          fine_under_load &&
          test_tools::level_at(simulator->simulator(), Point<2>(x, y)) ==
            static_cast<int>(max_level);
      test_tools::check(fine_under_load,
                        "t = " + test_tools::digits(t, 3) +
                          ": the finest level under the load");
      if (x - 0.8 > 0.1)
        test_tools::check(test_tools::level_at(simulator->simulator(),
                                               Point<2>(x - 0.8, 0.05)) ==
                            static_cast<int>(min_level),
                          "t = " + test_tools::digits(t, 3) +
                            ": coarse again 0.8 m behind the load");
    }
  test_tools::check(most_cells < 0.7 * uniform_cells,
                    "at most 70 % of the cells of the uniform finest mesh "
                    "(the load window spans about 40 % of the rail)");
}
