// Checkpoint and restart of the real executable, killed the hard way.
//
// Two scenes run 48 steps with a checkpoint every 10 steps: the small paper
// scene (uniform 32 x 8 mesh, friction) and the adaptive one (friction,
// load-following refinement and coarsening every 8 steps). The program is
// killed with SIGKILL (the fault-injection hook DYNAMIC_CONTACT_KILL) and
// continued with --resume:
//   after_step      uniform: killed after step 25 (checkpoints 10 and 20
//                   complete, rows 21..25 written beyond the newest), resumed;
//   in_checkpoint   uniform: killed while writing the checkpoint of step 30
//                   (its temporary directory left behind), resumed;
//   adaptive        adaptive: killed after step 25, resumed;
//   two_processes   adaptive: run, killed and resumed on 2 processes;
//   one_to_two      adaptive: killed on 1 process, resumed on 2;
//   bathe           uniform with Time/Scheme = bathe (two sub-steps a step):
//                   killed after step 25, resumed;
//   slip_length     adaptive with Friction/Slip length (a coefficient state
//                   per node, which the checkpoint carries): killed after
//                   step 25 on 1 process, resumed on 2.
// Every interrupted-and-resumed run must end "completed" with the results of
// the uninterrupted run: time_series.csv with each step once, every
// contact_NNNNN.csv, solution.pvd and the VTU files.
//   On the uniform mesh they agree to the last printed digit, except the
// column `factorizations` (the resumed run factorizes its matrix anew: an
// honest count of work): the checkpoint holds the whole state.
//   On the adaptive mesh a loaded mesh stores its cells in another order
// than the same mesh reached by refining and coarsening, so the sums over
// cells round differently and the Newton iterations stop at other iterates
// within their tolerance; on 2 processes the direct solver is not bitwise
// reproducible either. There the physical columns must agree to 1e-8 of
// their largest value, and the work counters are not compared.
// Two misuses give one clear error and leave the results alone: --resume
// where no checkpoint was written, and --resume with another mesh.

#include "run_checks.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;
  using namespace run_checks;

  /** Steps run and the checkpoint interval (see the header). */
  const std::vector<std::string> settings =
    with(overrides({"Time/End time=0.375",
                    "Checkpoint/Every=10",
                    "Checkpoint/Keep=2",
                    "Output/Write VTU=true",
                    "Output/VTU every=8"}),
         quiet);
  const unsigned int n_steps = 48;

  /**
   * Run the uniform or the adaptive scene into @p directory, as it is
   * (@p variant "") or with the Bathe scheme ("bathe") or a slip length
   * ("slip_length").
   */
  std::vector<std::string>
  arguments(const bool         adaptive,
            const std::string &directory,
            const bool         resume  = false,
            const std::string &variant = "")
  {
    std::vector<std::string> a = {
      test_tools::scene(adaptive ? "barboteu_danan_2016_adaptive_small.prm" :
                                   "barboteu_danan_2016_small.prm")};
    if (resume)
      a.insert(a.begin(), "--resume");
    a.insert(a.end(), settings.begin(), settings.end());
    a.push_back("--set");
    a.push_back("Output/Directory=" + directory);
    return with(a,
                overrides(variant == "bathe" ?
                            std::vector<std::string>{"Time/Scheme=bathe"} :
                          variant == "slip_length" ?
                            std::vector<std::string>{
                              "Friction/Slip length=0.01",
                              "Friction/Reference slip rate=0.001"} :
                            std::vector<std::string>{}));
  }

  Outcome
  run(const std::string              &name,
      const std::vector<std::string> &args,
      const unsigned int              processes,
      const std::string              &kill = "")
  {
    return execute(args,
                   launch_of(name,
                             processes,
                             0,
                             kill.empty() ? std::vector<std::string>{} :
                                            std::vector<std::string>{
                                              "DYNAMIC_CONTACT_KILL=" + kill}));
  }

  /** The names of the complete checkpoints and of the temporary ones. */
  std::string
  checkpoints_in(const std::string &directory)
  {
    std::set<std::string> names;
    for (const auto &e : fs::directory_iterator(directory))
      if (e.path().filename().string().rfind("checkpoint_", 0) == 0)
        names.insert(e.path().filename().string());
    std::string list;
    for (const auto &n : names)
      list += (list.empty() ? "" : " ") + n;
    return list.empty() ? "none" : list;
  }

  /**
   * The result files of a run (no checkpoints), sorted; not the program's
   * bookkeeping (.dynamic-contact, the manifest of what it wrote, and the
   * lock .dynamic-contact.lock: they name the process and its history),
   * nor its provenance (log.txt, parameters.prm and parameters.json name
   * the start time, the output directory and the resume; tests/provenance
   * checks them).
   */
  std::vector<std::string>
  result_files(const std::string &directory)
  {
    std::vector<std::string> names;
    for (const auto &e : fs::directory_iterator(directory))
      {
        const std::string n = e.path().filename().string();
        if (e.is_regular_file() && n != "run_status" && n[0] != '.' &&
            n != "log.txt" && n != "parameters.prm" && n != "parameters.json")
          names.push_back(n);
      }
    std::sort(names.begin(), names.end());
    return names;
  }

  /** The steps of time_series.csv, in order. */
  std::vector<unsigned int>
  steps_of(const std::string &directory)
  {
    std::vector<unsigned int> steps;
    const auto rows = read_csv(fs::path(directory) / "time_series.csv");
    for (unsigned int r = 1; r < rows.size(); ++r)
      steps.push_back(std::stoul(rows[r][0]));
    return steps;
  }

  /** Each step 0..n_steps once, in order. */
  bool
  each_step_once(const std::vector<unsigned int> &steps)
  {
    if (steps.size() != n_steps + 1)
      return false;
    for (unsigned int i = 0; i < steps.size(); ++i)
      if (steps[i] != i)
        return false;
    return true;
  }

  bool
  ends_with(const std::string &s, const std::string &end)
  {
    return s.size() >= end.size() &&
           s.compare(s.size() - end.size(), end.size(), end) == 0;
  }

  /** A file without the line that dates it ("generated ... on DATE"). */
  std::string
  without_date(const fs::path &file)
  {
    std::string text;
    for (const auto &line : lines_of(read_text(file)))
      if (line.find("generated by the deal.II library on") == std::string::npos)
        text += line + '\n';
    return text;
  }

  /**
   * The differences of a resumed run from the uninterrupted one: the columns
   * of time_series.csv, and the other result files (by name) that differ.
   */
  struct Comparison
  {
    std::set<std::string> time_series;
    std::set<std::string> files;
  };

  Comparison
  compare(const std::string &full, const std::string &resumed, const bool exact)
  {
    // Unless exact: the work counters may differ (see the header), and the
    // round-off-sized columns are checked against a bound instead.
    const std::set<std::string> not_physical = {"newton_iterations",
                                                "convexification_iterations",
                                                "factorizations",
                                                "active_set_cycles",
                                                "line_search_steps",
                                                "coefficient_residual",
                                                "energy_balance_defect",
                                                "relative_energy_defect",
                                                "relative_min_dissipation"};
    const double                tolerance    = exact ? 0 : 1e-8;
    Comparison                  result;
    result.time_series =
      differing_csv_columns(fs::path(full) / "time_series.csv",
                            fs::path(resumed) / "time_series.csv",
                            tolerance,
                            exact ? std::set<std::string>{} : not_physical);
    // Unless exact, the VTU files (on 2 processes even their pieces
    // NAME.0.vtu, NAME.1.vtu, ...) are not compared: the fields are, in the
    // contact files and the time series.
    auto compared = [exact](const std::vector<std::string> &all) {
      std::vector<std::string> names;
      for (const auto &n : all)
        if (exact || !ends_with(n, "vtu")) // .vtu, .pvtu
          names.push_back(n);
      return names;
    };
    const auto names = compared(result_files(full));
    if (names != compared(result_files(resumed)))
      result.files.insert("(the list of files)");
    for (const auto &n : names)
      {
        const fs::path a = fs::path(full) / n, b = fs::path(resumed) / n;
        if (n == "time_series.csv" || !fs::exists(b))
          continue;
        if (ends_with(n, ".csv") ?
              !differing_csv_columns(a, b, tolerance).empty() :
              without_date(a) != without_date(b))
          result.files.insert(n);
      }
    return result;
  }

  /** The largest |relative_energy_defect| of a run. */
  double
  max_relative_defect(const std::string &directory)
  {
    const auto rows = read_csv(fs::path(directory) / "time_series.csv");
    const auto c    = column(rows[0], "relative_energy_defect");
    double     max  = 0;
    for (unsigned int r = 1; r < rows.size(); ++r)
      max = std::max(max, std::abs(std::stod(rows[r][c])));
    return max;
  }

  /** An uninterrupted run, the reference of the cases of its scene. */
  struct Full
  {
    std::string name;
    bool        adaptive;
    std::string variant;
    Outcome     o = {};
  };

  /** A run killed, then resumed. */
  struct Case
  {
    std::string  directory;
    bool         adaptive;
    std::string  kill;
    unsigned int processes_first, processes_resumed;
    // What the kill leaves: the checkpoints and the last row.
    std::string  checkpoints_left;
    unsigned int last_row;
    Outcome      killed;
    std::string  variant = "";
  };

  std::vector<Case>
  cases()
  {
    const std::string two = "checkpoint_00010 checkpoint_00020";
    return {
      {"after_step", false, "after-step 25", 0, 0, two, 25, {}},
      {"in_checkpoint",
       false,
       "in-checkpoint 30",
       0,
       0,
       two + " checkpoint_00030.tmp",
       30,
       {}},
      {"adaptive", true, "after-step 25", 0, 0, two, 25, {}},
      {"two_processes", true, "after-step 25", 2, 2, two, 25, {}},
      {"one_to_two", true, "after-step 25", 0, 2, two, 25, {}},
      {"bathe", false, "after-step 25", 0, 0, two, 25, {}, "bathe"},
      {"slip_length", true, "after-step 25", 0, 2, two, 25, {}, "slip_length"}};
  }

  /**
   * The uninterrupted runs and the first (killed) part of each case; runs
   * on one process side by side (most of a short run is start-up).
   */
  void
  run_first_parts(std::vector<Full> &fulls, std::vector<Case> &cases)
  {
    std::vector<std::thread> threads;
    for (auto &f : fulls)
      threads.emplace_back([&f]() {
        f.o = run(f.name, arguments(f.adaptive, f.name, false, f.variant), 0);
      });
    for (auto &c : cases)
      if (c.processes_first == 0)
        threads.emplace_back([&c]() {
          c.killed = run(c.directory + ".1",
                         arguments(c.adaptive, c.directory, false, c.variant),
                         0,
                         c.kill);
        });
    for (auto &t : threads)
      t.join();
    for (auto &c : cases)
      if (c.processes_first > 0)
        c.killed = run(c.directory + ".1",
                       arguments(c.adaptive, c.directory, false, c.variant),
                       c.processes_first,
                       c.kill);
  }

  void
  check_uninterrupted(const Full &f, Checks &checks)
  {
    test_tools::out() << f.name << " (uninterrupted): exit code " << f.o.code
                      << ", " << run_status(f.name) << ", "
                      << steps_of(f.name).size() - 1 << " steps" << std::endl;
    checks.add(f.o.succeeded() && run_status(f.name) == "completed" &&
                 each_step_once(steps_of(f.name)),
               f.name + ": the uninterrupted run completes all " +
                 std::to_string(n_steps) + " steps");
  }

  /** What the kill left behind. */
  void
  check_killed(const Case &c, Checks &checks)
  {
    const bool ended_by_kill =
      c.killed.signal == 9 || (c.killed.exited && c.killed.code != 0);
    const auto steps = steps_of(c.directory);
    test_tools::out() << c.directory << ", killed (" << c.kill << ") on "
                      << processes_text(c.processes_first)
                      << ": ended abnormally: " << yes_no(ended_by_kill)
                      << ", run_status: " << run_status(c.directory)
                      << ", last row: step "
                      << (steps.empty() ? 0 : steps.back())
                      << ", checkpoints: " << checkpoints_in(c.directory)
                      << std::endl;
    checks.add(ended_by_kill && run_status(c.directory) == "running",
               c.directory + ": the killed run ended abnormally and its "
                             "status is not 'completed'");
    checks.add(!steps.empty() && steps.back() == c.last_row,
               c.directory + ": the killed run wrote rows up to step " +
                 std::to_string(c.last_row));
    checks.add(checkpoints_in(c.directory) == c.checkpoints_left,
               c.directory + ": checkpoints left: " + c.checkpoints_left);
  }

  void
  check_resumed(const Case &c, Checks &checks)
  {
    const Outcome     o       = run(c.directory + ".2",
                          arguments(c.adaptive, c.directory, true, c.variant),
                          c.processes_resumed);
    const bool        said_so = o.out.find("resumed from " + c.directory +
                                    "/checkpoint_00020") != std::string::npos;
    const bool        exact   = !c.adaptive;
    const std::string full    = !c.variant.empty() ? "full_" + c.variant :
                                c.adaptive         ? "full_adaptive" :
                                                     "full_uniform";
    const auto        steps   = steps_of(c.directory);
    const auto        diff    = compare(full, c.directory, exact);
    const double      defect  = max_relative_defect(c.directory);
    test_tools::out()
      << c.directory << ", resumed on " << processes_text(c.processes_resumed)
      << ": exit code " << o.code << ", " << run_status(c.directory)
      << ", from checkpoint_00020: " << yes_no(said_so)
      << ", each step once: " << yes_no(each_step_once(steps))
      << ", checkpoints: " << checkpoints_in(c.directory) << std::endl
      << "  vs the uninterrupted run"
      << (exact ? " (as printed)" : " (to 1e-8, physical columns)")
      << ": time series columns differing: " << join(diff.time_series)
      << "; other files differing: " << join(diff.files) << std::endl
      << "  max relative energy defect below 1e-10: " << yes_no(defect < 1e-10)
      << std::endl;

    checks.add(o.succeeded() && o.err.empty() &&
                 run_status(c.directory) == "completed",
               c.directory + ": the resumed run completes, nothing on stderr");
    checks.add(said_so,
               c.directory + ": resumed from the newest complete "
                             "checkpoint (step 20)");
    checks.add(each_step_once(steps),
               c.directory + ": time_series.csv holds each step once");
    checks.add(checkpoints_in(c.directory) ==
                 "checkpoint_00030 checkpoint_00040",
               c.directory + ": the newest two checkpoints are kept, no "
                             "temporary one is left");
    if (exact)
      checks.add(diff.time_series == std::set<std::string>{"factorizations"} &&
                   diff.files.empty(),
                 c.directory + ": the results are those of the "
                               "uninterrupted run, except the "
                               "factorization count");
    else
      checks.add(diff.time_series.empty() && diff.files.empty(),
                 c.directory + ": the results agree with the uninterrupted "
                               "run to 1e-8");
    checks.add(defect < 1e-10,
               c.directory + ": the energy balance holds across the restart");
  }

  /**
   * A misuse @p what of --resume: exit code 1 and a stderr of one error line
   * naming each of @p words (@p naming in words), the results @p untouched.
   */
  void
  check_misuse(const std::string              &what,
               const Outcome                  &o,
               const std::string              &naming,
               const std::vector<std::string> &words,
               const bool                      untouched,
               Checks                         &checks)
  {
    const bool names =
      lines_of(o.err).size() == 1 && one_line_naming(error_lines(o), words);
    test_tools::out() << what << ": exit code " << o.code
                      << ", one error line naming " << naming << ": "
                      << yes_no(names)
                      << ", results untouched: " << yes_no(untouched)
                      << std::endl;
    checks.add(o.exited && o.code == 1 && names,
               what + ": exit code 1 and one error line that names " + naming);
    checks.add(untouched, what + " leaves the results alone");
  }

  /**
   * Misuse 1: --resume where the run wrote no checkpoint. The results must
   * stay as they are.
   */
  void
  check_resume_without_checkpoint(Checks &checks)
  {
    std::vector<std::string> args =
      with(arguments(false, "never_checkpointed"),
           overrides({"Checkpoint/Every=0", "Time/End time=0.03125"}));
    const Outcome first = run("never_checkpointed.1", args, 0);
    args.insert(args.begin(), "--resume");
    const Outcome second = run("never_checkpointed.2", args, 0);
    checks.add(first.succeeded(), "the run without checkpoints completes");
    check_misuse("--resume without a checkpoint",
                 second,
                 "Output/Directory and Checkpoint/Every",
                 {"Output/Directory", "Checkpoint/Every"},
                 run_status("never_checkpointed") == "completed" &&
                   steps_of("never_checkpointed").size() == 5,
                 checks);
  }

  /** Misuse 2: --resume with another mesh than the checkpoint's. */
  void
  check_resume_other_mesh(Checks &checks)
  {
    const std::string before = read_text("full_uniform/time_series.csv");
    const Outcome     o      = run("other_mesh",
                          with(arguments(false, "full_uniform", true),
                               overrides({"Geometry/Repetitions=16, 4"})),
                          0);
    check_misuse("--resume with another mesh",
                 o,
                 "the checkpoint and Geometry",
                 {"checkpoint_00040", "Geometry"},
                 read_text("full_uniform/time_series.csv") == before &&
                   run_status("full_uniform") == "completed",
                 checks);
  }
} // namespace


int
main()
{
  Checks            checks;
  std::vector<Full> fulls = {{"full_uniform", false, ""},
                             {"full_adaptive", true, ""},
                             {"full_bathe", false, "bathe"},
                             {"full_slip_length", true, "slip_length"}};
  std::vector<Case> all   = cases();
  for (const auto &f : fulls)
    fs::remove_all(f.name);
  fs::remove_all("never_checkpointed");
  for (const auto &c : all)
    fs::remove_all(c.directory);

  run_first_parts(fulls, all);
  for (const auto &f : fulls)
    check_uninterrupted(f, checks);
  for (const auto &c : all)
    check_killed(c, checks);
  // Resume each.
  for (const auto &c : all)
    check_resumed(c, checks);

  check_resume_without_checkpoint(checks);
  check_resume_other_mesh(checks);

  checks.assert_all();
}
