// The output directory belongs to the run, and no write fails silently
// (README, "What can go wrong", items 1, 2 and 4). The real executable:
//
// Ownership (prm/pressed_block.prm, 8 steps):
//   user_directory    Output/Directory = . in a folder holding the user's
//                     contact_law.cc, solution_notes/ and checkpoint_old/:
//                     three runs (the second with VTU and checkpoints) leave
//                     them untouched, and each run removes exactly the
//                     results of the one before;
//   foreign_result    a directory holding the user's own time_series.csv is
//                     refused with a message naming it, and left as it was;
//   foreign_beside    a result-named file put beside a run's results is
//                     refused by name, the results left alone;
//   not_a_manifest    a file .dynamic-contact that is not the program's;
//   locked            a directory another run holds (the test takes the
//                     lock .dynamic-contact.lock as a run would) is refused.
// Full disk (the small paper scene, 8 steps, contact CSV every step, VTU
// every 4, a checkpoint every 4): DYNAMIC_CONTACT_DISK_FULL fills the disk
// during a given write (that write stores half its bytes), on 1 and 2
// processes; where root may mount one, also a real 300 kB tmpfs (else the
// same run with an injected 300 kB disk). Every run must end with a non-zero
// exit code (no signal, no abort), run_status "failed: cannot write FILE:
// No space left on device", each row of time_series.csv whole, no empty
// file, no temporary checkpoint left, and never "completed".
// An error on one process of two (DYNAMIC_CONTACT_FAIL on rank 1, then on
// rank 0, and a damaged time_series.csv on --resume) ends both within
// seconds with the message and run_status "failed: ...", not a hang.

#include "program_tools.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;

  std::string
  status_of(const fs::path &directory)
  {
    return trim(read_text(directory / "run_status"));
  }

  std::string
  first_error(const Outcome &o)
  {
    const auto lines = error_lines(o);
    return lines.empty() ? "(none)" : lines[0];
  }

  /** Every line of a CSV file has the fields of its header. */
  bool
  rows_whole(const fs::path &file)
  {
    const auto lines = lines_of(read_text(file));
    if (lines.empty())
      return false;
    const auto n = split(lines[0], ',').size();
    for (const auto &l : lines)
      if (split(l, ',').size() != n || l.empty() || l.back() == ',')
        return false;
    return read_text(file).back() == '\n';
  }

  /** No empty file, no temporary checkpoint under @p directory. */
  bool
  no_debris(const fs::path &directory)
  {
    for (const auto &e : fs::recursive_directory_iterator(directory))
      {
        const std::string n = e.path().filename().string();
        if (n.size() > 4 && n.substr(n.size() - 4) == ".tmp")
          return false;
        if (e.is_regular_file() && fs::file_size(e.path()) == 0 &&
            n != ".dynamic-contact.lock")
          return false;
      }
    return true;
  }
} // namespace


int
main()
{
  std::ostream     &out = test_tools::out();
  Checks            checks;
  const std::string block = test_tools::scene("pressed_block.prm");
  const std::string paper = test_tools::scene("barboteu_danan_2016_small.prm");

  // ------------------------------------------------------------ ownership
  out << "Ownership" << std::endl;
  {
    const fs::path dir = "user_directory";
    fs::remove_all(dir);
    fs::create_directories(dir / "solution_notes");
    fs::create_directories(dir / "checkpoint_old");
    write_text(dir / "contact_law.cc", "// the user's law\n");
    write_text(dir / "solution_notes" / "notes.txt", "notes\n");
    write_text(dir / "checkpoint_old" / "state.txt", "old\n");
    const auto user = snapshot(dir);

    Launch launch;
    launch.directory                      = dir;
    const std::vector<std::string> here   = {block,
                                             "--set",
                                             "Output/Directory=."};
    const Outcome                  first  = execute(with(here, quiet), launch);
    const Outcome                  second = execute(with(here,
                                        with(quiet,
                                             {"--set",
                                                               "Output/Write VTU=true",
                                                               "--set",
                                                               "Output/VTU every=4",
                                                               "--set",
                                                               "Checkpoint/Every=2"})),
                                   launch);
    const bool second_wrote = fs::exists(dir / "solution_00004.pvtu") &&
                              fs::exists(dir / "checkpoint_00006");
    const Outcome third             = execute(with(here, quiet), launch);
    auto          after             = snapshot(dir);
    bool          user_files_intact = true;
    for (const auto &[name, text] : user)
      user_files_intact =
        user_files_intact && after.count(name) == 1 && after[name] == text;
    const bool earlier_results_gone =
      !fs::exists(dir / "solution_00004.pvtu") &&
      !fs::exists(dir / "checkpoint_00006") &&
      !fs::exists(dir / "solution.pvd");
    out << "  user_directory: exit codes " << first.code << ", " << second.code
        << ", " << third.code
        << "; the user's contact_law.cc, solution_notes/, checkpoint_old/ "
           "unchanged: "
        << yes_no(user_files_intact)
        << "; the second run's VTU and checkpoints removed by the third: "
        << yes_no(second_wrote && earlier_results_gone)
        << "; run_status: " << status_of(dir) << std::endl;
    checks.add(first.succeeded() && second.succeeded() && third.succeeded(),
               "user_directory: the three runs complete");
    checks.add(user_files_intact,
               "user_directory: the user's files survive every run");
    checks.add(second_wrote && earlier_results_gone,
               "user_directory: a new run removes exactly the results of "
               "the earlier one");
  }

  auto refused = [&](const std::string                        &name,
                     const fs::path                           &dir,
                     const Outcome                            &o,
                     const std::map<std::string, std::string> &before,
                     const std::string                        &must_name) {
    const auto lines     = error_lines(o);
    const bool one       = lines.size() == 1;
    const bool names     = one && lines[0].find(must_name) != std::string::npos;
    const bool untouched = snapshot(dir) == before;
    out << "  " << name << ": exit code " << o.code
        << ", one error line naming '" << must_name << "': " << yes_no(names)
        << ", the directory untouched: " << yes_no(untouched) << std::endl
        << "    "
        << std::regex_replace(first_error(o),
                              std::regex(R"(process [0-9]+ on host [^)]*)"),
                              "process P on host H")
        << std::endl;
    checks.add(o.exited && o.code == 1, name + ": exit code 1");
    checks.add(names, name + ": one error line that names " + must_name);
    checks.add(untouched, name + ": nothing in the directory changed");
  };

  {
    const fs::path dir = "foreign_result";
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_text(dir / "time_series.csv", "my own measurements\n1,2,3\n");
    const auto    before = snapshot(dir);
    const Outcome o =
      execute(with({block, "--set", "Output/Directory=foreign_result"}, quiet),
              {"", "foreign_result"});
    refused("foreign_result", dir, o, before, "time_series.csv");
  }
  {
    const fs::path dir = "foreign_beside";
    fs::remove_all(dir);
    const auto args =
      with({block, "--set", "Output/Directory=foreign_beside"}, quiet);
    const Outcome first = execute(args, {"", "foreign_beside.1"});
    write_text(dir / "contact_00099.csv", "x,y\n1,2\n");
    const auto    before = snapshot(dir);
    const Outcome o      = execute(args, {"", "foreign_beside.2"});
    checks.add(first.succeeded(), "foreign_beside: the first run completes");
    refused("foreign_beside", dir, o, before, "contact_00099.csv");
  }
  {
    const fs::path dir = "not_a_manifest";
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_text(dir / ".dynamic-contact", "my notes\n");
    const auto    before = snapshot(dir);
    const Outcome o =
      execute(with({block, "--set", "Output/Directory=not_a_manifest"}, quiet),
              {"", "not_a_manifest"});
    refused("not_a_manifest", dir, o, before, ".dynamic-contact");
  }
  {
    const fs::path dir = "locked";
    fs::remove_all(dir);
    const auto args = with({block, "--set", "Output/Directory=locked"}, quiet);
    const Outcome first = execute(args, {"", "locked.1"});
    // Hold the lock as a running run does.
    const int     fd = ::open((dir / ".dynamic-contact.lock").c_str(), O_RDWR);
    const bool    held   = fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    const auto    before = snapshot(dir);
    const Outcome o      = execute(args, {"", "locked.2"});
    checks.add(first.succeeded() && held,
               "locked: the first run completes, the test holds its lock");
    refused("locked", dir, o, before, "in use by another run");
    if (fd >= 0)
      ::close(fd);
    const Outcome after = execute(args, {"", "locked.3"});
    out << "  locked, once released: exit code " << after.code
        << ", run_status: " << status_of(dir) << std::endl;
    checks.add(after.succeeded() && status_of(dir) == "completed",
               "locked: once the lock is released, a run completes");
  }

  // ------------------------------------------------------------ full disk
  out << "Full disk" << std::endl;
  const std::vector<std::string> paper_settings = {"--set",
                                                   "Time/End time=0.0625",
                                                   "--set",
                                                   "Output/Write VTU=true",
                                                   "--set",
                                                   "Output/VTU every=4",
                                                   "--set",
                                                   "Checkpoint/Every=4",
                                                   "--set",
                                                   "Checkpoint/Keep=10"};
  auto                           full_disk = [&](const std::string              &name,
                       const std::string              &injection,
                       const unsigned int              processes,
                       const fs::path                 &output = "",
                       const std::vector<std::string> &more = {}) {
    const fs::path dir = output.empty() ? fs::path(name) : output;
    fs::remove_all(dir);
    Launch launch;
    launch.name      = name;
    launch.processes = processes;
    launch.timeout   = 120;
    if (!injection.empty())
      launch.environment.push_back("DYNAMIC_CONTACT_DISK_FULL=" + injection);
    const Outcome o = execute(
      with(with(with({paper, "--set", "Output/Directory=" + dir.string()},
                     quiet),
                paper_settings),
           more),
      launch);
    const std::string status = status_of(dir);
    const std::string prefix = "failed: cannot write " + dir.string() + "/";
    const bool        says_why =
      status.rfind(prefix, 0) == 0 &&
      status.find(": No space left on device") != std::string::npos;
    // The file the status names (up to ": "), relative to the directory.
    const std::string file =
      says_why ? status.substr(prefix.size(),
                               status.find(": No space") - prefix.size()) :
                                           "?";
    const bool whole = rows_whole(dir / "time_series.csv");
    const bool clean = no_debris(dir);
    out << "  " << name << " on " << std::max(processes, 1u) << " process"
        << (processes > 1 ? "es" : "") << ": exit code nonzero: "
        << yes_no(o.exited && o.code != 0 && o.code != 124)
        << ", run_status 'failed: cannot write <file>: No space left on "
                                     "device': "
        << yes_no(says_why)
        << ", every row of time_series.csv whole: " << yes_no(whole)
        << ", no empty file or temporary checkpoint: " << yes_no(clean)
        << std::endl;
    checks.add(o.exited && o.code != 0 && o.code != 124 && o.code != 134,
               name + ": a non-zero exit (no signal, abort or hang)");
    checks.add(says_why,
               name +
                 ": run_status says which file could not be written "
                                           "and why" +
                 (says_why ? std::string() : " [" + status + "]"));
    checks.add(o.err.find("dynamic-contact: error: cannot write ") !=
                 std::string::npos,
               name + ": the message is on screen");
    checks.add(whole, name + ": every row of time_series.csv is whole");
    checks.add(clean, name + ": no empty file, no temporary checkpoint");
    return file;
  };

  // Each case prints the file its run_status names.
  const auto named = [&](const std::string &file) {
    out << "    the file: " << file << std::endl;
  };
  named(full_disk("disk_time_series", "time_series.csv:5", 0));
  out << "    rows left in time_series.csv: "
      << read_csv("disk_time_series/time_series.csv").size() - 1 << std::endl;
  checks.add(read_csv("disk_time_series/time_series.csv").size() == 5,
             "disk_time_series: the rows of steps 0 to 3 stay, the fifth "
             "is taken back");
  named(full_disk("disk_contact", "contact_00003.csv", 0));
  checks.add(!fs::exists("disk_contact/contact_00003.csv"),
             "disk_contact: no partial contact_00003.csv");
  named(full_disk("disk_vtu", "solution_00004.0.vtu", 0));
  named(full_disk("disk_checkpoint", "mesh", 0));
  checks.add(fs::exists("disk_checkpoint/checkpoint_00004") == false &&
               fs::exists("disk_checkpoint/checkpoint_00004.tmp") == false,
             "disk_checkpoint: no checkpoint_00004, complete or not");
  named(full_disk("disk_vtu_rank_1", "solution_00004.1.vtu@1", 2));
  named(full_disk("disk_time_series_2", "time_series.csv:3", 2));
  {
    // run_status itself cannot take "completed": the run must not pass.
    fs::remove_all("disk_status");
    Launch launch;
    launch.name = "disk_status";
    launch.environment.push_back("DYNAMIC_CONTACT_DISK_FULL=run_status:2");
    const Outcome o =
      execute(with(with({paper, "--set", "Output/Directory=disk_status"},
                        quiet),
                   paper_settings),
              launch);
    out << "  disk_status (run_status cannot be rewritten at the end): exit "
           "code "
        << o.code << ", run_status: " << status_of("disk_status")
        << ", error: " << first_error(o) << std::endl;
    checks.add(o.exited && o.code == 1 &&
                 status_of("disk_status") != "completed",
               "disk_status: a run whose final status cannot be written "
               "fails");
  }
  {
    // A real full disk: a 300 kB tmpfs where root may mount one, else the
    // same size injected.
    if (std::system("umount tmpfs 2>/dev/null") != 0)
      {} // none left from an earlier run
    fs::remove_all("tmpfs");
    fs::create_directories("tmpfs");
    const bool mounted =
      ::geteuid() == 0 &&
      std::system("mount -t tmpfs -o size=300k tmpfs tmpfs 2>/dev/null") == 0;
    full_disk("disk_300k",
              mounted ? "" : "300000",
              0,
              mounted ? fs::path("tmpfs/out") : fs::path("disk_300k"),
              {"--set", "Time/End time=0.25"});
    if (mounted)
      checks.add(std::system("umount tmpfs") == 0, "tmpfs unmounted");
  }

  // ----------------------------------------- an error on one process of two
  out << "An error on one process of two" << std::endl;
  for (const unsigned int rank : {1u, 0u})
    {
      const std::string name = "one_rank_" + std::to_string(rank);
      fs::remove_all(name);
      Launch launch;
      launch.name      = name;
      launch.processes = 2;
      launch.timeout   = 120;
      launch.environment.push_back("DYNAMIC_CONTACT_FAIL=after-step 2 rank " +
                                   std::to_string(rank));
      const auto    start = std::chrono::steady_clock::now();
      const Outcome o =
        execute(with(with({paper, "--set", "Output/Directory=" + name}, quiet),
                     paper_settings),
                launch);
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      const std::string expected =
        "failed: injected failure after step 2 (DYNAMIC_CONTACT_FAIL)";
      const bool message =
        o.err.find("dynamic-contact: error: injected "
                   "failure after step 2") != std::string::npos;
      out << "  failure on rank " << rank
          << ": every process ended with a non-zero exit code: "
          << yes_no(o.exited && o.code != 0 && o.code != 124)
          << ", the message on screen: " << yes_no(message)
          << ", run_status: " << status_of(name) << std::endl;
      checks.add(o.exited && o.code != 0 && o.code != 124 && seconds < 60,
                 name + ": the run ends, no hang");
      checks.add(message, name + ": the message is on screen");
      checks.add(status_of(name) == expected, name + ": run_status says why");
    }
  {
    // A damaged time_series.csv, found by rank 0 alone on --resume.
    const std::string name = "damaged_series";
    fs::remove_all(name);
    Launch launch;
    launch.name      = name + ".1";
    launch.processes = 2;
    launch.timeout   = 120;
    const auto args =
      with(with({paper, "--set", "Output/Directory=" + name}, quiet),
           paper_settings);
    const Outcome first = execute(args, launch);
    auto        lines = lines_of(read_text(fs::path(name) / "time_series.csv"));
    std::string text;
    for (unsigned int i = 0; i < lines.size(); ++i)
      text += (i == 3 ? std::string("3,garbage") : lines[i]) + "\n";
    write_text(fs::path(name) / "time_series.csv", text);
    launch.name     = name + ".2";
    const Outcome o = execute(with({"--resume"}, args), launch);
    out << "  damaged time_series.csv on --resume, 2 processes: exit code "
        << o.code << ", run_status: " << status_of(name) << std::endl
        << "    " << first_error(o) << std::endl;
    checks.add(first.succeeded(), "damaged_series: the first run completes");
    checks.add(o.exited && o.code == 1 && error_lines(o).size() == 1,
               "damaged_series: exit code 1, one error line, no hang");
    checks.add(status_of(name) == "completed",
               "damaged_series: the refused resume leaves run_status alone");
  }

  out << std::endl;
  checks.assert_all();
}
