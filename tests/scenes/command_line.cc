// The command line of the real executable, as a user meets it:
//   --help / -h                      usage text on stdout, exit 0;
//   --print-parameters               every subsection and entry, documented,
//                                    with the 2D defaults, exit 0;
//   --print-parameters --set 'Dimension=3'
//                                    the 3D defaults;
//   --print-parameters scene.prm --set 'Material/Density=2000'
//                                    the scene's values and the override,
//                                    without running anything;
//   scene.prm --set ... (a short run) exit 0, time_series.csv with steps
//                                    0, 1, 2, contact_00002.csv, run_status
//                                    "completed";
//   --version                        names dynamic-contact and deal.II;
//   --resume=auto                    a new run where there is no checkpoint,
//                                    a resumed one where there is.
//
// Every program run happens first and prints what it found; the checks
// follow, so that a failing test still shows the whole picture.

#include "program_tools.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;

  /**
   * The entries of a parameter listing in deal.II's PRM format, by path
   * "Section/Subsection/Entry", and whether each has a documentation
   * comment right before it.
   */
  struct Listing
  {
    std::map<std::string, std::string> values;
    std::map<std::string, bool>        documented;
    std::vector<std::string>           top_level_subsections;
    bool                               balanced = true;

    explicit Listing(const std::string &text)
    {
      std::vector<std::string> path;
      bool                     comment_before = false;
      for (const auto &raw : lines_of(text))
        {
          const std::string line = trim(raw);
          if (line.empty())
            continue;
          if (line[0] == '#')
            {
              comment_before = true;
              continue;
            }
          if (line.rfind("subsection ", 0) == 0)
            {
              if (path.empty())
                top_level_subsections.push_back(trim(line.substr(11)));
              path.push_back(trim(line.substr(11)));
            }
          else if (line == "end")
            {
              if (path.empty())
                balanced = false;
              else
                path.pop_back();
            }
          else if (line.rfind("set ", 0) == 0)
            {
              const auto  equal = line.find('=');
              std::string name  = trim(line.substr(4, equal - 4));
              std::string value = trim(line.substr(equal + 1));
              // "value # default: ..." when the value is not the default.
              value = trim(value.substr(0, value.find('#')));
              for (auto s = path.rbegin(); s != path.rend(); ++s)
                name = *s + "/" + name;
              values[name]     = value;
              documented[name] = comment_before;
            }
          comment_before = false;
        }
      balanced = balanced && path.empty();
    }

    std::string
    get(const std::string &name) const
    {
      const auto it = values.find(name);
      return it == values.end() ? "<missing>" : it->second;
    }
  };

  const std::string scene = test_tools::scene("pressed_block.prm");

  /** Print "  ENTRY = [VALUE]" of @p listing. */
  void
  print_entry(const Listing &listing, const std::string &entry)
  {
    test_tools::out() << "  " << entry << " = [" << listing.get(entry) << "]"
                      << std::endl;
  }

  void
  check_help(Checks &checks, const Run &help, const Run &h)
  {
    std::ostream &out = test_tools::out();
    out << "--help:" << std::endl;
    for (const std::string word :
         {"Usage:", "--set", "--print-parameters", "--resume", "--validate"})
      {
        const bool found = help.out.find(word) != std::string::npos;
        out << "  the usage text mentions '" << word << "': " << yes_no(found)
            << std::endl;
        checks.add(found, "--help: the usage text mentions '" + word + "'");
      }
    checks.add(h.out == help.out, "-h prints the same text as --help");
  }

  /** --print-parameters: every part is there. */
  void
  check_print_defaults(Checks &checks, const Listing &listing)
  {
    std::ostream &out = test_tools::out();
    out << "--print-parameters:" << std::endl;
    out << "  subsections:";
    for (const auto &s : listing.top_level_subsections)
      out << " [" << s << "]";
    out << std::endl;
    checks.add(listing.balanced,
               "--print-parameters: every subsection is closed by 'end'");

    for (const std::string s : {"Geometry",
                                "Boundary conditions",
                                "Material",
                                "Foundation",
                                "Friction",
                                "Time",
                                "Solver",
                                "Output",
                                "Body force",
                                "Initial conditions"})
      checks.add(std::find(listing.top_level_subsections.begin(),
                           listing.top_level_subsections.end(),
                           s) != listing.top_level_subsections.end(),
                 "--print-parameters: prints subsection " + s);

    // One entry of each part, nested function subsections included.
    for (const std::string e :
         {"Dimension",
          "Geometry/Lower left",
          "Geometry/Mesh file",
          "Finite element/Polynomial degree",
          "Boundary conditions/Clamped",
          "Boundary conditions/Traction",
          "Boundary conditions/Traction function/Function expression",
          "Boundary conditions/Traction function/Function constants",
          "Material/Density",
          "Foundation/Normal damping/Capped ramp/Coefficient",
          "Foundation/Initial gap/Function expression",
          "Friction/Law",
          "Time/Time step",
          "Solver/Contact solver",
          "Output/Directory",
          "Body force/Function expression",
          "Initial conditions/Displacement/Function expression",
          "Initial conditions/Velocity/Function expression"})
      {
        print_entry(listing, e);
        checks.add(listing.values.count(e) == 1,
                   "--print-parameters: prints entry " + e);
      }
  }

  /** --print-parameters: every entry documented, the 2D defaults. */
  void
  check_documentation(Checks            &checks,
                      const Listing     &listing,
                      const std::string &text)
  {
    std::ostream            &out = test_tools::out();
    std::vector<std::string> undocumented;
    for (const auto &[name, documented] : listing.documented)
      if (!documented)
        undocumented.push_back(name);
    out << "  every entry has a documentation comment: "
        << yes_no(undocumented.empty() && listing.values.size() > 40)
        << std::endl;
    for (const auto &name : undocumented)
      out << "  undocumented: " << name << std::endl;
    checks.add(listing.values.size() > 40,
               "--print-parameters: prints more than 40 entries");
    checks.add(undocumented.empty(),
               "--print-parameters: every entry has a documentation comment");
    checks.add(text.find("Mass density rho") != std::string::npos,
               "--print-parameters: documents Material/Density");

    // The 2D defaults, for comparison with the 3D ones.
    checks.add(split(listing.get("Geometry/Lower left"), ',').size() == 2,
               "--print-parameters: Geometry/Lower left has two coordinates "
               "by default (2D)");
  }

  /** --print-parameters --set Dimension=3: the 3D defaults. */
  void
  check_print_3d(Checks &checks, const Listing &listing)
  {
    test_tools::out() << "--print-parameters --set 'Dimension=3':" << std::endl;
    for (const std::string e : {"Dimension",
                                "Geometry/Lower left",
                                "Geometry/Upper right",
                                "Geometry/Repetitions",
                                "Body force/Function expression",
                                "Body force/Variable names"})
      print_entry(listing, e);
    checks.add(listing.get("Dimension") == "3",
               "--set 'Dimension=3': Dimension = 3");
    for (const std::string e : {"Geometry/Lower left",
                                "Geometry/Upper right",
                                "Geometry/Repetitions"})
      checks.add(split(listing.get(e), ',').size() == 3,
                 "--set 'Dimension=3': " + e + " has three coordinates");
    checks.add(
      split(listing.get("Body force/Function expression"), ';').size() == 3,
      "--set 'Dimension=3': the body force has three components");
    checks.add(listing.get("Body force/Variable names") == "x,y,z,t",
               "--set 'Dimension=3': the variables are x,y,z,t");
  }

  /** --print-parameters pressed_block.prm --set Material/Density=2000: the
   *  scene's values and the override, without running anything. */
  void
  check_print_scene(Checks &checks, const Run &print_scene)
  {
    const Listing listing(print_scene.out);
    test_tools::out() << "--print-parameters pressed_block.prm --set "
                         "'Material/Density=2000':"
                      << std::endl;
    const std::vector<std::pair<std::string, std::string>> expected = {
      {"Material/Density", "2000"},
      {"Material/Young modulus", "1e9"},
      {"Geometry/Repetitions", "4, 2"},
      {"Boundary conditions/Roller", "0, 1"},
      {"Time/End time", "8"},
      {"Boundary conditions/Traction function/Function constants", "P=1e7"},
      {"Boundary conditions/Traction function/Function expression", "0; -P"}};
    for (const auto &[e, value] : expected)
      {
        print_entry(listing, e);
        checks.add(listing.get(e) == value,
                   "--print-parameters pressed_block.prm: " + e + " = " +
                     value);
      }
    checks.add(print_scene.out.find("# default: 1000") != std::string::npos,
               "--print-parameters pressed_block.prm: the overridden density "
               "shows its default");
    checks.add(!fs::exists("output-pressed-block"),
               "--print-parameters pressed_block.prm: runs nothing (no output "
               "directory)");
  }

  /** A short run: run_status and time_series.csv. */
  void
  check_time_series(Checks &checks)
  {
    std::ostream &out = test_tools::out();
    out << "pressed_block.prm --set 'Output/Directory=run' --set 'Time/End "
           "time=2':"
        << std::endl;
    const std::string status = trim(read_text("run/run_status"));
    out << "  run_status: " << status << std::endl;
    checks.add(status == "completed", "run: run_status reads 'completed'");

    const auto                     series = read_csv("run/time_series.csv");
    const std::vector<std::string> header =
      series.empty() ? std::vector<std::string>() : series[0];
    for (const std::string column : {"step",
                                     "time",
                                     "normal_force",
                                     "kinetic_energy",
                                     "elastic_energy",
                                     "foundation_energy",
                                     "load_work",
                                     "dissipation",
                                     "energy_balance_defect",
                                     "newton_iterations",
                                     "n_contact",
                                     "dofs",
                                     "cells"})
      checks.add(std::find(header.begin(), header.end(), column) !=
                   header.end(),
                 "run: time_series.csv has the column " + column);

    const unsigned int n_rows = series.empty() ? 0 : series.size() - 1;
    out << "  time_series.csv: " << n_rows << " rows" << std::endl;
    checks.add(n_rows == 3, "run: time_series.csv has 3 rows");

    auto column = [&header](const std::string &name) {
      return static_cast<unsigned int>(
        std::find(header.begin(), header.end(), name) - header.begin());
    };
    bool fields_match = true, steps_match = true;
    for (unsigned int r = 1; r < series.size(); ++r)
      {
        const auto &row = series[r];
        fields_match    = fields_match && row.size() == header.size();
        if (row.size() != header.size())
          continue;
        const std::string step = row[column("step")];
        const double      time = std::atof(row[column("time")].c_str());
        const double normal    = std::atof(row[column("normal_force")].c_str());
        steps_match            = steps_match && step == std::to_string(r - 1) &&
                      time == static_cast<double>(r - 1);
        out << "  step " << step << "  time " << test_tools::digits(time)
            << "  normal_force " << test_tools::digits(normal) << std::endl;
      }
    checks.add(fields_match,
               "run: every row of time_series.csv has a field per column");
    checks.add(steps_match && n_rows == 3,
               "run: the rows are the steps 0, 1, 2 at times 0, 1, 2");
  }

  /** A short run: the contact file of its last step. */
  void
  check_contact_file(Checks &checks)
  {
    const auto        contact = read_csv("run/contact_00002.csv");
    const auto        lines   = lines_of(read_text("run/contact_00002.csv"));
    const std::string contact_header = lines.empty() ? "<missing>" : lines[0];
    test_tools::out() << "  contact_00002.csv: " << contact_header << ", "
                      << (contact.empty() ? 0 : contact.size() - 1) << " rows"
                      << std::endl;
    checks.add(contact_header.rfind("time,x,y,u_nu,w_nu,normal_pressure", 0) ==
                 0,
               "run: contact_00002.csv has the columns "
               "time,x,y,u_nu,w_nu,normal_pressure first");
    bool time_of_step = contact.size() > 1;
    for (std::size_t r = 1; r < contact.size(); ++r)
      time_of_step =
        time_of_step && !contact[r].empty() && std::stod(contact[r][0]) == 2.;
    checks.add(time_of_step,
               "run: every row of contact_00002.csv has the time 2 of step 2");
    checks.add(contact.size() == 6,
               "run: contact_00002.csv has a row per contact node (5)");
  }

  void
  check_version(Checks &checks, const Run &version)
  {
    const bool names = version.out.rfind("dynamic-contact ", 0) == 0 &&
                       version.out.find("(git ") != std::string::npos &&
                       version.out.find("deal.II 9.") != std::string::npos;
    test_tools::out()
      << "--version: names dynamic-contact, its git revision and deal.II: "
      << yes_no(names) << std::endl;
    checks.add(names,
               "--version: 'dynamic-contact X (git R), deal.II 9.x'" +
                 (names ? std::string() : " [" + trim(version.out) + "]"));
  }

  void
  check_resume_auto(Checks &checks, const Run &auto_new, const Run &resumed_run)
  {
    const bool new_run =
      auto_new.out.find("--resume=auto: no checkpoint") != std::string::npos;
    const bool resumed =
      resumed_run.out.find("resumed from") != std::string::npos;
    const auto        series = read_csv("auto/time_series.csv");
    const std::string status = trim(read_text("auto/run_status"));
    test_tools::out() << "--resume=auto: first a new run: " << yes_no(new_run)
                      << ", then a resumed one: " << yes_no(resumed)
                      << "; time_series.csv rows: " << series.size()
                      << ", run_status: " << status << std::endl;
    checks.add(new_run, "--resume=auto without a checkpoint: a new run");
    checks.add(resumed, "--resume=auto with a checkpoint: resumed");
    checks.add(series.size() == 6 && status == "completed",
               "--resume=auto: the resumed run ends at t = 4 (header and "
               "steps 0 to 4), completed");
  }

  /**
   * Every run of the program: most of a run is MPI's start-up, spent
   * waiting, so the independent ones run side by side; then --resume=auto
   * twice in one directory with checkpoints: a new run to t = 2, then (a
   * later end time) a resumed one to t = 4.
   */
  std::vector<Run>
  run_all()
  {
    fs::remove_all("run");
    fs::remove_all("output-pressed-block");
    fs::remove_all("auto");
    std::vector<Run> runs = {
      {{"--help"}, "help"},
      {{"-h"}, "h"},
      {{"--print-parameters"}, "print_defaults"},
      {{"--print-parameters", "--set", "Dimension=3"}, "print_3d"},
      {{"--print-parameters", scene, "--set", "Material/Density=2000"},
       "print_scene"},
      {{scene, "--set", "Output/Directory=run", "--set", "Time/End time=2"},
       "run"},
      {{"--version"}, "version"},
    };
    execute_all(runs);

    const std::vector<std::string> auto_run = {scene,
                                               "--resume=auto",
                                               "--set",
                                               "Output/Directory=auto",
                                               "--set",
                                               "Checkpoint/Every=1"};
    for (const auto &[name, end] : {std::make_pair("resume_auto_new", "2"),
                                    std::make_pair("resume_auto_resumed", "4")})
      {
        Run r(with(auto_run, {"--set", std::string("Time/End time=") + end}),
              name);
        execute_all({&r});
        runs.push_back(r);
      }
    return runs;
  }

  /** The run of @p runs called @p name. */
  const Run &
  named(const std::vector<Run> &runs, const std::string &name)
  {
    return *std::find_if(runs.begin(), runs.end(), [&](const Run &r) {
      return r.name == name;
    });
  }
} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  const std::vector<Run> runs = run_all();
  Checks                 checks;
  for (const auto &r : runs)
    {
      checks.add(r.succeeded(),
                 r.name + ": exits normally with code 0" +
                   (r.succeeded() ?
                      "" :
                      " [status " + std::to_string(r.status) + "]"));
      checks.add(r.err.empty(), r.name + ": nothing on stderr");
    }

  check_help(checks, named(runs, "help"), named(runs, "h"));
  const Run    &print_defaults = named(runs, "print_defaults");
  const Listing defaults(print_defaults.out);
  check_print_defaults(checks, defaults);
  check_documentation(checks, defaults, print_defaults.out);
  check_print_3d(checks, Listing(named(runs, "print_3d").out));
  check_print_scene(checks, named(runs, "print_scene"));
  check_time_series(checks);
  check_contact_file(checks);
  check_version(checks, named(runs, "version"));
  check_resume_auto(checks,
                    named(runs, "resume_auto_new"),
                    named(runs, "resume_auto_resumed"));

  test_tools::out() << std::endl;
  checks.assert_all();
  return 0;
}
