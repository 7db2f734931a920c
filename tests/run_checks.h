#ifndef dynamic_contact_tests_run_checks_h
#define dynamic_contact_tests_run_checks_h

// Shared helpers of the tests that run the program and judge what a run left
// behind (checkpoint_restart, gmsh_mesh, output_safety, resume_safety,
// screen_output, signals), on top of program_tools.h: command lines, how to
// launch a run, its run_status and error lines, CSV columns, and a verdict
// printed and checked in one go.

#include "program_tools.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace run_checks
{
  namespace fs = std::filesystem;

  /** "--set" before each "Section/Entry=value" of @p settings. */
  inline std::vector<std::string>
  overrides(const std::vector<std::string> &settings)
  {
    std::vector<std::string> arguments;
    for (const auto &s : settings)
      {
        arguments.push_back("--set");
        arguments.push_back(s);
      }
    return arguments;
  }

  /**
   * A run's launch: its NAME.stdout and NAME.stderr, @p processes (0: the
   * program itself), ended after @p timeout seconds (0: never), with the
   * variables "NAME=value" of @p environment.
   */
  inline program_tools::Launch
  launch_of(const std::string              &name,
            const unsigned int              processes   = 0,
            const unsigned int              timeout     = 0,
            const std::vector<std::string> &environment = {})
  {
    program_tools::Launch launch;
    launch.name        = name;
    launch.processes   = processes;
    launch.timeout     = timeout;
    launch.environment = environment;
    return launch;
  }

  /** The run_status of the results in @p directory. */
  inline std::string
  run_status(const fs::path &directory)
  {
    return program_tools::trim(
      program_tools::read_text(directory / "run_status"));
  }

  /** The first error line of a run, or "(none)". */
  inline std::string
  first_error(const program_tools::Outcome &o)
  {
    const auto lines = program_tools::error_lines(o);
    return lines.empty() ? "(none)" : lines[0];
  }

  /** "1 process" (also for 0: the program itself) or "N processes". */
  inline std::string
  processes_text(const unsigned int processes)
  {
    return std::to_string(std::max(processes, 1u)) + " process" +
           (processes > 1 ? "es" : "");
  }

  /** Whether @p lines is a single line that contains each of @p words. */
  inline bool
  one_line_naming(const std::vector<std::string> &lines,
                  const std::vector<std::string> &words)
  {
    bool names = lines.size() == 1;
    for (const auto &w : words)
      names = names && lines[0].find(w) != std::string::npos;
    return names;
  }

  /** The index of the column @p name of a CSV @p header (its size if none). */
  inline std::size_t
  column(const std::vector<std::string> &header, const std::string &name)
  {
    return std::find(header.begin(), header.end(), name) - header.begin();
  }

  /** Print "@p printed: yes" (or no) and add the check @p what. */
  inline void
  verdict(program_tools::Checks &checks,
          const bool             ok,
          const std::string     &printed,
          const std::string     &what)
  {
    test_tools::out() << printed << ": " << program_tools::yes_no(ok)
                      << std::endl;
    checks.add(ok, what);
  }

  /**
   * The small paper scene for 16 steps with a checkpoint every 4 (the newest
   * @p keep kept), quiet, its results in @p directory; then @p more.
   */
  inline std::vector<std::string>
  sixteen_steps(const std::string              &directory,
                const unsigned int              keep,
                const std::vector<std::string> &more = {})
  {
    using program_tools::with;
    return with(with(with({test_tools::scene("barboteu_danan_2016_small.prm")},
                          overrides(
                            {"Time/End time=0.125",
                             "Checkpoint/Every=4",
                             "Checkpoint/Keep=" + std::to_string(keep)})),
                     program_tools::quiet),
                with(overrides({"Output/Directory=" + directory}), more));
  }

  /**
   * Compare two CSV files of the same shape. Columns in @p skipped are not
   * compared. With tolerance 0 the other entries must be equal as text;
   * otherwise numbers may differ by tolerance times the largest magnitude in
   * their column (text entries must be equal). Returns the columns that
   * differ ("shape" if the header or the number of rows differs).
   */
  inline std::set<std::string>
  differing_csv_columns(const fs::path              &a_file,
                        const fs::path              &b_file,
                        const double                 tolerance,
                        const std::set<std::string> &skipped = {})
  {
    const auto a = program_tools::read_csv(a_file);
    const auto b = program_tools::read_csv(b_file);
    if (a.empty() || a.size() != b.size() || a[0] != b[0])
      return {"shape"};
    const auto           &header = a[0];
    std::set<std::string> differ;
    for (unsigned int c = 0; c < header.size(); ++c)
      {
        if (skipped.count(header[c]) > 0)
          continue;
        double scale = 0;
        for (unsigned int r = 1; r < a.size(); ++r)
          {
            if (a[r].size() != header.size() || b[r].size() != header.size())
              return {"shape"};
            try
              {
                scale = std::max(scale, std::abs(std::stod(a[r][c])));
              }
            catch (const std::exception &)
              {}
          }
        for (unsigned int r = 1; r < a.size(); ++r)
          {
            if (a[r][c] == b[r][c])
              continue;
            bool close = false;
            if (tolerance > 0)
              try
                {
                  close = std::abs(std::stod(a[r][c]) - std::stod(b[r][c])) <=
                          tolerance * scale;
                }
              catch (const std::exception &)
                {}
            if (!close)
              differ.insert(header[c]);
          }
      }
    return differ;
  }
} // namespace run_checks

#endif
