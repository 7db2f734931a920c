// Bad input to the real executable: every case starts from the valid scene
// prm/pressed_block.prm and changes one thing (or passes a wrong command
// line), runs the dynamic-contact executable of this build in a directory
// of its own, and checks what a user sees:
//   - a normal exit (no signal, no abort) with code 1 (input error) or 2
//     (usage error),
//   - exactly one line "dynamic-contact: error: ..." on stderr, that names
//     the parameter (as Section/Entry) or the file, and nothing else on
//     stderr (besides the usage text after a usage error),
//   - no output directory (input errors are found before it is created),
//     in particular no run_status "completed"; an error found only while
//     running (Newton iterations exhausted) leaves run_status "failed: ...".
// Two control cases (the unchanged scene, an empty file with all defaults)
// must run to completion, so that the checks can tell success from failure.
// Issue 11 added: non-finite loads, initial conditions and friction laws
// (each named before anything is written; a load that becomes NaN at a time
// between the sampled ones stops the run with the last good state), a
// velocity-strengthening law, scenes too large for the machine, parameter
// files that include themselves, a directory and a named pipe as parameter
// file, and a UTF-8 byte order mark (a control: tolerated). No case may
// leave "nan" or "inf" in a CSV file. Issue 12 added Gmsh meshes of
// triangles and tetrahedra (refused with how to recombine them), a binary
// mesh file, and names of physical groups in the boundary lists (a control,
// an unknown name, a name with the rectangle).
//
// The cases are tables, a function per group, in bad_input_cases.h; every
// case runs first and prints one line; the checks follow, so that a failing
// test still shows what every case did.

#include "bad_input_cases.h"
#include "program_tools.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;
  using namespace bad_input_cases;

  const std::string error_prefix = "dynamic-contact: error:";

  /**
   * An error line as it compares on every machine and after changes to the
   * solver or to the comments of prm/pressed_block.prm: absolute paths
   * replaced by their file names, a Newton residual by "...", and the line
   * number of the changed line by a description.
   */
  std::string
  deterministic(const std::string &text, const unsigned int changed_line)
  {
    static const std::regex residual(R"(relative residual [-+.0-9eE]+)");
    // The memory of the machine that runs the test.
    static const std::regex memory(
      R"(and [0-9.e+]+ GB are available on the [0-9]+ hosts?)");
    std::string result = without_directories(text);
    result = std::regex_replace(result, residual, "relative residual ...");
    result = std::regex_replace(result,
                                memory,
                                "and ... GB are available on the hosts");
    if (changed_line > 0)
      {
        const std::string line = "line " + std::to_string(changed_line) + ":";
        const auto        position = result.find(line);
        if (position != std::string::npos)
          result.replace(position, line.size(), "line (the changed line):");
      }
    return result;
  }

  /** A run of the program and what it left behind. */
  struct Result : Outcome
  {
    std::vector<std::string> error_lines;
    bool                     stderr_only_message = false;
    std::vector<std::string> new_directories;
    std::vector<std::string> completed_status_files;
    std::vector<std::string> failed_status_files;
    std::vector<std::string> non_finite_files;
  };

  /** The files of case @p c in a new @p directory. */
  void
  prepare(const Case &c, const fs::path &directory)
  {
    fs::remove_all(directory);
    fs::create_directories(directory);
    if (c.prm)
      write_text(directory / "scene.prm", *c.prm);
    for (const auto &[name, text] : c.extra_files)
      write_text(directory / name, text);
    if (!c.fifo.empty() && ::mkfifo((directory / c.fifo).c_str(), 0644) != 0)
      {
        std::cerr << "FAILED: cannot make the named pipe " << c.fifo
                  << std::endl;
        std::exit(1);
      }
  }

  /** The directories, run_status files and CSV files a run left behind. */
  void
  inspect(const fs::path &directory, Result &o)
  {
    for (const auto &entry : fs::recursive_directory_iterator(directory))
      {
        const std::string relative =
          fs::relative(entry.path(), directory).string();
        if (entry.is_directory() && relative.find('/') == std::string::npos)
          o.new_directories.push_back(relative);
        if (entry.path().extension() == ".csv")
          {
            std::string text = read_text(entry.path());
            std::transform(text.begin(), text.end(), text.begin(), ::tolower);
            if (text.find("nan") != std::string::npos ||
                text.find("inf") != std::string::npos)
              o.non_finite_files.push_back(relative);
          }
        if (entry.path().filename() == "run_status")
          {
            const std::string status = read_text(entry.path());
            if (status.rfind("completed", 0) == 0)
              o.completed_status_files.push_back(relative);
            if (status.rfind("failed: ", 0) == 0)
              o.failed_status_files.push_back(relative);
          }
      }
    std::sort(o.new_directories.begin(), o.new_directories.end());
  }

  Result
  run_case(const Case &c, const fs::path &directory)
  {
    prepare(c, directory);
    Launch launch;
    launch.directory = directory;
    launch.name      = "program";
    launch.timeout   = 120; // a pipe must not block the program
    Result o;
    static_cast<Outcome &>(o) = execute(c.arguments, launch);
    o.error_lines             = program_tools::error_lines(o);

    // Only the message; after a usage error the usage text may follow it.
    const auto lines = lines_of(o.err);
    if (c.expected_code == 0)
      o.stderr_only_message = o.err.empty();
    else if (!lines.empty() && lines[0].rfind(error_prefix, 0) == 0)
      {
        const std::string rest =
          o.err.substr(std::min(lines[0].size() + 1, o.err.size()));
        o.stderr_only_message =
          rest.empty() ||
          (c.expected_code == 2 && rest.rfind("\nUsage: ", 0) == 0);
      }
    inspect(directory, o);
    return o;
  }

  /** One line per case, the same on every machine. */
  std::string
  summary(const Case &c, const Result &o)
  {
    const std::string name = c.name + " | ";
    if (c.expected_code == 0)
      return name +
             "control, exit code zero: " + yes_no(o.exited && o.code == 0) +
             " | run_status completed: " +
             yes_no(o.completed_status_files.size() == 1);

    const unsigned int line = c.line_number();
    std::string        summary =
      name + "exit code nonzero: " + yes_no(o.exited && o.code != 0) +
      " | one error line: " + yes_no(o.error_lines.size() == 1);
    for (const auto &e : o.error_lines)
      summary += " | " + deterministic(e, line);
    if (o.error_lines.empty() && !o.err.empty())
      summary +=
        " | first line on stderr: " + deterministic(lines_of(o.err)[0], line);
    return summary;
  }

  /** The checks of a case that must fail with an error message. */
  void
  check_error(Checks &checks, const Case &c, const Result &o)
  {
    const std::string  name = c.name + ": ";
    const unsigned int line = c.line_number();
    checks.add(o.error_lines.size() == 1,
               name + "exactly one line '" + error_prefix + " ...' on stderr");
    for (const auto &n : c.names)
      checks.add(o.error_lines.size() == 1 &&
                   o.error_lines[0].find(n) != std::string::npos,
                 name + "the error line names '" + n + "'");
    if (!c.line_of.empty())
      checks.add(line > 0 && o.error_lines.size() == 1 &&
                   o.error_lines[0].find("line " + std::to_string(line) +
                                         ":") != std::string::npos,
                 name + "the error line gives the number of the line '" +
                   c.line_of + "'");
    checks.add(o.stderr_only_message,
               name + "stderr holds the error line only" +
                 (c.expected_code == 2 ? " (and the usage text)" : ""));
    if (c.runtime)
      checks.add(o.failed_status_files.size() == 1,
                 name + "run_status reads 'failed: ...'");
    else
      checks.add(o.new_directories.empty(),
                 name + "no output directory created");
    checks.add(o.completed_status_files.empty(),
               name + "no run_status 'completed' left");
  }

  /** The checks of a case: a control runs, any other fails as expected. */
  void
  check_case(Checks &checks, const Case &c, const Result &o)
  {
    const std::string name = c.name + ": ";
    checks.add(o.status != -1 && o.exited,
               name + "a normal exit (no signal, no abort)" +
                 (o.signal != 0 ? " [signal " + std::to_string(o.signal) + "]" :
                                  ""));
    checks.add(o.code == c.expected_code,
               name + "exit code " + std::to_string(c.expected_code) +
                 (o.code != c.expected_code ?
                    " [got " + std::to_string(o.code) + "]" :
                    ""));
    if (c.expected_code == 0)
      {
        checks.add(o.error_lines.empty() && o.stderr_only_message,
                   name + "nothing on stderr");
        checks.add(o.completed_status_files.size() == 1,
                   name + "run_status reads 'completed'");
      }
    else
      check_error(checks, c, o);
    checks.add(o.non_finite_files.empty(),
               name + "no 'nan' or 'inf' in a CSV file");
  }
} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  test_tools::check(scene().find("subsection Material") != std::string::npos,
                    "read prm/pressed_block.prm");

  std::vector<Case> cases;
  for (const auto group : {file_cases,
                           value_cases,
                           mesh_cases,
                           running_cases,
                           layout_cases,
                           parameter_file_cases,
                           command_line_cases})
    {
      const auto more = group();
      cases.insert(cases.end(), more.begin(), more.end());
    }

  // Most of a run is MPI's start-up, spent waiting: run a few at a time.
  std::vector<Result> outcomes(cases.size());
  in_parallel(cases.size(), 6, [&](const unsigned int i) {
    outcomes[i] = run_case(cases[i], fs::path("case_" + cases[i].name));
  });

  Checks checks;
  for (unsigned int i = 0; i < cases.size(); ++i)
    {
      test_tools::out() << summary(cases[i], outcomes[i]) << std::endl;
      check_case(checks, cases[i], outcomes[i]);
    }
  test_tools::out() << std::endl;
  checks.assert_all();
  return 0;
}
