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
// Every case runs first and prints one line; the checks follow, so that a
// failing test still shows what every case did.

#include "program_tools.h"

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  using namespace program_tools;

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
    static const std::regex path(R"((^|[\s'"<(])/(?:[^\s'"<>()]*/)?)");
    static const std::regex residual(R"(relative residual [-+.0-9eE]+)");
    // The memory of the machine that runs the test.
    static const std::regex memory(
      R"(and [0-9.e+]+ GB are available on the [0-9]+ hosts?)");
    std::string result = std::regex_replace(text, path, "$1");
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

  /** @p text with @p from replaced by @p to; the case is void if it is absent.
   */
  std::string
  changed(const std::string &text,
          const std::string &from,
          const std::string &to)
  {
    const auto position = text.find(from);
    if (position == std::string::npos)
      test_tools::check(false,
                        "prm/pressed_block.prm contains '" + from +
                          "' (the test changes it)");
    return text.substr(0, position) + to + text.substr(position + from.size());
  }

  struct Case
  {
    std::string name;
    /** Written to scene.prm in the case's directory if given. */
    std::optional<std::string> prm;
    std::vector<std::string>   arguments;
    /** 0: a control that must run; 1: input error; 2: usage error. */
    int expected_code;
    /** What the error line must contain. */
    std::vector<std::string> names;
    /** If not empty: the line of scene.prm (its text) the error is in. */
    std::string line_of = "";
    /** Found only while running: run_status must read "failed: ...". */
    bool runtime = false;
    /** Further files to write into the case's directory. */
    std::vector<std::pair<std::string, std::string>> extra_files = {};
    /** A named pipe (FIFO) to make in the case's directory. */
    std::string fifo = "";

    /** The number of the first line of prm containing line_of, or 0. */
    unsigned int
    line_number() const
    {
      if (line_of.empty() || !prm)
        return 0;
      const auto position = prm->find(line_of);
      if (position == std::string::npos)
        return 0;
      return 1 + std::count(prm->begin(), prm->begin() + position, '\n');
    }
  };

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

  Result
  run_case(const Case &c, const fs::path &directory)
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

    Launch launch;
    launch.directory = directory;
    launch.name      = "program";
    launch.timeout   = 120; // a pipe must not block the program
    Result o;
    static_cast<Outcome &>(o) = execute(c.arguments, launch);

    const auto lines = lines_of(o.err);
    for (const auto &line : lines)
      if (line.rfind(error_prefix, 0) == 0)
        o.error_lines.push_back(line);

    // Only the message; after a usage error the usage text may follow it.
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
    return o;
  }

} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);


  const std::string scene = read_text(test_tools::scene("pressed_block.prm"));
  test_tools::check(scene.find("subsection Material") != std::string::npos,
                    "read prm/pressed_block.prm");

  // Binary content: every byte value, control characters first.
  std::string garbage;
  for (unsigned int i = 0; i < 512; ++i)
    garbage += static_cast<char>(i % 256);

  const std::vector<std::string> file = {"scene.prm"};
  auto                           with = [&file](std::vector<std::string> more) {
    more.insert(more.begin(), file.begin(), file.end());
    return more;
  };

  std::vector<Case> cases;
  auto              add = [&cases](const std::string               &name,
                      const std::optional<std::string> prm,
                      const std::vector<std::string>  &arguments,
                      const int                        expected_code,
                      const std::vector<std::string>  &names) -> Case              &{
    cases.push_back(Case{name, prm, arguments, expected_code, names});
    return cases.back();
  };

  // A copy of the scene with @p from changed to @p to.
  auto change = [&scene](const std::string &from, const std::string &to) {
    return changed(scene, from, to);
  };

  const std::string density             = "set Density       = 1000";
  const std::string young               = "set Young modulus = 1e9";
  const std::string poisson             = "set Poisson ratio = 0.3";
  const std::string step                = "set Time step = 1";
  const std::string end                 = "set End time  = 8";
  const std::string traction_expression = "set Function expression = 0; -P";

  // Controls: valid input runs to completion.
  add("control_valid_scene", scene, file, 0, {});

  // The file itself.
  add("empty_file", "", file, 1, {"scene.prm", "empty"});
  add("only_comments", "# nothing set\n\n", file, 1, {"scene.prm", "empty"});
  add("missing_file", std::nullopt, {"missing.prm"}, 1, {"missing.prm"});
  add("binary_garbage_file", garbage, file, 1, {"scene.prm"});
  add("unknown_entry_top_level",
      scene + "\nset Foo = 1\n",
      file,
      1,
      {"scene.prm", "Foo"})
    .line_of = "set Foo = 1";
  add("unknown_entry_in_subsection",
      change(density, density + "\n  set Foo = 1"),
      file,
      1,
      {"scene.prm", "Material/Foo"})
    .line_of = "set Foo = 1";
  add("removed_entry",
      scene + "\nsubsection Friction\n  set Acceleration depth = 2\nend\n",
      file,
      1,
      {"scene.prm", "Friction/Acceleration depth", "removed"})
    .line_of = "set Acceleration depth = 2";
  add("unknown_subsection",
      change("subsection Foundation", "subsection Fundation"),
      file,
      1,
      {"scene.prm", "Fundation"})
    .line_of = "subsection Fundation";
  add("misspelt_entry",
      change(young, "set Youngs modulus = 1e9"),
      file,
      1,
      {"scene.prm", "Material/Youngs modulus"})
    .line_of = "set Youngs modulus = 1e9";
  add("malformed_value",
      change(density, "set Density = abc"),
      file,
      1,
      {"scene.prm", "Material/Density", "abc"})
    .line_of = "set Density = abc";
  add("nan_value",
      change(density, "set Density = nan"),
      file,
      1,
      {"scene.prm", "Material/Density", "nan"})
    .line_of = "set Density = nan";
  add("dimension_4",
      change("set Dimension = 2", "set Dimension = 4"),
      file,
      1,
      {"scene.prm", "Dimension", "4"})
    .line_of = "set Dimension = 4";

  // Values out of range.
  add("density_zero",
      change(density, "set Density = 0"),
      file,
      1,
      {"Material/Density"});
  add("density_negative",
      change(density, "set Density = -1000"),
      file,
      1,
      {"Material/Density"});
  add("young_modulus_zero",
      change(young, "set Young modulus = 0"),
      file,
      1,
      {"Material/Young modulus"});
  add("young_modulus_negative",
      change(young, "set Young modulus = -1e9"),
      file,
      1,
      {"Material/Young modulus"});
  add("poisson_ratio_0.5",
      change(poisson, "set Poisson ratio = 0.5"),
      file,
      1,
      {"Material/Poisson ratio"});
  add("poisson_ratio_-1",
      change(poisson, "set Poisson ratio = -1"),
      file,
      1,
      {"Material/Poisson ratio"});
  add("time_step_zero",
      change(step, "set Time step = 0"),
      file,
      1,
      {"Time/Time step"});
  add("time_step_negative",
      change(step, "set Time step = -1"),
      file,
      1,
      {"Time/Time step"});
  add("end_time_zero",
      change(end, "set End time = 0"),
      file,
      1,
      {"Time/End time"});
  add("end_time_negative",
      change(end, "set End time = -8"),
      file,
      1,
      {"Time/End time"});
  add("spectral_radius_without_bathe",
      scene,
      with({"--set", "Time/Spectral radius at infinity=0.5"}),
      1,
      {"Time/Spectral radius at infinity", "Time/Scheme = bathe"});
  add("spectral_radius_above_one",
      scene,
      with({"--set",
            "Time/Scheme=bathe",
            "--set",
            "Time/Spectral radius at infinity=1.5"}),
      1,
      {"Time/Spectral radius at infinity"});
  add("slip_length_with_sdirk",
      scene,
      with(
        {"--set", "Time/Scheme=sdirk", "--set", "Friction/Slip length=0.01"}),
      1,
      {"Friction/Slip length", "Time/Scheme"});
  add("slip_length_negative",
      scene,
      with({"--set", "Friction/Slip length=-1"}),
      1,
      {"Friction/Slip length"});

  // Boundary conditions against the mesh (ids 0..3 of the rectangle).
  add("boundary_id_twice",
      change("set Clamped  =", "set Clamped  = 2"),
      file,
      1,
      {"boundary id 2",
       "Boundary conditions/Clamped",
       "Boundary conditions/Contact"});
  add("boundary_id_unassigned",
      change("set Roller   = 0, 1", "set Roller   = 0"),
      file,
      1,
      {"Boundary conditions", "boundary id 1"});
  add("boundary_id_not_in_mesh",
      change("set Contact  = 2", "set Contact  = 2\n  set Free = 7"),
      file,
      1,
      {"Boundary conditions/Free", "boundary id 7"});

  // Functions.
  add("function_does_not_parse",
      change(traction_expression, "set Function expression = 0; -P*("),
      file,
      1,
      {"Boundary conditions/Traction function/Function expression"});
  add("function_wrong_number_of_components",
      change(traction_expression, "set Function expression = -P"),
      file,
      1,
      {"Boundary conditions/Traction function/Function expression"});

  // Geometry and output.
  add("gmsh_mesh_file_missing",
      change("set Type        = rectangle",
             "set Type        = gmsh\n  set Mesh file = missing.msh"),
      file,
      1,
      {"Geometry/Mesh file", "missing.msh"});
  // A Gmsh mesh of the block (1 x 0.5, two quadrilaterals): the control
  // tags the right, bottom and top edges 1, 2, 3 and leaves the left one
  // untagged (deal.II gives it id 0), as the rectangle's ids; the other tags
  // the left and right edges 10, so ids 0 and 1 named by Roller are missing.
  auto msh = [](const std::string &side_tag, const std::string &left_line) {
    return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
           "$Nodes\n6\n1 0 0 0\n2 0.5 0 0\n3 1 0 0\n4 0 0.5 0\n"
           "5 0.5 0.5 0\n6 1 0.5 0\n$EndNodes\n"
           "$Elements\n" +
           std::string(left_line.empty() ? "7" : "8") +
           "\n"
           "1 1 2 2 2 1 2\n2 1 2 2 2 2 3\n"
           "3 1 2 " +
           side_tag + " " + side_tag +
           " 3 6\n"
           "4 1 2 3 3 6 5\n5 1 2 3 3 5 4\n" +
           left_line + "7 3 2 5 5 1 2 5 4\n8 3 2 5 5 2 3 6 5\n$EndElements\n";
  };
  const std::string gmsh_scene =
    change("set Type        = rectangle",
           "set Type        = gmsh\n  set Mesh file = block.msh");
  add("control_gmsh_scene", gmsh_scene, file, 0, {}).extra_files = {
    {"block.msh", msh("1", "")}};
  add("gmsh_mesh_lacks_boundary_ids",
      gmsh_scene,
      file,
      1,
      {"Boundary conditions/Roller", "boundary id 0", "block.msh"})
    .extra_files = {{"block.msh", msh("10", "6 1 2 10 10 4 1\n")}};
  add("gmsh_mesh_file_garbage",
      gmsh_scene,
      file,
      1,
      {"Geometry/Mesh file", "block.msh"})
    .extra_files = {{"block.msh", garbage}};
  add("gmsh_mesh_file_truncated",
      gmsh_scene,
      file,
      1,
      {"Geometry/Mesh file", "block.msh"})
    .extra_files = {{"block.msh", msh("1", "").substr(0, 120)}};
  // Issue 12: Gmsh meshes this program cannot use are refused before
  // deal.II reads them (it crashed on triangles), and the boundary lists
  // may name physical groups.
  const std::string names =
    "$PhysicalNames\n4\n1 1 \"right\"\n1 2 \"bottom\"\n1 3 \"top\"\n"
    "2 5 \"block\"\n$EndPhysicalNames\n";
  auto named_msh = [&msh, &names]() {
    std::string m = msh("1", "");
    return m.insert(m.find("$Nodes"), names);
  };
  const std::string names_scene =
    changed(changed(changed(gmsh_scene,
                            "set Roller   = 0, 1",
                            "set Roller   = 0, right"),
                    "set Contact  = 2",
                    "set Contact  = bottom"),
            "set Traction = 3",
            "set Traction = top");
  add("control_gmsh_physical_names", names_scene, file, 0, {}).extra_files = {
    {"block.msh", named_msh()}};
  add("gmsh_unknown_physical_name",
      changed(names_scene, "set Contact  = bottom", "set Contact  = bottm"),
      file,
      1,
      {"Boundary conditions/Contact",
       "'bottm'",
       "block.msh",
       "'bottom' (2), 'right' (1), 'top' (3)"})
    .extra_files = {{"block.msh", named_msh()}};
  add("boundary_name_with_rectangle",
      change("set Contact  = 2", "set Contact  = bottom"),
      file,
      1,
      {"Boundary conditions/Contact", "'bottom'", "Geometry/Type = gmsh"});
  add("boundary_id_out_of_range",
      change("set Contact  = 2", "set Contact  = 2, 256"),
      file,
      1,
      {"Boundary conditions/Contact", "256", "0 to 255"});
  // Gmsh's default: triangles (2D), tetrahedra (3D).
  add("gmsh_triangles",
      gmsh_scene,
      file,
      1,
      {"Geometry/Mesh file",
       "block.msh",
       "2 3-node triangles",
       "Gmsh element type 2",
       "Mesh.RecombineAll = 1",
       "Mesh.SubdivisionAlgorithm = 1"})
    .extra_files = {
    {"block.msh",
     "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
     "2 1 0 0\n3 1 0.5 0\n4 0 0.5 0\n$EndNodes\n$Elements\n6\n"
     "1 1 2 2 2 1 2\n2 1 2 1 1 2 3\n3 1 2 3 3 3 4\n4 1 2 0 0 4 1\n"
     "5 2 2 5 5 1 2 3\n6 2 2 5 5 1 3 4\n$EndElements\n"}};
  {
    const std::string scene_3d =
      read_text(test_tools::scene("pressed_block_3d.prm"));
    add("gmsh_tetrahedra",
        changed(scene_3d,
                "set Type        = rectangle",
                "set Type        = gmsh\n  set Mesh file = block.msh"),
        file,
        1,
        {"Geometry/Mesh file",
         "block.msh",
         "1 4-node tetrahedron",
         "Gmsh element type 4",
         "Mesh.SubdivisionAlgorithm = 2"})
      .extra_files = {
      {"block.msh",
       "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n"
       "1 0 0 0 1 0.5 0.5 0 0\n$EndEntities\n$Nodes\n1 4 1 4\n"
       "3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 0.5 0\n0 0 0.5\n"
       "$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n"
       "$EndElements\n"}};
  }
  add("gmsh_binary",
      gmsh_scene,
      file,
      1,
      {"Geometry/Mesh file", "block.msh", "binary", "ASCII"})
    .extra_files = {{"block.msh", "$MeshFormat\n4.1 1 8\n" + garbage}};
  add("output_directory_not_creatable",
      change("set Directory = output-pressed-block",
             "set Directory = scene.prm/results"),
      file,
      1,
      {"Output/Directory", "scene.prm/results"});

  // Found only while running: the run must end as failed, not completed.
  add("newton_iterations_exhausted",
      change("subsection Output",
             "subsection Solver\n  set Maximum Newton "
             "iterations = 1\nend\n\nsubsection Output"),
      file,
      1,
      {"Solver/Maximum Newton iterations"})
    .runtime = true;

  // Values that are not finite: named before anything is written.
  add("traction_not_finite",
      change(traction_expression, "set Function expression = 0; -P/0"),
      file,
      1,
      {"Boundary conditions/Traction function", "-P/0", "-inf"});
  add("initial_velocity_not_finite",
      scene + "\nsubsection Initial conditions\n  subsection Velocity\n"
              "    set Function expression = 1/0; 0\n  end\nend\n",
      file,
      1,
      {"Initial conditions/Velocity", "1/0"});
  add("body_force_not_finite",
      scene + "\nsubsection Body force\n  set Function expression = 0; "
              "sqrt(-1)\nend\n",
      file,
      1,
      {"Body force", "sqrt(-1)"});
  add("initial_gap_not_finite",
      change("subsection Foundation",
             "subsection Foundation\n  subsection Initial gap\n    set "
             "Function expression = log(x-2)\n  end"),
      file,
      1,
      {"Foundation/Initial gap", "log(x-2)"});
  add("friction_not_finite",
      scene + "\nsubsection Friction\n  set Law = expression\n  subsection "
              "Expression\n    set Function expression = 0.5+sqrt(1-s)\n  "
              "end\nend\n",
      file,
      1,
      {"Friction/Expression", "0.5+sqrt(1-s)", "not finite"});
  // NaN only near t = 2.1, between the sampled times (0, 1, 8 and every
  // 0.5 s), reached by the steps of k = 0.3: the run stops after step 6.
  add("traction_not_finite_at_step_7",
      changed(change(step, "set Time step = 0.3"),
              traction_expression,
              "set Function expression = 0; -P*(1+0*sqrt(abs(t-2.1)-0.05))"),
      file,
      1,
      {"Boundary conditions/Traction function",
       "t = 2.1",
       "last good state (step 6)"})
    .runtime = true;
  // An entry of the flat layout of earlier versions: its new place named.
  add("old_layout_entry",
      scene + "\nsubsection Friction\n  set Decay rate = 3\nend\n",
      file,
      1,
      {"Friction/Decay rate",
       "Friction/Exponential/Decay rate",
       "scripts/update-prm"});
  add("velocity_strengthening",
      scene +
        "\nsubsection Friction\n  set Law = expression\n  subsection "
        "Expression\n    set Function expression = 1 - 0.5*exp(-2000*s)\n  "
        "end\nend\n",
      file,
      1,
      {"Friction/Expression",
       "increases with the slip rate",
       "Friction/Velocity strengthening"});

  // Scenes that cannot fit: refused with the estimate, before allocating.
  const std::string repetitions = "set Repetitions = 4, 2";
  add("repetitions_huge",
      change(repetitions, "set Repetitions = 100000, 100000"),
      file,
      1,
      {"too large", "1.0e+10 cells", "Geometry/Repetitions"});
  add("refinements_20",
      change(repetitions, repetitions + "\n  set Global refinements = 20"),
      file,
      1,
      {"too large", "Geometry/Global refinements"});
  add("memory_too_small",
      change(repetitions, repetitions + "\n  set Global refinements = 13"),
      file,
      1,
      {"does not fit into memory", "5.4e+08 cells", "GB"});

  // The parameter file itself.
  add("includes_itself",
      "include scene.prm\n" + scene,
      file,
      1,
      {"scene.prm", "includes itself"});
  add("includes_itself_indirectly",
      "include other.prm\n" + scene,
      file,
      1,
      {"scene.prm -> other.prm -> scene.prm", "includes itself"})
    .extra_files = {{"other.prm", "include scene.prm\n"}};
  add("includes_missing_file",
      "include missing.prm\n" + scene,
      file,
      1,
      {"missing.prm", "scene.prm"});
  add(
    "directory_as_parameter_file", scene, {"."}, 1, {"'.'", "is a directory"});
  add("named_pipe_as_parameter_file",
      std::nullopt,
      {"pipe.prm"},
      1,
      {"pipe.prm", "named pipe"})
    .fifo = "pipe.prm";
  add("control_byte_order_mark", "\xEF\xBB\xBF" + scene, file, 0, {});

  // --set.
  add("set_unknown_entry",
      scene,
      with({"--set", "Material/Foo=1"}),
      1,
      {"--set", "Material/Foo"});
  add("set_removed_entry",
      scene,
      with({"--set", "Friction/Acceleration depth=2"}),
      1,
      {"--set", "Friction/Acceleration depth", "removed"});
  add("set_removed_look_ahead",
      scene,
      with({"--set", "Mesh refinement/Load following/Look-ahead steps=3"}),
      1,
      {"--set", "Mesh refinement/Load following/Look-ahead steps", "removed"});
  add("set_unknown_subsection",
      scene,
      with({"--set", "Foo/Bar=1"}),
      1,
      {"--set", "Foo/Bar"});
  add("set_value_out_of_range",
      scene,
      with({"--set", "Material/Density=-1"}),
      1,
      {"Material/Density"});
  add("set_malformed_value",
      scene,
      with({"--set", "Time/Time step=abc"}),
      1,
      {"Time/Time step", "abc"});

  // The command line (usage errors, exit code 2). --set without '=' cannot
  // be read at all, like --set without an argument: a usage error.
  add("set_without_equals",
      scene,
      with({"--set", "Material/Density"}),
      2,
      {"--set", "Material/Density"});
  add("set_without_argument", scene, with({"--set"}), 2, {"--set"});
  add("unknown_option", scene, with({"--frobnicate"}), 2, {"--frobnicate"});
  add("two_parameter_files",
      scene,
      with({"other.prm"}),
      2,
      {"scene.prm", "other.prm"})
    .extra_files = {{"other.prm", scene}};
  add("no_parameter_file", scene, {}, 2, {"parameter file"});

  // Most of a run is MPI's start-up, spent waiting: run a few at a time.
  std::vector<Result> outcomes(cases.size());
  {
    std::atomic<unsigned int> next(0);
    std::vector<std::thread>  workers;
    for (unsigned int w = 0; w < 6; ++w)
      workers.emplace_back([&]() {
        for (unsigned int i = next++; i < cases.size(); i = next++)
          outcomes[i] = run_case(cases[i], fs::path("case_" + cases[i].name));
      });
    for (auto &w : workers)
      w.join();
  }

  Checks checks;
  for (unsigned int i = 0; i < cases.size(); ++i)
    {
      const Case        &c    = cases[i];
      const Result      &o    = outcomes[i];
      const unsigned int line = c.line_number();

      // One line per case, the same on every machine.
      std::string summary = c.name + " | ";
      if (c.expected_code == 0)
        summary +=
          "control, exit code zero: " + yes_no(o.exited && o.code == 0) +
          " | run_status completed: " +
          yes_no(o.completed_status_files.size() == 1);
      else
        {
          summary += "exit code nonzero: " + yes_no(o.exited && o.code != 0) +
                     " | one error line: " + yes_no(o.error_lines.size() == 1);
          for (const auto &e : o.error_lines)
            summary += " | " + deterministic(e, line);
          if (o.error_lines.empty() && !o.err.empty())
            summary += " | first line on stderr: " +
                       deterministic(lines_of(o.err)[0], line);
        }
      test_tools::out() << summary << std::endl;

      const std::string name = c.name + ": ";
      checks.add(o.status != -1 && o.exited,
                 name + "a normal exit (no signal, no abort)" +
                   (o.signal != 0 ?
                      " [signal " + std::to_string(o.signal) + "]" :
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
          checks.add(o.non_finite_files.empty(),
                     name + "no 'nan' or 'inf' in a CSV file");
          continue;
        }

      checks.add(o.error_lines.size() == 1,
                 name + "exactly one line '" + error_prefix +
                   " ...' on stderr");
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
      checks.add(o.non_finite_files.empty(),
                 name + "no 'nan' or 'inf' in a CSV file");
    }

  test_tools::out() << std::endl;
  checks.assert_all();
  return 0;
}
