// benchmarks/scaling in its quick mode (two tiny meshes of the 3D rail and
// of the paper's domain, both contact solvers, 2 steps): the script runs,
// every run completes, and scaling_quick.csv has the documented columns and
// a row per run with sensible values; scaling_quick_sections.csv has each
// run's timer sections (those of its solver), and benchmarks/cost-model
// fits its terms to them. No timings are printed (they are in the CSV).

#include "program_tools.h"

using namespace program_tools;

namespace
{
  /** scaling_quick.csv: its columns, a row per run with sensible values. */
  void
  check_runs(Checks &checks)
  {
    const auto rows = test_tools::read_csv("scaling_quick.csv");
    checks.add(
      test_tools::has_columns(
        rows,
        "scene,dofs,contact_nodes,ranks,steps,solver,"
        "setup_time,wall_time_per_step,newton_per_step,passes_per_step,"
        "linear_iterations_per_newton,peak_memory_mb"),
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
  }


  /** The timer sections, and the cost model fitted to them. */
  void
  check_sections(Checks &checks)
  {
    const auto sections = test_tools::read_csv("scaling_quick_sections.csv");
    checks.add(test_tools::has_columns(
                 sections,
                 "scene,dofs,contact_nodes,ranks,steps,solver,section,"
                 "calls,time"),
               "scaling_quick_sections.csv has the documented columns");
    std::set<std::string> runs_with_their_section;
    for (std::size_t r = 1; r < sections.size(); ++r)
      {
        const auto &row = sections[r];
        if (row.size() == 9 && std::stod(row[8]) >= 0 &&
            row[6] == (row[5] == "condensed" ? "Bulk: factorization of K0" :
                                               "Newton: iterative solve"))
          runs_with_their_section.insert(row[0] + row[1] + row[5]);
      }
    checks.add(runs_with_their_section.size() == 8,
               "every run's timer sections, with its solver's own (the "
               "factorization of K0, the iterative solves)");
    Launch fit;
    fit.name    = "cost-model";
    fit.program = "python3";
    const Outcome model =
      execute({std::string(REPOSITORY_DIR) + "/benchmarks/cost-model",
               "--scaling",
               "scaling_quick.csv",
               "--text",
               "cost_model_quick.txt"},
              fit);
    checks.add(model.succeeded() &&
                 test_tools::read_text("cost_model_quick.txt")
                     .find("mispredicted choices: ") != std::string::npos,
               "benchmarks/cost-model fits these runs and compares its "
               "choices with theirs");
  }
} // namespace


int
main()
{
  const Outcome o = run_benchmark_script(
    "scaling",
    {"--quick", "--work-dir", "scaling-runs", "--csv", "scaling_quick.csv"},
    "scaling");
  Checks checks;
  checks.add(o.succeeded(), "benchmarks/scaling --quick succeeded");
  check_runs(checks);
  check_sections(checks);
  checks.assert_all();
}
