#ifndef dynamic_contact_tests_scenes_bad_input_cases_h
#define dynamic_contact_tests_scenes_bad_input_cases_h

// The cases of bad_input.cc, a table per group: every case starts from the
// valid scene prm/pressed_block.prm and changes one thing (or passes a wrong
// command line), and names what the error line must contain. bad_input.cc
// runs them and checks what a user sees.

#include "program_tools.h"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bad_input_cases
{
  using namespace program_tools;

  /** @p text with @p from replaced by @p to; the case is void if it is absent.
   */
  inline std::string
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

  /** prm/pressed_block.prm, the valid scene every case starts from. */
  inline const std::string &
  scene()
  {
    static const std::string text =
      read_text(test_tools::scene("pressed_block.prm"));
    return text;
  }

  /** A copy of the scene with @p from changed to @p to. */
  inline std::string
  edit(const std::string &from, const std::string &to)
  {
    return changed(scene(), from, to);
  }

  // Lines of the scene that the cases change.
  inline const std::string density = "set Density       = 1000";
  inline const std::string young   = "set Young modulus = 1e9";
  inline const std::string poisson = "set Poisson ratio = 0.3";
  inline const std::string step    = "set Time step = 1";
  inline const std::string end     = "set End time  = 8";
  inline const std::string traction_expression =
    "set Function expression = 0; -P";
  inline const std::string rectangle   = "set Type        = rectangle";
  inline const std::string repetitions = "set Repetitions = 4, 2";
  inline const std::string contact     = "set Contact  = 2";

  /** Binary content: every byte value, control characters first. */
  inline std::string
  garbage()
  {
    std::string bytes;
    for (unsigned int i = 0; i < 512; ++i)
      bytes += static_cast<char>(i % 256);
    return bytes;
  }

  /** The arguments "scene.prm --set S" for each S of @p settings. */
  inline std::vector<std::string>
  with_sets(const std::vector<std::string> &settings)
  {
    std::vector<std::string> arguments = {"scene.prm"};
    for (const auto &s : settings)
      arguments.insert(arguments.end(), {"--set", s});
    return arguments;
  }

  /**
   * One bad input (or a control) and what the program must say about it. A
   * row of the tables below reads {name, scene.prm, what the error line
   * names, the line of scene.prm it is in}, then the exit code and the
   * command line where they are not 1 and "scene.prm".
   */
  struct Case
  {
    std::string name;
    /** Written to scene.prm in the case's directory if given. */
    std::optional<std::string> prm;
    /** What the error line must contain. */
    std::vector<std::string> names;
    /** If not empty: the line of scene.prm (its text) the error is in. */
    std::string line_of = "";
    /** 0: a control that must run; 1: input error; 2: usage error. */
    int expected_code = 1;
    /** The command line. */
    std::vector<std::string> arguments = {"scene.prm"};
    /** Further files to write into the case's directory. */
    std::vector<std::pair<std::string, std::string>> extra_files = {};
    /** Found only while running: run_status must read "failed: ...". */
    bool runtime = false;
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

    /** This case with the file @p file (@p text) beside scene.prm. */
    Case
    with_file(const std::string &file, const std::string &text) const
    {
      Case c = *this;
      c.extra_files.emplace_back(file, text);
      return c;
    }

    /** This case with a named pipe @p file beside scene.prm. */
    Case
    with_named_pipe(const std::string &file) const
    {
      Case c = *this;
      c.fifo = file;
      return c;
    }

    /** This case with the error found only while running. */
    Case
    found_while_running() const
    {
      Case c    = *this;
      c.runtime = true;
      return c;
    }
  };

  /** A case of the scene and the command line @p arguments. */
  inline Case
  run_with(const std::string              &name,
           const std::vector<std::string> &arguments,
           const int                       code,
           const std::vector<std::string> &names)
  {
    return {name, scene(), names, "", code, arguments};
  }

  /** A case of the scene and --set @p settings. */
  inline Case
  set_case(const std::string              &name,
           const std::vector<std::string> &settings,
           const int                       code,
           const std::vector<std::string> &names)
  {
    return run_with(name, with_sets(settings), code, names);
  }

  /** The file itself, and values that cannot be read. */
  inline std::vector<Case>
  file_cases()
  {
    return {
      // Controls: valid input runs to completion.
      {"control_valid_scene", scene(), {}, "", 0},

      // The file itself.
      {"empty_file", "", {"scene.prm", "empty"}},
      {"only_comments", "# nothing set\n\n", {"scene.prm", "empty"}},
      {"missing_file", std::nullopt, {"missing.prm"}, "", 1, {"missing.prm"}},
      {"binary_garbage_file", garbage(), {"scene.prm"}},
      {"unknown_entry_top_level",
       scene() + "\nset Foo = 1\n",
       {"scene.prm", "Foo"},
       "set Foo = 1"},
      {"unknown_entry_in_subsection",
       edit(density, density + "\n  set Foo = 1"),
       {"scene.prm", "Material/Foo"},
       "set Foo = 1"},
      {"removed_entry",
       scene() + "\nsubsection Friction\n  set Acceleration depth = 2\nend\n",
       {"scene.prm", "Friction/Acceleration depth", "removed"},
       "set Acceleration depth = 2"},
      {"unknown_subsection",
       edit("subsection Foundation", "subsection Fundation"),
       {"scene.prm", "Fundation"},
       "subsection Fundation"},
      {"misspelt_entry",
       edit(young, "set Youngs modulus = 1e9"),
       {"scene.prm", "Material/Youngs modulus"},
       "set Youngs modulus = 1e9"},
      {"malformed_value",
       edit(density, "set Density = abc"),
       {"scene.prm", "Material/Density", "abc"},
       "set Density = abc"},
      {"nan_value",
       edit(density, "set Density = nan"),
       {"scene.prm", "Material/Density", "nan"},
       "set Density = nan"},
      {"dimension_4",
       edit("set Dimension = 2", "set Dimension = 4"),
       {"scene.prm", "Dimension", "4"},
       "set Dimension = 4"},
    };
  }

  /**
   * Values out of range: the line of the scene that sets an entry
   * ("Section/Name"), and the value it is set to instead.
   */
  struct OutOfRange
  {
    std::string name, line, entry, value;
  };
  inline const std::vector<OutOfRange> out_of_range = {
    {"density_zero", density, "Material/Density", "0"},
    {"density_negative", density, "Material/Density", "-1000"},
    {"young_modulus_zero", young, "Material/Young modulus", "0"},
    {"young_modulus_negative", young, "Material/Young modulus", "-1e9"},
    {"poisson_ratio_0.5", poisson, "Material/Poisson ratio", "0.5"},
    {"poisson_ratio_-1", poisson, "Material/Poisson ratio", "-1"},
    {"time_step_zero", step, "Time/Time step", "0"},
    {"time_step_negative", step, "Time/Time step", "-1"},
    {"end_time_zero", end, "Time/End time", "0"},
    {"end_time_negative", end, "Time/End time", "-8"}};

  /** Values out of range, boundary conditions and functions. */
  inline std::vector<Case>
  value_cases()
  {
    std::vector<Case> cases;
    for (const auto &[name, line, entry, value] : out_of_range)
      cases.push_back(
        {name,
         edit(line, "set " + entry.substr(entry.find('/') + 1) + " = " + value),
         {entry}});
    const std::vector<Case> more = {
      // The entry of the time scheme's own subsection since the schemes
      // are plugins: the old place names both new ones.
      set_case("spectral_radius_old_place",
               {"Time/Spectral radius at infinity=0.5"},
               1,
               {"Time/Spectral radius at infinity",
                "Time/Bathe/Spectral radius at infinity",
                "Time/Sdirk/Spectral radius at infinity"}),
      set_case("spectral_radius_above_one",
               {"Time/Scheme=bathe",
                "Time/Bathe/Spectral radius at infinity=1.5"},
               1,
               {"Time/Bathe/Spectral radius at infinity"}),
      // A scheme without a local error estimate cannot choose its steps.
      set_case("adaptive_without_estimate",
               {"Time/Scheme=trapezoidal", "Time/Adaptive=true"},
               1,
               {"Time/Adaptive", "Time/Scheme = trapezoidal"}),
      set_case("slip_length_with_sdirk",
               {"Time/Scheme=sdirk", "Friction/Slip length=0.01"},
               1,
               {"Friction/Slip length", "Time/Scheme"}),
      set_case("slip_length_negative",
               {"Friction/Slip length=-1"},
               1,
               {"Friction/Slip length"}),

      // Boundary conditions against the mesh (ids 0..3 of the rectangle).
      {"boundary_id_twice",
       edit("set Clamped  =", "set Clamped  = 2"),
       {"boundary id 2",
        "Boundary conditions/Clamped",
        "Boundary conditions/Contact"}},
      {"boundary_id_unassigned",
       edit("set Roller   = 0, 1", "set Roller   = 0"),
       {"Boundary conditions", "boundary id 1"}},
      {"boundary_id_not_in_mesh",
       edit(contact, "set Contact  = 2\n  set Free = 7"),
       {"Boundary conditions/Free", "boundary id 7"}},

      // Functions.
      {"function_does_not_parse",
       edit(traction_expression, "set Function expression = 0; -P*("),
       {"Boundary conditions/Traction function/Function expression"}},
      {"function_wrong_number_of_components",
       edit(traction_expression, "set Function expression = -P"),
       {"Boundary conditions/Traction function/Function expression"}},
    };
    cases.insert(cases.end(), more.begin(), more.end());
    return cases;
  }

  /**
   * A Gmsh mesh of the block (1 x 0.5, two quadrilaterals): the control
   * tags the right, bottom and top edges 1, 2, 3 and leaves the left one
   * untagged (deal.II gives it id 0), as the rectangle's ids; the other tags
   * the left and right edges 10, so ids 0 and 1 named by Roller are missing.
   */
  inline std::string
  msh(const std::string &side_tag, const std::string &left_line)
  {
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
  }

  /** The control mesh with names of its physical groups. */
  inline std::string
  named_msh()
  {
    const std::string names =
      "$PhysicalNames\n4\n1 1 \"right\"\n1 2 \"bottom\"\n1 3 \"top\"\n"
      "2 5 \"block\"\n$EndPhysicalNames\n";
    std::string m = msh("1", "");
    return m.insert(m.find("$Nodes"), names);
  }

  /** The scene on the mesh of block.msh. */
  inline std::string
  gmsh_scene()
  {
    return edit(rectangle,
                "set Type        = gmsh\n  set Mesh file = block.msh");
  }

  /** The same, its boundaries named by physical groups. */
  inline std::string
  names_scene()
  {
    return changed(changed(changed(gmsh_scene(),
                                   "set Roller   = 0, 1",
                                   "set Roller   = 0, right"),
                           contact,
                           "set Contact  = bottom"),
                   "set Traction = 3",
                   "set Traction = top");
  }

  /** Gmsh meshes, and the output directory. */
  inline std::vector<Case>
  mesh_cases()
  {
    const std::string gmsh  = gmsh_scene();
    const std::string named = names_scene();
    return {
      {"gmsh_mesh_file_missing",
       edit(rectangle, "set Type        = gmsh\n  set Mesh file = missing.msh"),
       {"Geometry/Mesh file", "missing.msh"}},
      Case{"control_gmsh_scene", gmsh, {}, "", 0}.with_file("block.msh",
                                                            msh("1", "")),
      Case{"gmsh_mesh_lacks_boundary_ids",
           gmsh,
           {"Boundary conditions/Roller", "boundary id 0", "block.msh"}}
        .with_file("block.msh", msh("10", "6 1 2 10 10 4 1\n")),
      Case{"gmsh_mesh_file_garbage", gmsh, {"Geometry/Mesh file", "block.msh"}}
        .with_file("block.msh", garbage()),
      Case{"gmsh_mesh_file_truncated",
           gmsh,
           {"Geometry/Mesh file", "block.msh"}}
        .with_file("block.msh", msh("1", "").substr(0, 120)),
      // Issue 12: Gmsh meshes this program cannot use are refused before
      // deal.II reads them (it crashed on triangles), and the boundary lists
      // may name physical groups.
      Case{"control_gmsh_physical_names", named, {}, "", 0}.with_file(
        "block.msh", named_msh()),
      Case{"gmsh_unknown_physical_name",
           changed(named, "set Contact  = bottom", "set Contact  = bottm"),
           {"Boundary conditions/Contact",
            "'bottm'",
            "block.msh",
            "'bottom' (2), 'right' (1), 'top' (3)"}}
        .with_file("block.msh", named_msh()),
      {"boundary_name_with_rectangle",
       edit(contact, "set Contact  = bottom"),
       {"Boundary conditions/Contact", "'bottom'", "Geometry/Type = gmsh"}},
      {"boundary_id_out_of_range",
       edit(contact, "set Contact  = 2, 256"),
       {"Boundary conditions/Contact", "256", "0 to 255"}},
      // Gmsh's default: triangles (2D), tetrahedra (3D).
      Case{"gmsh_triangles",
           gmsh,
           {"Geometry/Mesh file",
            "block.msh",
            "2 3-node triangles",
            "Gmsh element type 2",
            "Mesh.RecombineAll = 1",
            "Mesh.SubdivisionAlgorithm = 1"}}
        .with_file(
          "block.msh",
          "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
          "2 1 0 0\n3 1 0.5 0\n4 0 0.5 0\n$EndNodes\n$Elements\n6\n"
          "1 1 2 2 2 1 2\n2 1 2 1 1 2 3\n3 1 2 3 3 3 4\n4 1 2 0 0 4 1\n"
          "5 2 2 5 5 1 2 3\n6 2 2 5 5 1 3 4\n$EndElements\n"),
      Case{"gmsh_tetrahedra",
           changed(read_text(test_tools::scene("pressed_block_3d.prm")),
                   rectangle,
                   "set Type        = gmsh\n  set Mesh file = block.msh"),
           {"Geometry/Mesh file",
            "block.msh",
            "1 4-node tetrahedron",
            "Gmsh element type 4",
            "Mesh.SubdivisionAlgorithm = 2"}}
        .with_file("block.msh",
                   "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n"
                   "1 0 0 0 1 0.5 0.5 0 0\n$EndEntities\n$Nodes\n1 4 1 4\n"
                   "3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 0.5 0\n0 0 0.5\n"
                   "$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n"
                   "$EndElements\n"),
      Case{"gmsh_binary",
           gmsh,
           {"Geometry/Mesh file", "block.msh", "binary", "ASCII"}}
        .with_file("block.msh", "$MeshFormat\n4.1 1 8\n" + garbage()),
      {"output_directory_not_creatable",
       edit("set Directory = output-pressed-block",
            "set Directory = scene.prm/results"),
       {"Output/Directory", "scene.prm/results"}},
    };
  }

  /** Errors found while running, values that are not finite, scenes that
   *  cannot fit. */
  inline std::vector<Case>
  running_cases()
  {
    return {
      // Found only while running: the run must end as failed, not completed.
      Case{"newton_iterations_exhausted",
           edit("subsection Output",
                "subsection Solver\n  set Maximum Newton "
                "iterations = 1\nend\n\nsubsection Output"),
           {"Solver/Maximum Newton iterations"}}
        .found_while_running(),

      // Values that are not finite: named before anything is written.
      {"traction_not_finite",
       edit(traction_expression, "set Function expression = 0; -P/0"),
       {"Boundary conditions/Traction function", "-P/0", "-inf"}},
      {"initial_velocity_not_finite",
       scene() + "\nsubsection Initial conditions\n  subsection Velocity\n"
                 "    set Function expression = 1/0; 0\n  end\nend\n",
       {"Initial conditions/Velocity", "1/0"}},
      {"body_force_not_finite",
       scene() + "\nsubsection Body force\n  set Function expression = 0; "
                 "sqrt(-1)\nend\n",
       {"Body force", "sqrt(-1)"}},
      {"initial_gap_not_finite",
       edit("subsection Foundation",
            "subsection Foundation\n  subsection Initial gap\n    set "
            "Function expression = log(x-2)\n  end"),
       {"Foundation/Initial gap", "log(x-2)"}},
      {"friction_not_finite",
       scene() + "\nsubsection Friction\n  set Law = expression\n  subsection "
                 "Expression\n    set Function expression = 0.5+sqrt(1-s)\n  "
                 "end\nend\n",
       {"Friction/Expression", "0.5+sqrt(1-s)", "not finite"}},
      // NaN only near t = 2.1, between the sampled times (0, 1, 8 and every
      // 0.5 s), reached by the steps of k = 0.3: the run stops after step 6.
      Case{"traction_not_finite_at_step_7",
           changed(edit(step, "set Time step = 0.3"),
                   traction_expression,
                   "set Function expression = 0; "
                   "-P*(1+0*sqrt(abs(t-2.1)-0.05))"),
           {"Boundary conditions/Traction function",
            "t = 2.1",
            "last good state (step 6)"}}
        .found_while_running(),
      {"velocity_strengthening",
       scene() +
         "\nsubsection Friction\n  set Law = expression\n  subsection "
         "Expression\n    set Function expression = 1 - 0.5*exp(-2000*s)\n  "
         "end\nend\n",
       {"Friction/Expression",
        "increases with the slip rate",
        "Friction/Velocity strengthening"}},

      // Scenes that cannot fit: refused with the estimate, before allocating.
      {"repetitions_huge",
       edit(repetitions, "set Repetitions = 100000, 100000"),
       {"too large", "1.0e+10 cells", "Geometry/Repetitions"}},
      {"refinements_20",
       edit(repetitions, repetitions + "\n  set Global refinements = 20"),
       {"too large", "Geometry/Global refinements"}},
      {"memory_too_small",
       edit(repetitions, repetitions + "\n  set Global refinements = 13"),
       {"does not fit into memory", "5.4e+08 cells", "GB"}},
    };
  }

  /**
   * Entries of the earlier flat layout (their new place named) and
   * solver entries that do not go together.
   */
  inline std::vector<Case>
  layout_cases()
  {
    return {
      // An entry of the flat layout of earlier versions: its new place named.
      {"old_layout_entry",
       scene() + "\nsubsection Friction\n  set Decay rate = 3\nend\n",
       {"Friction/Decay rate",
        "Friction/Exponential/Decay rate",
        "scripts/update-prm"}},
      // A contact solver's entry of the flat Solver section.
      {"old_solver_entry",
       scene() + "\nsubsection Solver\n  set Condensed limit = 0\nend\n",
       {"Solver/Condensed limit",
        "Solver/Condensed/Limit",
        "scripts/update-prm"}},
      {"old_amg_entry",
       scene() + "\nsubsection Solver\n  set AMG aggregation = plain\nend\n",
       {"Solver/AMG aggregation", "Solver/AMG/Aggregation"}},
      {"gmg_degree_3",
       scene() + "\nsubsection Finite element\n  set Polynomial degree = "
                 "3\nend\nsubsection Solver\n  set Preconditioner = "
                 "GMG\nend\n",
       {"Solver/Preconditioner = GMG", "degree up to 2", "degree = 3"}},
      {"matrix_free_condensed",
       scene() + "\nsubsection Solver\n  set Contact solver = condensed\n  "
                 "set Preconditioner = matrix-free GMG\nend\n",
       {"matrix-free GMG", "stores no K0", "Solver/Contact solver"}},
    };
  }

  /** The parameter file itself. */
  inline std::vector<Case>
  parameter_file_cases()
  {
    return {
      {"includes_itself",
       "include scene.prm\n" + scene(),
       {"scene.prm", "includes itself"}},
      Case{"includes_itself_indirectly",
           "include other.prm\n" + scene(),
           {"scene.prm -> other.prm -> scene.prm", "includes itself"}}
        .with_file("other.prm", "include scene.prm\n"),
      {"includes_missing_file",
       "include missing.prm\n" + scene(),
       {"missing.prm", "scene.prm"}},
      run_with(
        "directory_as_parameter_file", {"."}, 1, {"'.'", "is a directory"}),
      Case{"named_pipe_as_parameter_file",
           std::nullopt,
           {"pipe.prm", "named pipe"},
           "",
           1,
           {"pipe.prm"}}
        .with_named_pipe("pipe.prm"),
      {"control_byte_order_mark", "\xEF\xBB\xBF" + scene(), {}, "", 0},
    };
  }

  /** --set and the command line. */
  inline std::vector<Case>
  command_line_cases()
  {
    return {
      // --set.
      set_case(
        "set_unknown_entry", {"Material/Foo=1"}, 1, {"--set", "Material/Foo"}),
      set_case("set_removed_entry",
               {"Friction/Acceleration depth=2"},
               1,
               {"--set", "Friction/Acceleration depth", "removed"}),
      set_case("set_removed_look_ahead",
               {"Mesh refinement/Load following/Look-ahead steps=3"},
               1,
               {"--set",
                "Mesh refinement/Load following/Look-ahead steps",
                "removed"}),
      set_case(
        "set_unknown_subsection", {"Foo/Bar=1"}, 1, {"--set", "Foo/Bar"}),
      set_case("set_value_out_of_range",
               {"Material/Density=-1"},
               1,
               {"Material/Density"}),
      set_case("set_malformed_value",
               {"Time/Time step=abc"},
               1,
               {"Time/Time step", "abc"}),

      // The command line (usage errors, exit code 2). --set without '=' cannot
      // be read at all, like --set without an argument: a usage error.
      set_case("set_without_equals",
               {"Material/Density"},
               2,
               {"--set", "Material/Density"}),
      run_with("set_without_argument", {"scene.prm", "--set"}, 2, {"--set"}),
      run_with(
        "unknown_option", {"scene.prm", "--frobnicate"}, 2, {"--frobnicate"}),
      run_with("two_parameter_files",
               {"scene.prm", "other.prm"},
               2,
               {"scene.prm", "other.prm"})
        .with_file("other.prm", scene()),
      run_with("no_parameter_file", {}, 2, {"parameter file"}),
    };
  }
} // namespace bad_input_cases

#endif
