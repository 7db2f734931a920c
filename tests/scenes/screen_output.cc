// What a run prints (issue 12): the end summary agrees with
// time_series.csv (steps, cut-backs, the largest relative energy defect and
// the largest friction-law residual of a step), the timer sections are
// disjoint (the rows of the table add up to the total, which is the wall
// time), the progress lines give an estimate of the time left, and
// Output/Print timings = false leaves out the times only and Output/Print
// iteration counts = false the iteration counts (both differ from run to
// run on several processes): the summary stays. The scene:
// prm/stress/critical_speed.prm at the size of the stress suite's quick mode
// (the load at the critical speed: the time step is cut back several times), 1
// ms of it.
//
// Only verdicts are printed (no times, no counts): the output compares on
// every machine.

#include "run_checks.h"

#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace program_tools;
using namespace run_checks;

namespace
{
  using Table = std::vector<std::vector<std::string>>;

  Outcome
  run(const std::string &directory, const bool timings, const bool counts)
  {
    return execute(with({test_tools::scene("stress/critical_speed.prm")},
                        overrides(
                          {"Output/Directory=" + directory,
                           "Geometry/Repetitions=32, 8",
                           "Output/Output every=0",
                           "Output/Progress every=50",
                           "Output/VTU every=100",
                           std::string("Output/Print timings=") +
                             (timings ? "true" : "false"),
                           std::string("Output/Print iteration counts=") +
                             (counts ? "true" : "false")})),
                   launch_of(directory, 0, 300));
  }

  /** The number after @p label in @p text (NaN if absent). */
  double
  number_after(const std::string &text, const std::string &label)
  {
    const auto at = text.find(label);
    if (at == std::string::npos)
      return std::nan("");
    return std::strtod(text.c_str() + at + label.size(), nullptr);
  }

  double
  column_max(const Table &csv, const std::string &name, const bool sum = false)
  {
    const auto c      = column(csv[0], name);
    double     result = 0;
    for (unsigned int r = 2; r < csv.size(); ++r) // after row 0
      {
        const double x = std::stod(csv[r][c]);
        result         = sum ? result + x : std::max(result, x);
      }
    return result;
  }

  /** Print "@p what: yes" (or no) and check it. */
  void
  say(Checks &checks, const bool ok, const std::string &what)
  {
    verdict(checks, ok, what, what);
  }

  /** The summary of the run @p out against its time_series.csv @p csv. */
  void
  check_summary(const std::string &out, const Table &csv, Checks &checks)
  {
    const double steps = csv.size() - 2; // header, row 0
    say(checks,
        number_after(out, "Completed ") == steps,
        "summary: the number of steps");
    const double cutbacks = column_max(csv, "cutbacks", true);
    say(checks,
        cutbacks > 0 && number_after(out, "time step cut-backs: ") == cutbacks,
        "summary: the cut-backs (their sum in time_series.csv, > 0)");
    say(checks,
        out.find("steps kept with an unconverged convexification loop: 0") !=
          std::string::npos,
        "summary: no step kept with an unconverged convexification loop");
    say(checks,
        out.find("Summary: results in timed/") != std::string::npos,
        "summary: the output directory");
    // The largest of a column, to 3 digits: the label, the column, the check.
    struct Largest
    {
      std::string label, name, what;
    };
    for (const auto &l : std::vector<Largest>{
           {"largest relative energy balance defect: ",
            "relative_energy_defect",
            "summary: the largest relative energy defect (to 3 digits)"},
           {"largest friction-law residual max |mu_i - mu(|w_tau,i|)|: ",
            "coefficient_residual",
            "summary: the largest friction-law residual (to 3 digits)"}})
      say(checks,
          test_tools::close(number_after(out, l.label),
                            column_max(csv, l.name),
                            0.01),
          l.what);
  }

  /** The table of timer sections: disjoint, adding up to the wall time. */
  void
  check_timer_table(const std::string &out, Checks &checks)
  {
    static const std::regex row(
      R"(^  (.+?)\s+(\d*)\s+([0-9.]+) s\s+([0-9.]+) %$)");
    double       sum = 0, total = -1, shares = 0;
    unsigned int sections = 0;
    bool         in_table = false;
    for (const auto &line : lines_of(out))
      {
        if (line.rfind("Timings (wall clock", 0) == 0)
          in_table = true;
        std::smatch m;
        if (!in_table || !std::regex_match(line, m, row))
          continue;
        const double t = std::stod(m[3].str());
        if (m[1].str() == "total")
          total = t;
        else
          {
            sum += t;
            shares += std::stod(m[4].str());
            sections += m[2].str().empty() ? 0 : 1;
          }
      }
    say(checks, sections >= 8, "the timer table lists the sections");
    // Each row is rounded to 0.01 s and 0.1 %.
    say(checks,
        total > 0 && std::abs(sum - total) <= 0.005 * (sections + 1) + 1e-9,
        "the rows of the timer table add up to the total");
    say(checks,
        std::abs(shares - 100) <= 0.05 * (sections + 1),
        "the shares of the timer table add up to 100 %");
    const double wall = number_after(out, "wall time: ");
    say(checks,
        std::abs(wall - total) <= 0.05 + 0.01 * wall,
        "the total of the table is the wall time of the run");
  }

  /**
   * Progress lines: the time left with timings, Newton counts in both; the
   * summary without timings.
   */
  void
  check_progress_lines(const std::string &timed,
                       const std::string &counts,
                       const std::string &quiet,
                       Checks            &checks)
  {
    say(checks,
        std::regex_search(
          timed, std::regex(R"(Newton \d+ .*\([0-9.]+ s, ~[0-9.]+ s left\))")),
        "with timings: the progress lines give the time left");
    say(checks,
        std::regex_search(
          counts, std::regex(R"(step .* Newton \d+ .* contact \d+ )")) &&
          counts.find(" left)") == std::string::npos &&
          counts.find(" Newton iterations (mean ") != std::string::npos,
        "without timings, with iteration counts: progress lines and the "
        "summary with the counts, without times");
    say(checks,
        std::regex_search(quiet, std::regex(R"(step .* contact \d+ )")) &&
          !std::regex_search(quiet, std::regex(R"(Newton \d)")) &&
          quiet.find(" Newton iterations") == std::string::npos &&
          quiet.find(" left)") == std::string::npos,
        "without timings and iteration counts: progress lines without times "
        "and counts");
    say(checks,
        quiet.find("Summary: results in quiet/") != std::string::npos &&
          quiet.find("time step cut-backs: ") != std::string::npos &&
          quiet.find("Timings") == std::string::npos &&
          quiet.find("wall time") == std::string::npos &&
          counts.find("Timings") == std::string::npos &&
          counts.find("wall time") == std::string::npos,
        "without timings: the summary, no timer table, no wall time");
  }
} // namespace


int
main()
{
  Checks checks;

  const Outcome timed  = run("timed", true, true);
  const Outcome counts = run("counts", false, true);
  const Outcome quiet  = run("quiet", false, false);
  say(checks,
      timed.succeeded() && counts.succeeded() && quiet.succeeded(),
      "the three runs complete");
  const auto csv = test_tools::read_csv(fs::path("timed") / "time_series.csv");
  say(checks, csv.size() > 3, "time_series.csv has rows");
  if (csv.size() <= 3)
    {
      checks.assert_all();
      return 1;
    }

  check_summary(timed.out, csv, checks);
  check_timer_table(timed.out, checks);
  check_progress_lines(timed.out, counts.out, quiet.out, checks);

  checks.assert_all();
  return 0;
}
