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

#include "program_tools.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;

  const std::vector<std::string> settings = with({"--set",
                                                  "Time/End time=0.125",
                                                  "--set",
                                                  "Checkpoint/Every=4",
                                                  "--set",
                                                  "Checkpoint/Keep=3"},
                                                 quiet);

  std::vector<std::string>
  arguments(const std::string              &directory,
            const bool                      resume,
            const std::vector<std::string> &more = {})
  {
    std::vector<std::string> a;
    if (resume)
      a.push_back("--resume");
    a.push_back(test_tools::scene("barboteu_danan_2016_small.prm"));
    a.insert(a.end(), settings.begin(), settings.end());
    a.push_back("--set");
    a.push_back("Output/Directory=" + directory);
    a.insert(a.end(), more.begin(), more.end());
    return a;
  }

  std::string
  status_of(const fs::path &directory)
  {
    return trim(read_text(directory / "run_status"));
  }

  void
  copy_of(const std::string &from, const std::string &to)
  {
    fs::remove_all(to);
    fs::copy(from, to, fs::copy_options::recursive);
  }
} // namespace


int
main()
{
  std::ostream &out = test_tools::out();
  Checks        checks;

  fs::remove_all("full");
  const Outcome full = execute(arguments("full", false), {"", "full"});
  out << "uninterrupted run: exit code " << full.code << ", "
      << status_of("full") << ", "
      << read_csv("full/time_series.csv").size() - 2 << " steps" << std::endl;
  checks.add(full.succeeded() && status_of("full") == "completed" &&
               fs::exists("full/checkpoint_00012"),
             "the uninterrupted run completes with checkpoint_00012");

  // ------------------------------------------------ damaged checkpoints
  out << "Damaged checkpoints" << std::endl;
  struct Damage
  {
    std::string           name;
    std::function<void()> damage;
    unsigned int          processes;
  };
  const auto truncate = [](const fs::path &file, const std::uintmax_t size) {
    fs::resize_file(file, size);
  };
  std::vector<Damage> damages = {
    {"mesh_fixed_truncated",
     [&]() {
       truncate("mesh_fixed_truncated/checkpoint_00012/mesh_fixed.data", 100);
     },
     0},
    {"mesh_truncated",
     [&]() { truncate("mesh_truncated/checkpoint_00012/mesh", 500); },
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
  for (const auto &d : damages)
    {
      copy_of("full", d.name);
      d.damage();
      Launch launch;
      launch.name      = d.name;
      launch.processes = d.processes;
      launch.timeout   = 120;
      const Outcome o  = execute(arguments(d.name, true), launch);
      const bool    named =
        o.out.find("Warning: the checkpoint " + d.name +
                   "/checkpoint_00012 is damaged: ") != std::string::npos;
      const bool fell_back =
        o.out.find("resumed from " + d.name + "/checkpoint_00008") !=
        std::string::npos;
      const auto differ =
        differing_columns("full", d.name, 16, d.processes > 1 ? 1e-8 : 0);
      // The warning, without sizes and checksums (they follow the round-off
      // of the run and the versions of p4est and deal.II).
      std::string warning;
      for (const auto &l : lines_of(o.out))
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
      out << "  " << d.name << " (" << std::max(d.processes, 1u) << " process"
          << (d.processes > 1 ? "es" : "") << "): exit code " << o.code << ", "
          << status_of(d.name)
          << ", damaged checkpoint named: " << yes_no(named)
          << ", resumed from checkpoint_00008: " << yes_no(fell_back)
          << ", time series columns differing from the uninterrupted run: "
          << join(differ) << std::endl
          << "    " << warning << std::endl;
      checks.add(o.succeeded() && o.err.empty() &&
                   status_of(d.name) == "completed",
                 d.name + ": the resumed run completes, nothing on stderr");
      checks.add(named, d.name + ": the damaged checkpoint is named");
      checks.add(fell_back, d.name + ": it falls back to checkpoint_00008");
      checks.add(differ.empty(),
                 d.name + ": the results are those of the uninterrupted run");
    }

  // Every checkpoint damaged: a clear error, nothing changed.
  {
    copy_of("full", "all_damaged");
    for (const char *c :
         {"checkpoint_00004", "checkpoint_00008", "checkpoint_00012"})
      fs::resize_file(fs::path("all_damaged") / c / "mesh", 10);
    const auto before = snapshot("all_damaged");
    Launch     launch;
    launch.name         = "all_damaged";
    launch.processes    = 2;
    launch.timeout      = 120;
    const Outcome o     = execute(arguments("all_damaged", true), launch);
    const auto    lines = error_lines(o);
    const bool    names_all =
      lines.size() == 1 &&
      lines[0].find("checkpoint_00004: mesh has 10 bytes") !=
        std::string::npos &&
      lines[0].find("checkpoint_00012: mesh has 10 bytes") != std::string::npos;
    out << "  all_damaged (2 processes): exit code " << o.code
        << ", one error line naming every checkpoint: " << yes_no(names_all)
        << ", directory unchanged: "
        << yes_no(snapshot("all_damaged") == before) << std::endl;
    checks.add(o.exited && o.code == 1 && names_all,
               "all_damaged: exit code 1, one error line naming each "
               "damaged checkpoint");
    checks.add(snapshot("all_damaged") == before,
               "all_damaged: nothing in the directory changed");
  }

  // ------------------------------------------------------ changed settings
  out << "Changed settings" << std::endl;
  const auto refused = [&](const std::string              &name,
                           const std::vector<std::string> &more,
                           const std::vector<std::string> &must_name) {
    copy_of("full", name);
    const auto    before = snapshot(name);
    const Outcome o      = execute(arguments(name, true, more), {"", name});
    const auto    lines  = error_lines(o);
    bool          names  = lines.size() == 1;
    for (const auto &n : must_name)
      names = names && lines[0].find(n) != std::string::npos;
    const bool untouched = snapshot(name) == before;
    out << "  " << name << ": exit code " << o.code
        << ", one error line naming what differs: " << yes_no(names)
        << ", directory unchanged: " << yes_no(untouched) << std::endl
        << "    " << (lines.empty() ? "(no error line)" : lines[0])
        << std::endl;
    checks.add(o.exited && o.code == 1 && names,
               name + ": refused with one error line that names it");
    checks.add(untouched, name + ": nothing in the directory changed");
  };
  refused("changed_geometry",
          {"--set", "Geometry/Upper right=20, 1"},
          {"Geometry/Upper right = '20, 1' (checkpoint: '2, 0.1')"});
  refused("changed_friction",
          {"--set",
           "Friction/Law=constant",
           "--set",
           "Friction/Constant/Coefficient=0.3",
           "--set",
           "Material/Density=1e3"},
          {"2 entries",
           "Friction/Law = 'constant'",
           "Friction/Constant/Coefficient = '0.3'"});
  refused("end_before_rows",
          {"--set", "Time/End time=0.1"},
          {"Time/End time", "before the last row already written"});
  refused("end_before_checkpoint",
          {"--set", "Time/End time=0.05"},
          {"Time/End time", "before the time of the checkpoint"});

  // A new time step is honoured after the checkpoint.
  {
    copy_of("full", "new_time_step");
    const Outcome o    = execute(arguments("new_time_step",
                                        true,
                                        {"--set", "Time/Time step=0.00390625"}),
                              {"", "new_time_step"});
    const auto    rows = read_csv("new_time_step/time_series.csv");
    const auto    column =
      std::find(rows[0].begin(), rows[0].end(), "time_step") - rows[0].begin();
    bool before_unchanged =
      differing_columns("full", "new_time_step", 12, 0).empty();
    bool after_new = rows.size() == 1 + 13 + 8;
    for (unsigned int r = 14; after_new && r < rows.size(); ++r)
      after_new = std::stod(rows[r][column]) == 0.00390625;
    out << "  new_time_step: exit code " << o.code << ", "
        << status_of("new_time_step")
        << ", rows up to the checkpoint unchanged: " << yes_no(before_unchanged)
        << ", the 8 steps after it with k = 0.00390625: " << yes_no(after_new)
        << ", says so: "
        << yes_no(o.out.find("Time/Time step changed") != std::string::npos)
        << std::endl;
    checks.add(o.succeeded() && status_of("new_time_step") == "completed",
               "new_time_step: completes");
    checks.add(before_unchanged && after_new,
               "new_time_step: the rows before the checkpoint stay, the "
               "steps after it use the new time step");
  }
  // A later end time (and another Newton tolerance) continues the run.
  {
    copy_of("full", "later_end");
    const Outcome o    = execute(arguments("later_end",
                                        true,
                                        {"--set",
                                            "Time/End time=0.1875",
                                            "--set",
                                            "Solver/Newton tolerance=1e-11"}),
                              {"", "later_end"});
    const auto    rows = read_csv("later_end/time_series.csv");
    out << "  later_end: exit code " << o.code << ", " << status_of("later_end")
        << ", steps: " << rows.size() - 2 << std::endl;
    checks.add(o.succeeded() && status_of("later_end") == "completed" &&
                 rows.size() == 2 + 24,
               "later_end: continues to step 24");
  }

  out << std::endl;
  checks.assert_all();
}
