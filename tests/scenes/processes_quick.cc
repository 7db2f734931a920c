// benchmarks/processes in its quick mode (the small paper scene and the
// small rail for 8 steps, on 1 and 2 processes, once): the script runs,
// processes_quick.csv has the machine line, the documented columns and a
// row per scene and process count, with the solver of each run's plan;
// both scenes are far
// below Solver/Minimum DoFs per process, so on 2 processes one takes part
// and the answers are those of one process, digit for digit. No timings
// are printed (they are in the CSV).

#include "program_tools.h"

using namespace program_tools;
using test_tools::out;

int
main()
{
  const Outcome o =
    run_benchmark_script("processes",
                         {"--quick", "--csv", "processes_quick.csv"},
                         "processes");
  Checks checks;
  checks.add(o.succeeded(), "benchmarks/processes --quick succeeded");
  // The rows after the machine line.
  auto rows = test_tools::read_csv("processes_quick.csv");
  if (!rows.empty() && !rows[0].empty() && rows[0][0].rfind("#", 0) == 0)
    rows.erase(rows.begin());
  checks.add(test_tools::has_columns(
               rows,
               "scene,ranks,runs,steps,dofs,solver,newton_per_step,"
               "passes_per_step,wall_time_median,wall_time_min,"
               "wall_time_max,ratio_to_fewest,answer_difference"),
             "processes_quick.csv has the documented columns");
  checks.add(rows.size() == 5, "4 rows: 2 scenes x 1 and 2 processes");
  bool sensible = rows.size() == 5;
  for (std::size_t r = 1; sensible && r < rows.size(); ++r)
    {
      const auto &row = rows[r];
      sensible = row.size() == 13 && row[0] == (r <= 2 ? "paper" : "rail") &&
                 row[1] == (r % 2 == 1 ? "1" : "2") && row[5] == "condensed" &&
                 std::stod(row[3]) > 0 && std::stod(row[4]) > 0 &&
                 std::stod(row[8]) > 0 && std::stod(row[11]) > 0 &&
                 row[12] == "0.0e+00";
      out() << row[0] << ", " << row[1] << " process(es): " << row[3]
            << " steps, " << row[4] << " DoFs, " << row[5]
            << ", answers within " << row[12] << std::endl;
    }
  checks.add(sensible,
             "every row: its scene and processes, steps, DoFs, the condensed "
             "solver, a time, and on 2 processes the answers of one");
  checks.assert_all();
}
