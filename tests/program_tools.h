#ifndef dynamic_contact_tests_program_tools_h
#define dynamic_contact_tests_program_tools_h

// Shared helpers of the tests that run the dynamic-contact executable as a
// user does (bad_input, command_line, provenance, checkpoint_restart, ...):
// text and CSV files, a shell command line, the outcome of one run of the
// program (with or without mpiexec), runs side by side, error lines as they
// read on every machine, and a list of checks made after every run has
// printed what it found.

#include "test_tools.h"

#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#ifndef DYNAMIC_CONTACT_EXECUTABLE
#  error "tests/CMakeLists.txt must define DYNAMIC_CONTACT_EXECUTABLE"
#endif

namespace program_tools
{
  namespace fs = std::filesystem;

  using test_tools::lines_of;
  using test_tools::read_csv;
  using test_tools::read_text;
  using test_tools::split;
  using test_tools::trim;
  using test_tools::write_text;

  /** One argument for sh, in single quotes. */
  inline std::string
  quote(const std::string &s)
  {
    std::string q = "'";
    for (const char c : s)
      q += (c == '\'' ? std::string("'\\''") : std::string(1, c));
    return q + "'";
  }

  inline std::string
  yes_no(const bool b)
  {
    return b ? "yes" : "no";
  }

  /** How one run of the program ended, and what it printed. */
  struct Outcome
  {
    int         status = -1; // of std::system
    bool        exited = false;
    int         code   = -1; // exit code if exited
    int         signal = 0;  // the signal that ended it, if any
    std::string out, err;

    bool
    succeeded() const
    {
      return status != -1 && exited && code == 0;
    }
  };

  /** How to run the program. */
  struct Launch
  {
    /** Working directory (created if missing; "" for the current one). */
    fs::path directory = "";
    /** stdout and stderr go to NAME.stdout and NAME.stderr there. */
    std::string name = "run";
    /** Environment variables "NAME=value" for this run only. */
    std::vector<std::string> environment = {};
    /** 0: the program itself; N > 0: under mpiexec with N processes. */
    unsigned int processes = 0;
    /** With processes > 1 and this build's program: every process takes
     *  part (Solver/Minimum DoFs per process = 0; the tests' scenes are
     *  small, and they test the parallel code). */
    bool every_process = true;
    /** What to run: this build's dynamic-contact unless told otherwise (a
     *  script that runs it in turn). */
    std::string program = DYNAMIC_CONTACT_EXECUTABLE;
    /** If > 0: end the run (SIGTERM, SIGKILL 10 s later) after this many
     *  seconds, so that a hang fails the test instead of stalling it (exit
     *  code 124 of timeout(1)). */
    unsigned int timeout = 0;
  };

  /**
   * Run the executable of this build (or launch.program) with @p arguments,
   * stdin empty. Without
   * mpiexec the program is exec'ed by the shell, so a signal that ends it is
   * seen as such (not as the exit code 128 + N of a shell around it).
   */
  inline Outcome
  execute(const std::vector<std::string> &arguments, const Launch &launch = {})
  {
    std::string command;
    if (!launch.directory.empty())
      {
        fs::create_directories(launch.directory);
        command += "cd " + quote(launch.directory.string()) + " && ";
      }
    // The program is a process of its own: OpenMPI refuses root there
    // unless told (containers and CI run as root). Set for the child only
    // (runs may be started from several threads).
    command += "exec ";
    if (launch.timeout > 0)
      command += "timeout -k 10 " + std::to_string(launch.timeout) + " ";
    command += "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";
    for (const auto &e : launch.environment)
      command += " " + quote(e);
#ifdef DYNAMIC_CONTACT_MPIEXEC
    if (launch.processes > 0)
      command += " " + quote(DYNAMIC_CONTACT_MPIEXEC) + " -n " +
                 std::to_string(launch.processes) +
                 " --allow-run-as-root --oversubscribe";
#else
    if (launch.processes > 0)
      test_tools::check(false,
                        "tests/CMakeLists.txt defines DYNAMIC_CONTACT_MPIEXEC");
#endif
    command += " " + quote(launch.program);
    for (const auto &a : arguments)
      command += " " + quote(a);
    if (launch.processes > 1 && launch.every_process &&
        launch.program == DYNAMIC_CONTACT_EXECUTABLE)
      command += " --set 'Solver/Minimum DoFs per process=0'";
    command += " </dev/null >" + quote(launch.name + ".stdout") + " 2>" +
               quote(launch.name + ".stderr");

    Outcome o;
    o.status = std::system(command.c_str());
    if (o.status != -1)
      {
        o.exited = WIFEXITED(o.status);
        o.code   = o.exited ? WEXITSTATUS(o.status) : -1;
        o.signal = WIFSIGNALED(o.status) ? WTERMSIG(o.status) : 0;
      }
    o.out = read_text(launch.directory / (launch.name + ".stdout"));
    o.err = read_text(launch.directory / (launch.name + ".stderr"));
    return o;
  }


  /** One run of the program: its arguments, the NAME of its NAME.stdout and
   *  NAME.stderr, and (once executed) its outcome. */
  struct Run : Outcome
  {
    Run(const std::vector<std::string> &arguments, const std::string &name)
      : arguments(arguments)
      , name(name)
    {}

    std::vector<std::string> arguments;
    std::string              name;
  };

  /**
   * Call @p f(i) for i = 0, ..., @p n - 1 on @p workers threads, each taking
   * the next i as soon as it is done with one.
   */
  template <typename F>
  inline void
  in_parallel(const unsigned int n, const unsigned int workers, const F &f)
  {
    std::atomic<unsigned int> next(0);
    std::vector<std::thread>  threads;
    for (unsigned int w = 0; w < workers; ++w)
      threads.emplace_back([&]() {
        for (unsigned int i = next++; i < n; i = next++)
          f(i);
      });
    for (auto &t : threads)
      t.join();
  }

  /**
   * Execute @p runs side by side, in the current directory (most of a run
   * is MPI's start-up, spent waiting), each ended after @p timeout seconds.
   */
  inline void
  execute_all(const std::vector<Run *> &runs, const unsigned int timeout = 300)
  {
    in_parallel(runs.size(), runs.size(), [&](const unsigned int i) {
      Launch launch;
      launch.name                      = runs[i]->name;
      launch.timeout                   = timeout;
      static_cast<Outcome &>(*runs[i]) = execute(runs[i]->arguments, launch);
    });
  }

  /** The same for every run of @p runs. */
  inline void
  execute_all(std::vector<Run> &runs, const unsigned int timeout = 300)
  {
    std::vector<Run *> all;
    for (auto &r : runs)
      all.push_back(&r);
    execute_all(all, timeout);
  }

  /**
   * Run the script benchmarks/@p script with @p arguments (python3, with
   * $DYNAMIC_CONTACT this build's program); its output goes to
   * @p name.stdout and @p name.stderr.
   */
  inline Outcome
  run_benchmark_script(const std::string              &script,
                       const std::vector<std::string> &arguments,
                       const std::string              &name)
  {
    Launch launch;
    launch.name                      = name;
    launch.program                   = "python3";
    launch.environment               = {std::string("DYNAMIC_CONTACT=") +
                                        DYNAMIC_CONTACT_EXECUTABLE};
    std::vector<std::string> command = {std::string(REPOSITORY_DIR) +
                                        "/benchmarks/" + script};
    command.insert(command.end(), arguments.begin(), arguments.end());
    return execute(command, launch);
  }

  /** The names the output manifest of @p directory lists. */
  inline std::set<std::string>
  manifest(const fs::path &directory)
  {
    std::set<std::string> names;
    for (const auto &line : lines_of(read_text(directory / ".dynamic-contact")))
      if (!trim(line).empty() && trim(line)[0] != '#')
        names.insert(trim(line));
    return names;
  }

  /**
   * Every regular file under @p directory with its content, by relative
   * path, without the lock (every run takes it and writes its process
   * into it); empty if the directory does not exist.
   */
  inline std::map<std::string, std::string>
  snapshot(const fs::path &directory)
  {
    std::map<std::string, std::string> files;
    if (!fs::exists(directory))
      return files;
    for (const auto &e : fs::recursive_directory_iterator(directory))
      if (e.is_regular_file() && e.path().filename() != ".dynamic-contact.lock")
        files[fs::relative(e.path(), directory).string()] = read_text(e.path());
    return files;
  }

  /**
   * The settings that keep a run's screen output deterministic (no progress
   * lines, no timings, no iteration counts), as command-line arguments.
   */
  inline const std::vector<std::string> quiet = {
    "--set",
    "Output/Progress every=0",
    "--set",
    "Output/Print timings=false",
    "--set",
    "Output/Print iteration counts=false"};

  /** @p a followed by @p more. */
  inline std::vector<std::string>
  with(std::vector<std::string> a, const std::vector<std::string> &more)
  {
    a.insert(a.end(), more.begin(), more.end());
    return a;
  }

  /**
   * @p text without the directories of its absolute paths: an error line as
   * it reads on every machine.
   */
  inline std::string
  without_directories(const std::string &text)
  {
    static const std::regex path(R"((^|[\s'"<(])/(?:[^\s'"<>()]*/)?)");
    return std::regex_replace(text, path, "$1");
  }

  /** The error lines of a run's stderr. */
  inline std::vector<std::string>
  error_lines(const Outcome &o)
  {
    std::vector<std::string> lines;
    for (const auto &l : lines_of(o.err))
      if (l.rfind("dynamic-contact: error:", 0) == 0)
        lines.push_back(l);
    return lines;
  }

  /**
   * The columns of time_series.csv in which @p b differs from @p a in the
   * rows of steps up to @p last_step ("shape" if the steps differ); with
   * @p tolerance > 0 numbers may differ by that fraction of their column's
   * largest magnitude; work counters are never compared.
   */
  inline std::set<std::string>
  differing_columns(const fs::path    &a_dir,
                    const fs::path    &b_dir,
                    const unsigned int last_step,
                    const double       tolerance)
  {
    const std::set<std::string> work     = {"newton_iterations",
                                            "convexification_iterations",
                                            "factorizations",
                                            "active_set_cycles",
                                            "line_search_steps"};
    const std::set<std::string> roundoff = {"coefficient_residual",
                                            "energy_balance_defect",
                                            "relative_energy_defect",
                                            "relative_min_dissipation"};
    const auto                  a        = read_csv(a_dir / "time_series.csv");
    const auto                  b        = read_csv(b_dir / "time_series.csv");
    if (a.size() < last_step + 2 || b.size() < last_step + 2 || a[0] != b[0])
      return {"shape"};
    std::set<std::string> differ;
    for (unsigned int c = 0; c < a[0].size(); ++c)
      {
        const std::string &name = a[0][c];
        if (work.count(name) || (tolerance > 0 && roundoff.count(name)))
          continue;
        double scale = 0;
        for (unsigned int r = 1; r <= last_step + 1; ++r)
          scale = std::max(scale, std::abs(std::stod(a[r][c])));
        for (unsigned int r = 1; r <= last_step + 1; ++r)
          if (a[r][c] != b[r][c] &&
              !(tolerance > 0 &&
                std::abs(std::stod(a[r][c]) - std::stod(b[r][c])) <=
                  tolerance * scale))
            differ.insert(name);
      }
    return differ;
  }

  /** "a, b, c", or "none". */
  inline std::string
  join(const std::set<std::string> &s)
  {
    std::string list;
    for (const auto &x : s)
      list += (list.empty() ? "" : ", ") + x;
    return list.empty() ? "none" : list;
  }

  /**
   * Checks collected while the runs print what they found, and made at the
   * end, so that a failing test still shows the whole picture.
   */
  struct Checks
  {
    std::vector<std::pair<bool, std::string>> list;

    void
    add(const bool condition, const std::string &what)
    {
      list.emplace_back(condition, what);
    }

    void
    assert_all() const
    {
      for (const auto &[ok, what] : list)
        if (!ok)
          std::cerr << "FAILED: " << what << std::endl;
      for (const auto &[ok, what] : list)
        test_tools::check(ok, what);
    }
  };
} // namespace program_tools

#endif
