// Provenance and input formats of the real executable (issue 12):
//   - every output directory holds parameters.prm and parameters.json (the
//     parameters with the --set overrides applied) and log.txt (the screen
//     output, with a line naming the version, deal.II, the processes and
//     the start time), all three in the manifest; run again from either
//     parameter file into another directory, the program writes the same
//     time_series.csv, byte for byte;
//   - after --resume, log.txt goes on (a new section), the first part kept;
//   - a scene in JSON or XML (as --print-parameters=json|xml writes it)
//     runs and gives the same time_series.csv as the PRM scene; a
//     hand-written short JSON scene too; bad JSON/XML files give one clear
//     error naming the file (empty, no parameter set, unknown entry, bad
//     value, not JSON at all, missing);
//   - --validate: exit 0 and nothing written for a good scene; for a bad
//     one (unassigned boundary id, broken expression, missing mesh file,
//     an initial condition that is not finite) exit 1 with exactly the
//     error line the run itself stops with, and nothing written either;
//   - doc/parameters.md is what --print-parameters=markdown prints (the
//     test fails while the committed file is stale).
//
// Every run happens first and prints what it found; the checks follow.

#include "program_tools.h"

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;

  std::string
  first_error(const Outcome &o)
  {
    const auto lines = error_lines(o);
    return lines.empty() ? "<none>" : without_directories(lines[0]);
  }

  const std::regex provenance_line(
    R"(  dynamic-contact [0-9][^ ]* \(git [^ )]+\), deal\.II [0-9.]+, 1 MPI process, started [0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z)");
  const std::regex plan_line(R"(  solver plan: (condensed|assembled).*)");

  /** @p text with every line ended by a newline. */
  std::string
  ended_lines(const std::string &text)
  {
    std::string ended;
    for (const auto &line : lines_of(text))
      ended += line + "\n";
    return ended;
  }

  const std::string scene = test_tools::scene("pressed_block.prm");

  /**
   * The scene of every comparison: @p arguments with the overrides of
   * pressed_block.prm, its results in @p directory.
   */
  std::vector<std::string>
  compared(const std::vector<std::string> &arguments,
           const std::string              &directory)
  {
    return with(arguments,
                {"--set",
                 "Time/End time=3",
                 "--set",
                 "Material/Density=2000",
                 "--set",
                 "Output/Print timings=false",
                 "--set",
                 "Output/Print iteration counts=false",
                 "--set",
                 "Output/Directory=" + directory});
  }

  // A JSON scene written by hand: the values only (pressed_block.prm).
  const std::string short_json = R"({
  "Dimension": "2",
  "Geometry": {"Lower left": "0, 0", "Upper right": "1, 0.5",
               "Repetitions": "4, 2"},
  "Boundary conditions": {
    "Clamped": "", "Roller": "0, 1", "Contact": "2", "Traction": "3",
    "Traction function": {"Function constants": "P=1e7",
                          "Function expression": "0; -P"}},
  "Material": {"Density": "2000", "Young modulus": "1e9",
               "Poisson ratio": "0.3"},
  "Foundation": {
    "Normal compliance": {"Capped ramp": {"Stiffness": "1e10"}},
    "Normal damping": {"Capped ramp": {"Coefficient": "1e8"}}},
  "Time": {"End time": "3", "Time step": "1"},
  "Output": {"Directory": "from_short_json", "VTU every": "0",
             "Print timings": "false",
             "Print iteration counts": "false"}
}
)";

  /** Bad JSON and XML files: bad/FILE holds CONTENT (json_missing: none). */
  struct BadFile
  {
    std::string name, file, content, must_contain;
  };
  const std::vector<BadFile> bad_files = {
    {"json_empty", "empty.json", "", "is empty: it sets no parameter"},
    {"json_no_value",
     "nothing.json",
     "{ }\n",
     "is empty: it sets no parameter"},
    {"json_unknown",
     "unknown.json",
     R"({"Material": {"Densty": "1000"}})",
     "Densty"},
    {"json_bad_value",
     "bad_value.json",
     R"({"Material": {"Density": "heavy"}})",
     "Density = 'heavy' is not a number"},
    {"json_not_json", "broken.json", "{\"Material\": ", "is not valid JSON"},
    {"xml_unknown",
     "unknown.xml",
     "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<ParameterHandler>"
     "<Materiall><Density><value>1</value></Density></Materiall>"
     "</ParameterHandler>\n",
     "Materiall"},
    {"json_missing", "missing.json", "", "Cannot open the parameter file"}};

  /** --validate, and the run itself, on good and bad scenes. */
  struct Validation
  {
    std::string              name;
    std::vector<std::string> sets;
    std::string              must_contain; // "" for the good scene
  };
  const std::vector<Validation> validations = {
    {"good", {}, ""},
    {"unassigned_id", {"Boundary conditions/Traction="}, "3"},
    {"broken_expression",
     {"Boundary conditions/Traction function/Function expression=0; -P*"},
     "Traction function"},
    {"missing_mesh",
     {"Geometry/Type=gmsh", "Geometry/Mesh file=no_such_mesh.msh"},
     "no_such_mesh.msh"},
    {"nan_initial",
     {"Initial conditions/Velocity/Function expression=0; sqrt(-1-x)"},
     "Initial conditions"}};

  /** The directories and files of an earlier run of this test. */
  void
  remove_earlier_results()
  {
    for (const std::string d : {"original",
                                "again_prm",
                                "again_json",
                                "from_json",
                                "from_xml",
                                "from_short_json",
                                "resumed",
                                "bad"})
      fs::remove_all(d);
    for (const auto &v : validations)
      {
        fs::remove_all("validate_" + v.name);
        fs::remove_all("run_" + v.name);
      }
    for (const std::string f : {"scene.json", "scene.xml", "short.json"})
      fs::remove(f);
  }

  /** Every run of the test; a later one may read what earlier ones wrote. */
  struct Runs
  {
    Run original{compared({scene}, "original"), "original"};
    Run print_json{compared({"--print-parameters=json", scene}, "from_json"),
                   "print_json"};
    Run print_xml{compared({"--print-parameters=xml", scene}, "from_xml"),
                  "print_xml"};
    Run markdown{{"--print-parameters=markdown"}, "markdown"};
    Run again_prm{{"original/parameters.prm",
                   "--set",
                   "Output/Directory=again_prm"},
                  "again_prm"};
    Run again_json{{"original/parameters.json",
                    "--set",
                    "Output/Directory=again_json"},
                   "again_json"};
    Run from_json{{"scene.json"}, "from_json"};
    Run from_xml{{"scene.xml"}, "from_xml"};
    Run from_short_json{{"short.json"}, "from_short_json"};
    // A run with checkpoints to t = 2, resumed to t = 3.
    Run first_part{
      with(compared({scene}, "resumed"),
           {"--set", "Checkpoint/Every=1", "--set", "Time/End time=2"}),
      "first_part"};
    Run second_part{with(compared({scene, "--resume"}, "resumed"),
                         {"--set", "Checkpoint/Every=1"}),
                    "second_part"};

    // The bad files, --validate, and the runs --validate is compared with.
    std::vector<Run> bad, validate, plain;

    void
    execute();
  };

  void
  Runs::execute()
  {
    execute_all({&original, &print_json, &print_xml, &markdown});
    write_text("scene.json", print_json.out);
    write_text("scene.xml", print_xml.out);
    write_text("short.json", short_json);
    execute_all({&again_prm,
                 &again_json,
                 &from_json,
                 &from_xml,
                 &from_short_json,
                 &first_part});
    execute_all({&second_part});

    fs::create_directories("bad");
    for (const auto &b : bad_files)
      {
        if (b.name != "json_missing")
          write_text(fs::path("bad") / b.file, b.content);
        bad.emplace_back(std::vector<std::string>{"bad/" + b.file}, b.name);
      }
    for (const auto &v : validations)
      {
        std::vector<std::string> arguments = {scene};
        for (const auto &s : v.sets)
          arguments.insert(arguments.end(), {"--set", s});
        arguments.insert(arguments.end(),
                         {"--set", "Output/Directory=validate_" + v.name});
        validate.emplace_back(with({"--validate"}, arguments),
                              "validate_" + v.name);
        arguments.back() = "Output/Directory=run_" + v.name;
        plain.emplace_back(arguments, "run_" + v.name);
      }
    std::vector<Run *> all;
    for (auto &r : bad)
      all.push_back(&r);
    for (auto &r : validate)
      all.push_back(&r);
    for (unsigned int i = 1; i < plain.size(); ++i)
      all.push_back(&plain[i]);
    execute_all(all);
  }

  /** parameters.prm, parameters.json and log.txt, in the manifest. */
  void
  check_provenance_files(Checks &checks)
  {
    std::ostream &out = test_tools::out();
    out << "provenance files:" << std::endl;
    const auto names = manifest("original");
    for (const std::string f : {"parameters.prm", "parameters.json", "log.txt"})
      {
        const bool exists = fs::is_regular_file(fs::path("original") / f);
        const bool listed = names.count(f) == 1;
        out << "  " << f << ": written " << yes_no(exists)
            << ", in the manifest " << yes_no(listed) << std::endl;
        checks.add(exists && listed, f + " written and in the manifest");
      }
    const std::string prm = read_text("original/parameters.prm");
    const bool        has_overrides =
      std::regex_search(prm, std::regex(R"(set Density\s*=\s*2000)")) &&
      std::regex_search(prm, std::regex(R"(set End time\s*=\s*3)"));
    out << "  parameters.prm has the --set values: " << yes_no(has_overrides)
        << std::endl;
    checks.add(has_overrides, "parameters.prm holds the --set values");
  }

  /**
   * log.txt: the screen output, one provenance line, the solver plan (which
   * contact solver, which factorization, why) and, at the end, the memory
   * table (what the run holds, part by part).
   */
  void
  check_log(Checks &checks, const Run &original)
  {
    const std::regex memory_header(
      R"(  memory \([0-9]+ DoFs on 1 processes\): MB in all, .*)");
    const std::regex memory_row(
      R"(    [a-zA-Z].* +[0-9.]+ +[0-9.]+ +[0-9]+(  \(measured\))?)");
    std::string  rest;
    unsigned int provenance_lines = 0, plan_lines = 0, memory_tables = 0,
                 memory_rows = 0;
    bool in_memory_table     = false;
    for (const auto &line : lines_of(read_text("original/log.txt")))
      if (std::regex_match(line, provenance_line))
        ++provenance_lines;
      else if (std::regex_match(line, plan_line))
        ++plan_lines;
      else if (std::regex_match(line, memory_header))
        {
          ++memory_tables;
          in_memory_table = true;
        }
      else if (in_memory_table && std::regex_match(line, memory_row))
        ++memory_rows;
      else
        {
          in_memory_table = false;
          rest += line + "\n";
        }
    const std::string screen = ended_lines(original.out);
    test_tools::out() << "  log.txt: " << provenance_lines
                      << " provenance line(s), " << plan_lines
                      << " solver plan line(s), " << memory_tables
                      << " memory table(s); the rest is the screen output: "
                      << yes_no(rest == screen) << std::endl;
    checks.add(original.succeeded(), "original: exit code 0");
    checks.add(provenance_lines == 1, "log.txt has one provenance line");
    checks.add(plan_lines == 1, "log.txt has the solver plan");
    // The mesh, the pattern, M, the two other bulk matrices, K0 and the
    // totals at least.
    checks.add(memory_tables == 1 && memory_rows >= 10,
               "log.txt ends with the memory table");
    checks.add(rest == screen && !screen.empty(),
               "log.txt is a copy of the screen output");
    checks.add(!std::regex_search(original.out, std::regex("started [0-9]")),
               "with Print timings = false the screen has no start time");
  }

  /**
   * Whether each of @p runs wrote the time_series.csv of the original run:
   * printed ("  NAME: exit CODE, PRINTED: yes") and checked (exit code 0 and
   * the same series: "NAME: WHAT").
   */
  void
  check_same_series(Checks                         &checks,
                    const std::vector<const Run *> &runs,
                    const std::string              &printed,
                    const std::string              &what)
  {
    const std::string series = read_text("original/time_series.csv");
    for (const Run *r : runs)
      {
        const bool same =
          read_text(fs::path(r->name) / "time_series.csv") == series;
        test_tools::out() << "  " << r->name << ": exit " << r->code << ", "
                          << printed << ": " << yes_no(same) << std::endl;
        checks.add(r->succeeded() && same, r->name + ": " + what);
      }
  }

  /** After --resume, log.txt goes on (a new section), the first part kept. */
  void
  check_resumed_log(Checks    &checks,
                    const Run &first_part,
                    const Run &second_part)
  {
    const std::string first_screen = ended_lines(first_part.out);
    std::string       log_without;
    unsigned int      resume_marks = 0;
    for (const auto &line : lines_of(read_text("resumed/log.txt")))
      {
        resume_marks += (line == "==== --resume ====");
        if (!std::regex_match(line, provenance_line) &&
            !std::regex_match(line, plan_line))
          log_without += line + "\n";
      }
    const bool kept    = log_without.rfind(first_screen, 0) == 0;
    const bool goes_on = log_without.find(second_part.out) != std::string::npos;
    test_tools::out() << "  --resume: log.txt keeps the first part "
                      << yes_no(kept) << ", one section mark "
                      << yes_no(resume_marks == 1)
                      << ", then the resumed run's screen output "
                      << yes_no(goes_on) << std::endl;
    checks.add(first_part.succeeded() && second_part.succeeded(),
               "first_part and second_part exit with code 0");
    checks.add(kept && resume_marks == 1 && goes_on,
               "after --resume log.txt is continued, not overwritten");
  }

  void
  check_provenance(Checks &checks, const Runs &runs)
  {
    check_provenance_files(checks);
    check_log(checks, runs.original);
    // Run again from the files written.
    checks.add(!read_text("original/time_series.csv").empty(),
               "original: time_series.csv written");
    check_same_series(checks,
                      {&runs.again_prm, &runs.again_json},
                      "the same time_series.csv",
                      "the run again gives the same time series");
    check_resumed_log(checks, runs.first_part, runs.second_part);
  }

  void
  check_input_formats(Checks &checks, const Runs &runs)
  {
    test_tools::out() << "input formats:" << std::endl;
    checks.add(runs.print_json.succeeded() && runs.print_xml.succeeded(),
               "--print-parameters=json|xml exit with code 0");
    check_same_series(checks,
                      {&runs.from_json, &runs.from_xml, &runs.from_short_json},
                      "the time_series.csv of the PRM scene",
                      "the same time series as the PRM scene");
    for (unsigned int i = 0; i < bad_files.size(); ++i)
      {
        const Run &r     = runs.bad[i];
        const auto lines = error_lines(r);
        const bool ok =
          r.code == 1 && lines.size() == 1 &&
          lines[0].find(bad_files[i].file) != std::string::npos &&
          lines[0].find(bad_files[i].must_contain) != std::string::npos;
        test_tools::out() << "  " << r.name << ": exit " << r.code << ": "
                          << first_error(r) << std::endl;
        checks.add(ok,
                   r.name + ": exit 1 and one error naming the file and '" +
                     bad_files[i].must_contain + "'");
      }
  }

  /** --validate of the good scene: exit 0, it says so, nothing written. */
  void
  check_valid(Checks &checks, const Validation &v, const Run &validate)
  {
    const bool nothing = !fs::exists("validate_" + v.name);
    const bool said    = validate.out.find("is valid") != std::string::npos;
    test_tools::out() << "  " << v.name << ": exit " << validate.code
                      << ", says it is valid " << yes_no(said)
                      << ", nothing written " << yes_no(nothing) << std::endl;
    checks.add(validate.succeeded() && said && nothing && validate.err.empty(),
               "--validate " + v.name + ": exit 0, nothing written");
  }

  /** --validate of a bad scene: the error the run stops with. */
  void
  check_invalid(Checks           &checks,
                const Validation &v,
                const Run        &validate,
                const Run        &run)
  {
    const bool nothing    = !fs::exists("validate_" + v.name);
    const auto validate_e = error_lines(validate);
    const auto run_e      = error_lines(run);
    const bool same       = validate_e == run_e && validate_e.size() == 1;
    test_tools::out() << "  " << v.name << ": exit " << validate.code
                      << " (the run: " << run.code << "), the error of the run "
                      << yes_no(same) << ", nothing written " << yes_no(nothing)
                      << ": " << first_error(validate) << std::endl;
    checks.add(validate.code == 1 && run.code == 1,
               "--validate " + v.name + ": exit 1 like the run");
    checks.add(same,
               "--validate " + v.name + ": exactly the error line of the run");
    checks.add(validate_e.size() == 1 &&
                 validate_e[0].find(v.must_contain) != std::string::npos,
               "--validate " + v.name + ": the error names '" + v.must_contain +
                 "'");
    checks.add(nothing, "--validate " + v.name + ": nothing written");
  }

  void
  check_validate(Checks &checks, const Runs &runs)
  {
    test_tools::out() << "--validate:" << std::endl;
    for (unsigned int i = 0; i < validations.size(); ++i)
      if (validations[i].must_contain.empty())
        check_valid(checks, validations[i], runs.validate[i]);
      else
        check_invalid(checks, validations[i], runs.validate[i], runs.plain[i]);
  }

  /** doc/parameters.md is what --print-parameters=markdown prints. */
  void
  check_parameter_page(Checks &checks, const Run &markdown)
  {
    const fs::path doc = fs::path(REPOSITORY_DIR) / "doc" / "parameters.md";
    const bool fresh   = markdown.succeeded() && read_text(doc) == markdown.out;
    test_tools::out()
      << "doc/parameters.md is what --print-parameters=markdown prints: "
      << yes_no(fresh) << std::endl;
    checks.add(fresh,
               "doc/parameters.md is up to date (if not, regenerate it: "
               "build/dynamic-contact --print-parameters=markdown > "
               "doc/parameters.md)");
  }
} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  remove_earlier_results();
  Runs runs;
  runs.execute();

  Checks checks;
  check_provenance(checks, runs);
  check_input_formats(checks, runs);
  check_validate(checks, runs);
  check_parameter_page(checks, runs.markdown);
  checks.assert_all();
  test_tools::out() << "OK" << std::endl;
}
