// --resume loads only a checkpoint that is whole, and continues exactly the
// problem of its checkpoint or refuses (README, "What can go wrong", items
// 3 and 5). The small paper scene runs 16 steps with a checkpoint every 4
// (checkpoint_00004, _00008, _00012 kept); each case works on a copy of
// that directory.
//
// Damaged checkpoints (the newest, checkpoint_00012): mesh_fixed.data cut
// short, the p4est file mesh cut short (on 2 processes: p4est would abort),
// a byte of state.txt changed, mesh.info deleted, manifest.txt deleted. The
// run names the damaged checkpoint, falls back to checkpoint_00008 and ends
// with the results of the uninterrupted run (1 process: as printed except
// the factorization count; 2 processes: the physical columns to 1e-8).
// With every checkpoint damaged it stops with one error line that names
// them, exit code 1, and leaves the directory as it was.
//
// Changed settings: another geometry or friction law, an end time before
// the checkpoint or before rows already written: refused with one error
// line that lists what differs, the directory unchanged. A new time step is
// honoured after the checkpoint (the rows before it unchanged); a later
// end time with another Newton tolerance continues the run.

#include "run_checks.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;
  using namespace run_checks;

  std::vector<std::string>
  arguments(const std::string              &directory,
            const bool                      resume,
            const std::vector<std::string> &more = {})
  {
    const auto a = sixteen_steps(directory, 3, more);
    return resume ? with({"--resume"}, a) : a;
  }

  void
  copy_of(const std::string &from, const std::string &to)
  {
    fs::remove_all(to);
    fs::copy(from, to, fs::copy_options::recursive);
  }

  void
  check_uninterrupted(Checks &checks)
  {
    fs::remove_all("full");
    const Outcome full = execute(arguments("full", false), {"", "full"});
    test_tools::out() << "uninterrupted run: exit code " << full.code << ", "
                      << run_status("full") << ", "
                      << read_csv("full/time_series.csv").size() - 2 << " steps"
                      << std::endl;
    checks.add(full.succeeded() && run_status("full") == "completed" &&
                 fs::exists("full/checkpoint_00012"),
               "the uninterrupted run completes with checkpoint_00012");
  }

  // ------------------------------------------------ damaged checkpoints

  /** A damage done to the copy @p name of the run, resumed on @p processes. */
  struct Damage
  {
    std::string           name;
    std::function<void()> damage;
    unsigned int          processes;
  };

  const std::vector<Damage> damages = {
    {"mesh_fixed_truncated",
     []() {
       fs::resize_file("mesh_fixed_truncated/checkpoint_00012/mesh_fixed.data",
                       100);
     },
     0},
    {"mesh_truncated",
     []() { fs::resize_file("mesh_truncated/checkpoint_00012/mesh", 500); },
     2},
    {"state_changed",
     []() {
       const fs::path file = "state_changed/checkpoint_00012/state.txt";
       std::string    text = read_text(file);
       text[text.find("time ") + 5] ^= 1;
       write_text(file, text);
     },
     0},
    {"file_missing",
     []() { fs::remove("file_missing/checkpoint_00012/mesh.info"); },
     0},
    {"manifest_missing",
     []() { fs::remove("manifest_missing/checkpoint_00012/manifest.txt"); },
     0}};

  /**
   * The warning about a damaged checkpoint in @p text, without sizes and
   * checksums (they follow the round-off of the run and the versions of
   * p4est and deal.II).
   */
  std::string
  warning_in(const std::string &text)
  {
    std::string warning;
    for (const auto &l : lines_of(text))
      if (l.rfind("Warning: the checkpoint", 0) == 0)
        {
          warning =
            std::regex_replace(l,
                               std::regex(R"((checksum|says) [0-9a-f]{8}\b)"),
                               "$1 X");
          warning = std::regex_replace(warning,
                                       std::regex(R"(\b[0-9]+ bytes)"),
                                       "N bytes");
          warning = std::regex_replace(warning,
                                       std::regex(R"(says [0-9]+\b)"),
                                       "says M");
        }
    return warning;
  }

  void
  check_damaged(const Damage &d, Checks &checks)
  {
    copy_of("full", d.name);
    d.damage();
    const Outcome o =
      execute(arguments(d.name, true), launch_of(d.name, d.processes, 120));
    const bool named =
      o.out.find("Warning: the checkpoint " + d.name +
                 "/checkpoint_00012 is damaged: ") != std::string::npos;
    const bool fell_back = o.out.find("resumed from " + d.name +
                                      "/checkpoint_00008") != std::string::npos;
    const auto differ =
      differing_columns("full", d.name, 16, d.processes > 1 ? 1e-8 : 0);
    test_tools::out() << "  " << d.name << " (" << processes_text(d.processes)
                      << "): exit code " << o.code << ", " << run_status(d.name)
                      << ", damaged checkpoint named: " << yes_no(named)
                      << ", resumed from checkpoint_00008: "
                      << yes_no(fell_back)
                      << ", time series columns differing from the "
                         "uninterrupted run: "
                      << join(differ) << std::endl
                      << "    " << warning_in(o.out) << std::endl;
    checks.add(o.succeeded() && o.err.empty() &&
                 run_status(d.name) == "completed",
               d.name + ": the resumed run completes, nothing on stderr");
    checks.add(named, d.name + ": the damaged checkpoint is named");
    checks.add(fell_back, d.name + ": it falls back to checkpoint_00008");
    checks.add(differ.empty(),
               d.name + ": the results are those of the uninterrupted run");
  }

  /** Every checkpoint damaged: a clear error, nothing changed. */
  void
  check_all_damaged(Checks &checks)
  {
    copy_of("full", "all_damaged");
    for (const char *c :
         {"checkpoint_00004", "checkpoint_00008", "checkpoint_00012"})
      fs::resize_file(fs::path("all_damaged") / c / "mesh", 10);
    const auto    before = snapshot("all_damaged");
    const Outcome o =
      execute(arguments("all_damaged", true), launch_of("all_damaged", 2, 120));
    const bool names_all =
      one_line_naming(error_lines(o),
                      {"checkpoint_00004: mesh has 10 bytes",
                       "checkpoint_00012: mesh has 10 bytes"});
    const bool unchanged = snapshot("all_damaged") == before;
    test_tools::out() << "  all_damaged (2 processes): exit code " << o.code
                      << ", one error line naming every checkpoint: "
                      << yes_no(names_all)
                      << ", directory unchanged: " << yes_no(unchanged)
                      << std::endl;
    checks.add(o.exited && o.code == 1 && names_all,
               "all_damaged: exit code 1, one error line naming each "
               "damaged checkpoint");
    checks.add(unchanged, "all_damaged: nothing in the directory changed");
  }

  // ------------------------------------------------------ changed settings

  /** A change --resume refuses: the settings, what the error must name. */
  struct Refusal
  {
    std::string              name;
    std::vector<std::string> settings;
    std::vector<std::string> must_name;
  };

  const std::vector<Refusal> refusals = {
    {"changed_geometry",
     {"Geometry/Upper right=20, 1"},
     {"Geometry/Upper right = '20, 1' (checkpoint: '2, 0.1')"}},
    {"changed_friction",
     {"Friction/Law=constant",
      "Friction/Constant/Coefficient=0.3",
      "Material/Density=1e3"},
     {"2 entries",
      "Friction/Law = 'constant'",
      "Friction/Constant/Coefficient = '0.3'"}},
    {"end_before_rows",
     {"Time/End time=0.1"},
     {"Time/End time", "before the last row already written"}},
    {"end_before_checkpoint",
     {"Time/End time=0.05"},
     {"Time/End time", "before the time of the checkpoint"}}};

  void
  check_refused(const Refusal &r, Checks &checks)
  {
    copy_of("full", r.name);
    const auto    before = snapshot(r.name);
    const Outcome o =
      execute(arguments(r.name, true, overrides(r.settings)), {"", r.name});
    const auto lines     = error_lines(o);
    const bool names     = one_line_naming(lines, r.must_name);
    const bool untouched = snapshot(r.name) == before;
    test_tools::out() << "  " << r.name << ": exit code " << o.code
                      << ", one error line naming what differs: "
                      << yes_no(names)
                      << ", directory unchanged: " << yes_no(untouched)
                      << std::endl
                      << "    "
                      << (lines.empty() ? "(no error line)" : lines[0])
                      << std::endl;
    checks.add(o.exited && o.code == 1 && names,
               r.name + ": refused with one error line that names it");
    checks.add(untouched, r.name + ": nothing in the directory changed");
  }

  /** A new time step is honoured after the checkpoint. */
  void
  check_new_time_step(Checks &checks)
  {
    copy_of("full", "new_time_step");
    const Outcome o =
      execute(arguments("new_time_step",
                        true,
                        overrides({"Time/Time step=0.00390625"})),
              {"", "new_time_step"});
    const auto rows = read_csv("new_time_step/time_series.csv");
    const auto c    = column(rows[0], "time_step");
    bool       before_unchanged =
      differing_columns("full", "new_time_step", 12, 0).empty();
    bool after_new = rows.size() == 1 + 13 + 8;
    for (unsigned int r = 14; after_new && r < rows.size(); ++r)
      after_new = std::stod(rows[r][c]) == 0.00390625;
    test_tools::out() << "  new_time_step: exit code " << o.code << ", "
                      << run_status("new_time_step")
                      << ", rows up to the checkpoint unchanged: "
                      << yes_no(before_unchanged)
                      << ", the 8 steps after it with k = 0.00390625: "
                      << yes_no(after_new) << ", says so: "
                      << yes_no(o.out.find("Time/Time step changed") !=
                                std::string::npos)
                      << std::endl;
    checks.add(o.succeeded() && run_status("new_time_step") == "completed",
               "new_time_step: completes");
    checks.add(before_unchanged && after_new,
               "new_time_step: the rows before the checkpoint stay, the "
               "steps after it use the new time step");
  }

  /** A later end time (and another Newton tolerance) continues the run. */
  void
  check_later_end(Checks &checks)
  {
    copy_of("full", "later_end");
    const auto more =
      overrides({"Time/End time=0.1875", "Solver/Newton tolerance=1e-11"});
    const Outcome o =
      execute(arguments("later_end", true, more), {"", "later_end"});
    const auto rows = read_csv("later_end/time_series.csv");
    test_tools::out() << "  later_end: exit code " << o.code << ", "
                      << run_status("later_end")
                      << ", steps: " << rows.size() - 2 << std::endl;
    checks.add(o.succeeded() && run_status("later_end") == "completed" &&
                 rows.size() == 2 + 24,
               "later_end: continues to step 24");
  }
} // namespace


int
main()
{
  std::ostream &out = test_tools::out();
  Checks        checks;

  check_uninterrupted(checks);

  out << "Damaged checkpoints" << std::endl;
  for (const auto &d : damages)
    check_damaged(d, checks);
  check_all_damaged(checks);

  out << "Changed settings" << std::endl;
  for (const auto &r : refusals)
    check_refused(r, checks);
  check_new_time_step(checks);
  check_later_end(checks);

  out << std::endl;
  checks.assert_all();
}
