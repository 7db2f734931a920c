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

#include "run_checks.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
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
  using namespace run_checks;

  const std::string block = test_tools::scene("pressed_block.prm");
  const std::string paper = test_tools::scene("barboteu_danan_2016_small.prm");

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

  // ------------------------------------------------------------ ownership

  void
  check_user_directory(Checks &checks)
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
    launch.directory                     = dir;
    const std::vector<std::string> here  = {block,
                                            "--set",
                                            "Output/Directory=."};
    const Outcome                  first = execute(with(here, quiet), launch);
    const Outcome                  second =
      execute(with(here,
                   with(quiet,
                        overrides({"Output/Write VTU=true",
                                   "Output/VTU every=4",
                                   "Checkpoint/Every=2"}))),
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
    test_tools::out()
      << "  user_directory: exit codes " << first.code << ", " << second.code
      << ", " << third.code
      << "; the user's contact_law.cc, solution_notes/, checkpoint_old/ "
         "unchanged: "
      << yes_no(user_files_intact)
      << "; the second run's VTU and checkpoints removed by the third: "
      << yes_no(second_wrote && earlier_results_gone)
      << "; run_status: " << run_status(dir) << std::endl;
    checks.add(first.succeeded() && second.succeeded() && third.succeeded(),
               "user_directory: the three runs complete");
    checks.add(user_files_intact,
               "user_directory: the user's files survive every run");
    checks.add(second_wrote && earlier_results_gone,
               "user_directory: a new run removes exactly the results of "
               "the earlier one");
  }

  /**
   * A directory the program must refuse: made ready by @p prepare (after a
   * completed run into it if @p earlier_run); the refusal names @p must_name.
   */
  struct Refusal
  {
    std::string                           name;
    bool                                  earlier_run;
    std::function<bool(const fs::path &)> prepare;
    std::string                           must_name;
    /** The check of the earlier run and of prepare. */
    std::string earlier_check = "the first run completes";
  };

  void
  check_refusal(const Refusal &r, Checks &checks)
  {
    const fs::path dir = r.name;
    fs::remove_all(dir);
    const auto args =
      with({block, "--set", "Output/Directory=" + r.name}, quiet);
    Outcome first;
    if (r.earlier_run)
      first = execute(args, {"", r.name + ".1"});
    else
      fs::create_directories(dir);
    const bool    prepared = r.prepare(dir);
    const auto    before   = snapshot(dir);
    const Outcome o =
      execute(args, {"", r.earlier_run ? r.name + ".2" : r.name});
    if (r.earlier_run)
      checks.add(first.succeeded() && prepared,
                 r.name + ": " + r.earlier_check);

    const bool names     = one_line_naming(error_lines(o), {r.must_name});
    const bool untouched = snapshot(dir) == before;
    test_tools::out()
      << "  " << r.name << ": exit code " << o.code
      << ", one error line naming '" << r.must_name << "': " << yes_no(names)
      << ", the directory untouched: " << yes_no(untouched) << std::endl
      << "    "
      << std::regex_replace(first_error(o),
                            std::regex(R"(process [0-9]+ on host [^)]*)"),
                            "process P on host H")
      << std::endl;
    checks.add(o.exited && o.code == 1, r.name + ": exit code 1");
    checks.add(names, r.name + ": one error line that names " + r.must_name);
    checks.add(untouched, r.name + ": nothing in the directory changed");
  }

  /** A file @p name with @p text in the directory, made ready by it. */
  std::function<bool(const fs::path &)>
  put(const std::string &name, const std::string &text)
  {
    return [name, text](const fs::path &dir) {
      write_text(dir / name, text);
      return true;
    };
  }

  const std::vector<Refusal> refusals = {
    {"foreign_result",
     false,
     put("time_series.csv", "my own measurements\n1,2,3\n"),
     "time_series.csv"},
    {"foreign_beside",
     true,
     put("contact_00099.csv", "x,y\n1,2\n"),
     "contact_00099.csv"},
    {"not_a_manifest",
     false,
     put(".dynamic-contact", "my notes\n"),
     ".dynamic-contact"}};

  /** A directory whose lock the test holds; once released, a run works. */
  void
  check_locked(Checks &checks)
  {
    int fd = -1;
    // Hold the lock as a running run does.
    const auto hold = [&fd](const fs::path &dir) {
      fd = ::open((dir / ".dynamic-contact.lock").c_str(), O_RDWR);
      return fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    };
    check_refusal({"locked",
                   true,
                   hold,
                   "in use by another run",
                   "the first run completes, the test holds its lock"},
                  checks);
    if (fd >= 0)
      ::close(fd);
    const Outcome after =
      execute(with({block, "--set", "Output/Directory=locked"}, quiet),
              {"", "locked.3"});
    test_tools::out() << "  locked, once released: exit code " << after.code
                      << ", run_status: " << run_status("locked") << std::endl;
    checks.add(after.succeeded() && run_status("locked") == "completed",
               "locked: once the lock is released, a run completes");
  }

  // ------------------------------------------------------------ full disk

  /** The small paper scene, 8 steps, every kind of output, into @p dir. */
  std::vector<std::string>
  paper_arguments(const std::string &dir)
  {
    return with(with({paper, "--set", "Output/Directory=" + dir}, quiet),
                overrides({"Time/End time=0.0625",
                           "Output/Write VTU=true",
                           "Output/VTU every=4",
                           "Checkpoint/Every=4",
                           "Checkpoint/Keep=10"}));
  }

  /**
   * Run @p name with a full disk (@p injection: where it fills, "" for a
   * real one) into @p output (default: @p name), check how it ends, and
   * return the file its run_status names.
   */
  std::string
  full_disk(Checks                         &checks,
            const std::string              &name,
            const std::string              &injection,
            const unsigned int              processes,
            const fs::path                 &output = "",
            const std::vector<std::string> &more   = {})
  {
    const fs::path dir = output.empty() ? fs::path(name) : output;
    fs::remove_all(dir);
    std::vector<std::string> environment;
    if (!injection.empty())
      environment.push_back("DYNAMIC_CONTACT_DISK_FULL=" + injection);
    const Outcome     o = execute(with(paper_arguments(dir.string()), more),
                              launch_of(name, processes, 120, environment));
    const std::string status = run_status(dir);
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
    test_tools::out()
      << "  " << name << " on " << processes_text(processes)
      << ": exit code nonzero: "
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
  }

  /** A full disk injected into a write; checks of what that write left. */
  struct DiskFull
  {
    std::string                   name;
    std::string                   injection;
    unsigned int                  processes;
    std::function<void(Checks &)> more_checks;
  };

  const std::vector<DiskFull> disks_full = {
    {"disk_time_series",
     "time_series.csv:5",
     0,
     [](Checks &checks) {
       test_tools::out()
         << "    rows left in time_series.csv: "
         << read_csv("disk_time_series/time_series.csv").size() - 1
         << std::endl;
       checks.add(read_csv("disk_time_series/time_series.csv").size() == 5,
                  "disk_time_series: the rows of steps 0 to 3 stay, the "
                  "fifth is taken back");
     }},
    {"disk_contact",
     "contact_00003.csv",
     0,
     [](Checks &checks) {
       checks.add(!fs::exists("disk_contact/contact_00003.csv"),
                  "disk_contact: no partial contact_00003.csv");
     }},
    {"disk_vtu", "solution_00004.0.vtu", 0, nullptr},
    {"disk_checkpoint",
     "mesh",
     0,
     [](Checks &checks) {
       checks.add(fs::exists("disk_checkpoint/checkpoint_00004") == false &&
                    fs::exists("disk_checkpoint/checkpoint_00004.tmp") == false,
                  "disk_checkpoint: no checkpoint_00004, complete or not");
     }},
    {"disk_vtu_rank_1", "solution_00004.1.vtu@1", 2, nullptr},
    {"disk_time_series_2", "time_series.csv:3", 2, nullptr}};

  void
  check_disk_full(const DiskFull &d, Checks &checks)
  {
    // Each case prints the file its run_status names.
    const std::string file =
      full_disk(checks, d.name, d.injection, d.processes);
    test_tools::out() << "    the file: " << file << std::endl;
    if (d.more_checks)
      d.more_checks(checks);
  }

  /** run_status itself cannot take "completed": the run must not pass. */
  void
  check_status_unwritable(Checks &checks)
  {
    fs::remove_all("disk_status");
    const Outcome o =
      execute(paper_arguments("disk_status"),
              launch_of("disk_status",
                        0,
                        0,
                        {"DYNAMIC_CONTACT_DISK_FULL=run_status:2"}));
    test_tools::out()
      << "  disk_status (run_status cannot be rewritten at the end): exit "
         "code "
      << o.code << ", run_status: " << run_status("disk_status")
      << ", error: " << first_error(o) << std::endl;
    checks.add(o.exited && o.code == 1 &&
                 run_status("disk_status") != "completed",
               "disk_status: a run whose final status cannot be written "
               "fails");
  }

  /**
   * A real full disk: a 300 kB tmpfs where root may mount one, else the
   * same size injected.
   */
  void
  check_real_disk_full(Checks &checks)
  {
    if (std::system("umount tmpfs 2>/dev/null") != 0)
      {} // none left from an earlier run
    fs::remove_all("tmpfs");
    fs::create_directories("tmpfs");
    const bool mounted =
      ::geteuid() == 0 &&
      std::system("mount -t tmpfs -o size=300k tmpfs tmpfs 2>/dev/null") == 0;
    full_disk(checks,
              "disk_300k",
              mounted ? "" : "300000",
              0,
              mounted ? fs::path("tmpfs/out") : fs::path("disk_300k"),
              overrides({"Time/End time=0.25"}));
    if (mounted)
      checks.add(std::system("umount tmpfs") == 0, "tmpfs unmounted");
  }

  // ----------------------------------------- an error on one process of two

  void
  check_failure_on_rank(const unsigned int rank, Checks &checks)
  {
    const std::string name = "one_rank_" + std::to_string(rank);
    fs::remove_all(name);
    const auto    start = std::chrono::steady_clock::now();
    const Outcome o =
      execute(paper_arguments(name),
              launch_of(name,
                        2,
                        120,
                        {"DYNAMIC_CONTACT_FAIL=after-step 2 rank " +
                         std::to_string(rank)}));
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    const std::string expected =
      "failed: injected failure after step 2 (DYNAMIC_CONTACT_FAIL)";
    const bool message =
      o.err.find("dynamic-contact: error: injected "
                 "failure after step 2") != std::string::npos;
    test_tools::out() << "  failure on rank " << rank
                      << ": every process ended with a non-zero exit code: "
                      << yes_no(o.exited && o.code != 0 && o.code != 124)
                      << ", the message on screen: " << yes_no(message)
                      << ", run_status: " << run_status(name) << std::endl;
    checks.add(o.exited && o.code != 0 && o.code != 124 && seconds < 60,
               name + ": the run ends, no hang");
    checks.add(message, name + ": the message is on screen");
    checks.add(run_status(name) == expected, name + ": run_status says why");
  }

  /** A damaged time_series.csv, found by rank 0 alone on --resume. */
  void
  check_damaged_series(Checks &checks)
  {
    const std::string name = "damaged_series";
    fs::remove_all(name);
    const auto    args  = paper_arguments(name);
    const Outcome first = execute(args, launch_of(name + ".1", 2, 120));
    auto        lines = lines_of(read_text(fs::path(name) / "time_series.csv"));
    std::string text;
    for (unsigned int i = 0; i < lines.size(); ++i)
      text += (i == 3 ? std::string("3,garbage") : lines[i]) + "\n";
    write_text(fs::path(name) / "time_series.csv", text);
    const Outcome o =
      execute(with({"--resume"}, args), launch_of(name + ".2", 2, 120));
    test_tools::out()
      << "  damaged time_series.csv on --resume, 2 processes: exit code "
      << o.code << ", run_status: " << run_status(name) << std::endl
      << "    " << first_error(o) << std::endl;
    checks.add(first.succeeded(), "damaged_series: the first run completes");
    checks.add(o.exited && o.code == 1 && error_lines(o).size() == 1,
               "damaged_series: exit code 1, one error line, no hang");
    checks.add(run_status(name) == "completed",
               "damaged_series: the refused resume leaves run_status alone");
  }
} // namespace


int
main()
{
  std::ostream &out = test_tools::out();
  Checks        checks;

  out << "Ownership" << std::endl;
  check_user_directory(checks);
  for (const auto &r : refusals)
    check_refusal(r, checks);
  check_locked(checks);

  out << "Full disk" << std::endl;
  for (const auto &d : disks_full)
    check_disk_full(d, checks);
  check_status_unwritable(checks);
  check_real_disk_full(checks);

  out << "An error on one process of two" << std::endl;
  for (const unsigned int rank : {1u, 0u})
    check_failure_on_rank(rank, checks);
  check_damaged_series(checks);

  out << std::endl;
  checks.assert_all();
}
