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

} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ostream                            &out = test_tools::out();


  const std::string scene = test_tools::scene("pressed_block.prm");
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
  // Most of a run is MPI's start-up, spent waiting: run them side by side.
  {
    std::vector<Run *> all;
    for (auto &r : runs)
      all.push_back(&r);
    execute_all(all);
  }
  // --resume=auto twice in one directory with checkpoints: a new run to
  // t = 2, then (a later end time) a resumed one to t = 4.
  const std::vector<std::string> auto_run = {scene,
                                             "--resume=auto",
                                             "--set",
                                             "Output/Directory=auto",
                                             "--set",
                                             "Checkpoint/Every=1"};
  Run                            auto_new(auto_run, "resume_auto_new");
  auto_new.arguments.insert(auto_new.arguments.end(),
                            {"--set", "Time/End time=2"});
  execute_all({&auto_new});
  Run auto_resumed(auto_run, "resume_auto_resumed");
  auto_resumed.arguments.insert(auto_resumed.arguments.end(),
                                {"--set", "Time/End time=4"});
  execute_all({&auto_resumed});
  runs.push_back(auto_new);
  runs.push_back(auto_resumed);
  const Run &help = runs[0], &h = runs[1], &print_defaults = runs[2],
            &print_3d = runs[3], &print_scene = runs[4], &version = runs[6];

  Checks checks;
  for (const auto &r : runs)
    {
      checks.add(r.succeeded(),
                 r.name + ": exits normally with code 0" +
                   (r.succeeded() ?
                      "" :
                      " [status " + std::to_string(r.status) + "]"));
      checks.add(r.err.empty(), r.name + ": nothing on stderr");
    }

  // ------------------------------------------------------------ --help
  {
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

  // ------------------------------------------------ --print-parameters
  {
    const Listing listing(print_defaults.out);
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
        const bool found = listing.values.count(e) == 1;
        out << "  " << e << " = [" << listing.get(e) << "]" << std::endl;
        checks.add(found, "--print-parameters: prints entry " + e);
      }

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
    checks.add(print_defaults.out.find("Mass density rho") != std::string::npos,
               "--print-parameters: documents Material/Density");

    // The 2D defaults, for comparison with the 3D ones.
    checks.add(split(listing.get("Geometry/Lower left"), ',').size() == 2,
               "--print-parameters: Geometry/Lower left has two coordinates "
               "by default (2D)");
  }

  // ------------------------------ --print-parameters --set Dimension=3
  {
    const Listing listing(print_3d.out);
    out << "--print-parameters --set 'Dimension=3':" << std::endl;
    for (const std::string e : {"Dimension",
                                "Geometry/Lower left",
                                "Geometry/Upper right",
                                "Geometry/Repetitions",
                                "Body force/Function expression",
                                "Body force/Variable names"})
      out << "  " << e << " = [" << listing.get(e) << "]" << std::endl;
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

  // ------- --print-parameters pressed_block.prm --set Material/Density=2000
  {
    const Listing listing(print_scene.out);
    out << "--print-parameters pressed_block.prm --set "
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
        out << "  " << e << " = [" << listing.get(e) << "]" << std::endl;
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

  // ----------------------------------------------------- a short run
  {
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

    const auto        contact = read_csv("run/contact_00002.csv");
    const std::string contact_header =
      lines_of(read_text("run/contact_00002.csv")).empty() ?
        "<missing>" :
        lines_of(read_text("run/contact_00002.csv"))[0];
    out << "  contact_00002.csv: " << contact_header << ", "
        << (contact.empty() ? 0 : contact.size() - 1) << " rows" << std::endl;
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

  // ------------------------------------------------------------ --version
  {
    const bool names = version.out.rfind("dynamic-contact ", 0) == 0 &&
                       version.out.find("(git ") != std::string::npos &&
                       version.out.find("deal.II 9.") != std::string::npos;
    out << "--version: names dynamic-contact, its git revision and deal.II: "
        << yes_no(names) << std::endl;
    checks.add(names,
               "--version: 'dynamic-contact X (git R), deal.II 9.x'" +
                 (names ? std::string() : " [" + trim(version.out) + "]"));
  }

  // ------------------------------------------------------- --resume=auto
  {
    const bool new_run =
      auto_new.out.find("--resume=auto: no checkpoint") != std::string::npos;
    const bool resumed =
      auto_resumed.out.find("resumed from") != std::string::npos;
    const auto        series = read_csv("auto/time_series.csv");
    const std::string status = trim(read_text("auto/run_status"));
    out << "--resume=auto: first a new run: " << yes_no(new_run)
        << ", then a resumed one: " << yes_no(resumed)
        << "; time_series.csv rows: " << series.size()
        << ", run_status: " << status << std::endl;
    checks.add(new_run, "--resume=auto without a checkpoint: a new run");
    checks.add(resumed, "--resume=auto with a checkpoint: resumed");
    checks.add(series.size() == 6 && status == "completed",
               "--resume=auto: the resumed run ends at t = 4 (header and "
               "steps 0 to 4), completed");
  }

  out << std::endl;
  checks.assert_all();
  return 0;
}
