// benchmarks/scaling in its quick mode (two tiny meshes of the 3D rail and
// of the paper's domain, both contact solvers, 2 steps): the script runs,
// every run completes, and scaling_quick.csv has the documented columns and
// a row per run with sensible values. No timings are printed (they are in
// the CSV).

#include "program_tools.h"

using namespace program_tools;

int
main()
{
  Launch launch;
  launch.name        = "scaling";
  launch.program     = "python3";
  launch.environment = {std::string("DYNAMIC_CONTACT=") +
                        DYNAMIC_CONTACT_EXECUTABLE};
  const Outcome o = execute({std::string(SOURCE_DIR) + "/../benchmarks/scaling",
                             "--quick",
                             "--work-dir",
                             "scaling-runs",
                             "--csv",
                             "scaling_quick.csv"},
                            launch);
  Checks        checks;
  checks.add(o.succeeded(), "benchmarks/scaling --quick succeeded");
  const auto rows = test_tools::read_csv("scaling_quick.csv");
  checks.add(!rows.empty() &&
               rows.front() ==
                 std::vector<std::string>{"scene",
                                          "dofs",
                                          "contact_nodes",
                                          "ranks",
                                          "steps",
                                          "solver",
                                          "setup_time",
                                          "wall_time_per_step",
                                          "newton_per_step",
                                          "passes_per_step",
                                          "linear_iterations_per_newton",
                                          "peak_memory_mb"},
             "scaling_quick.csv has the documented columns");
  checks.add(rows.size() == 9, "8 runs: 2 scenes x 2 meshes x 2 solvers");
  bool sensible = rows.size() > 1;
  for (std::size_t r = 1; r < rows.size(); ++r)
    {
      const auto &row = rows[r];
      sensible =
        sensible && row.size() == 12 && std::stod(row[1]) > 0 &&
        std::stod(row[2]) > 0 && row[4] == "2" && std::stod(row[7]) > 0 &&
        std::stod(row[8]) >= 1 && std::stod(row[9]) >= 1 &&
        std::stod(row[11]) > 0 &&
        (row[5] == "condensed" ? row[10].empty() : std::stod(row[10]) >= 1);
    }
  checks.add(sensible,
             "every row: DoFs, contact nodes, 2 steps, time, Newton "
             "iterations, passes, memory, and Krylov iterations for the "
             "sparse solver");
  checks.assert_all();
}
