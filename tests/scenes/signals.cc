// A signal stops a run cleanly (README, "What can go wrong", item 6): on
// SIGTERM, SIGINT, SIGHUP and SIGUSR1 the program finishes the current
// step, writes a checkpoint (with Checkpoint/Every > 0), sets run_status to
// "stopped: signal N at step S" and exits with 128 + N, on every process.
//
// The small paper scene, 16 steps, a checkpoint every 4:
//   - each signal raised after step 5 (the fault injection
//     DYNAMIC_CONTACT_KILL = "signal N after-step 5"), on 1 process;
//   - SIGTERM raised on rank 1 alone of 2 processes: both stop after step 5;
//   - SIGINT without checkpoints: stopped, no checkpoint;
//   - SIGTERM sent by this test to the running program (a larger mesh, so
//     that it runs for seconds) at a step it does not choose;
//   - the run stopped by SIGTERM, resumed, ends with the results of the
//     uninterrupted run (as printed, except the factorization count).

#include "run_checks.h"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

extern char **environ;

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;
  using namespace run_checks;

  /** Checkpoints kept: the newest two. */
  const unsigned int keep = 2;

  unsigned int
  last_row(const fs::path &directory)
  {
    const auto rows = read_csv(directory / "time_series.csv");
    return rows.size() < 2 ? 0 : std::stoul(rows.back()[0]);
  }

  bool
  verified_checkpoint(const fs::path &directory, const unsigned int step)
  {
    char name[32];
    std::snprintf(name, sizeof(name), "checkpoint_%05u", step);
    return fs::exists(directory / name / "manifest.txt");
  }

  /** A signal raised after step 5 by the fault injection. */
  struct Case
  {
    std::string              name;
    int                      signal;
    unsigned int             processes;
    std::string              rank;
    std::vector<std::string> more;
  };

  const std::vector<Case> cases = {
    {"sigterm", SIGTERM, 0, "", {}},
    {"sigint", SIGINT, 0, "", {}},
    {"sighup", SIGHUP, 0, "", {}},
    {"sigusr1", SIGUSR1, 0, "", {}},
    {"sigterm_rank_1_of_2", SIGTERM, 2, " rank 1", {}},
    {"sigint_no_checkpoints", SIGINT, 0, "", {"--set", "Checkpoint/Every=0"}}};

  void
  check_signal(const Case &c, Checks &checks)
  {
    fs::remove_all(c.name);
    const Outcome o =
      execute(sixteen_steps(c.name, keep, c.more),
              launch_of(c.name,
                        c.processes,
                        120,
                        {"DYNAMIC_CONTACT_KILL=signal " +
                         std::to_string(c.signal) + " after-step 5" + c.rank}));
    const std::string expected =
      "stopped: signal " + std::to_string(c.signal) + " at step 5";
    const bool checkpoints = c.more.empty();
    test_tools::out() << c.name << " (" << processes_text(c.processes)
                      << "): exit code " << o.code
                      << ", run_status: " << run_status(c.name)
                      << ", last row: step " << last_row(c.name)
                      << ", checkpoint_00005: "
                      << yes_no(verified_checkpoint(c.name, 5)) << std::endl;
    checks.add(o.exited && o.code == 128 + c.signal,
               c.name + ": exit code 128 + " + std::to_string(c.signal));
    checks.add(run_status(c.name) == expected,
               c.name + ": run_status '" + expected + "'");
    checks.add(last_row(c.name) == 5, c.name + ": rows up to step 5");
    checks.add(verified_checkpoint(c.name, 5) == checkpoints,
               c.name + (checkpoints ? ": a checkpoint of step 5" :
                                       ": no checkpoint"));
    // (mpiexec reports the non-zero exit codes on stderr.)
    checks.add(c.processes > 1 ?
                 o.err.find("dynamic-contact: error") == std::string::npos :
                 o.err.empty(),
               c.name + ": no error on stderr");
  }

  /** Resumed, the stopped run ends as if it had not been stopped. */
  void
  check_resumed(Checks &checks)
  {
    const Outcome o =
      execute(with({"--resume"}, sixteen_steps("sigterm", keep)),
              {"", "sigterm.resumed"});
    const auto differing = differing_csv_columns("full/time_series.csv",
                                                 "sigterm/time_series.csv",
                                                 0,
                                                 {"factorizations"});
    const bool said =
      o.out.find("resumed from sigterm/checkpoint_00005") != std::string::npos;
    test_tools::out() << "sigterm, resumed: exit code " << o.code << ", "
                      << run_status("sigterm")
                      << ", from checkpoint_00005: " << yes_no(said)
                      << ", time series columns differing from the "
                         "uninterrupted run (besides factorizations): "
                      << join(differing) << std::endl;
    checks.add(o.succeeded() && run_status("sigterm") == "completed" && said,
               "sigterm: resumed from checkpoint_00005, completes");
    checks.add(differing.empty(),
               "sigterm: the resumed run ends with the results of the "
               "uninterrupted one");
  }

  /**
   * Start the program with @p arguments in the background, its output in
   * @p name.stdout and @p name.stderr; its process id (0 if not started).
   */
  pid_t
  spawn(const std::string &name, const std::vector<std::string> &arguments)
  {
    std::vector<std::string> argv_strings = {"/bin/sh",
                                             "-c",
                                             "exec \"$0\" \"$@\" </dev/null >" +
                                               name + ".stdout 2>" + name +
                                               ".stderr",
                                             DYNAMIC_CONTACT_EXECUTABLE};
    argv_strings.insert(argv_strings.end(), arguments.begin(), arguments.end());
    std::vector<char *> argv;
    for (auto &a : argv_strings)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, "/bin/sh", nullptr, nullptr, argv.data(), environ) !=
        0)
      return 0;
    return pid;
  }

  /** SIGTERM from outside, at a step the program does not choose. */
  void
  check_external_sigterm(Checks &checks)
  {
    const std::string name = "external_sigterm";
    fs::remove_all(name);
    const pid_t pid =
      spawn(name,
            sixteen_steps(name,
                          keep,
                          overrides({"Geometry/Repetitions=128, 32",
                                     "Time/End time=1"})));
    const bool started = pid != 0;
    // Wait for a few steps, then stop it.
    const auto start = std::chrono::steady_clock::now();
    while (started && last_row(name) < 3 &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const unsigned int rows_before = last_row(name);
    int                status      = 0;
    if (started)
      {
        ::kill(pid, SIGTERM);
        ::waitpid(pid, &status, 0);
      }
    const bool         exited = started && WIFEXITED(status);
    const int          code   = exited ? WEXITSTATUS(status) : -1;
    const unsigned int last   = last_row(name);
    const bool         stopped_there =
      run_status(name) == "stopped: signal 15 at step " + std::to_string(last);
    test_tools::out() << "external SIGTERM: exit code " << code
                      << ", run_status 'stopped: signal 15 at step S', S the "
                         "last row of time_series.csv: "
                      << yes_no(stopped_there) << ", a checkpoint of step S: "
                      << yes_no(verified_checkpoint(name, last)) << std::endl;
    checks.add(exited && code == 143, "external SIGTERM: exit code 143");
    const bool stopped_in_time =
      stopped_there && last >= rows_before && last < 128;
    checks.add(stopped_in_time,
               "external SIGTERM: stopped after the step it was in" +
                 (stopped_in_time ? std::string() :
                                    " [" + run_status(name) + "]"));
    checks.add(verified_checkpoint(name, last),
               "external SIGTERM: a checkpoint of the last step");
  }
} // namespace


int
main()
{
  Checks checks;

  fs::remove_all("full");
  const Outcome full = execute(sixteen_steps("full", keep), {"", "full"});
  checks.add(full.succeeded() && run_status("full") == "completed",
             "the uninterrupted run completes");

  for (const auto &c : cases)
    check_signal(c, checks);
  check_resumed(checks);
  check_external_sigterm(checks);

  test_tools::out() << std::endl;
  checks.assert_all();
}
