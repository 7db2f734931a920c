// Gmsh meshes (issue 12): the example prm/gmsh_rail.prm (the small paper
// scene on prm/gmsh_rail.msh, MSH 4.1, its boundary conditions naming the
// physical groups 'ends', 'foundation', 'load') runs; the same mesh in MSH
// 2.2 (prm/gmsh_rail_msh22.msh) and the groups given by their numbers give
// the same time_series.csv digit for digit; and the rectangle of
// prm/barboteu_danan_2016_small.prm (the same 32 x 8 cells) agrees to
// round-off. A mesh of triangles on two processes is refused with one
// error naming the file, the element type and how to recombine it, exit
// code 1, nothing written.

#include "run_checks.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace program_tools;
using namespace run_checks;

namespace
{
  using Table = std::vector<std::vector<std::string>>;

  const std::string example = test_tools::scene("gmsh_rail.prm");

  Outcome
  run(const std::string              &prm,
      const std::string              &directory,
      const std::vector<std::string> &more,
      const unsigned int              processes = 0)
  {
    return execute(with(with({prm, "--set", "Output/Directory=" + directory},
                             overrides({"Time/End time=0.0625",
                                        "Output/Output every=0"})),
                        more),
                   launch_of(directory, processes, 300));
  }

  /**
   * The largest difference of the physical columns of two time series,
   * relative to the largest magnitude of the column; 1 if the files do not
   * have the same rows and columns.
   */
  double
  difference(const Table &a, const Table &b)
  {
    if (a.empty() || a.size() != b.size() || a[0] != b[0])
      return 1;
    const std::vector<std::string> physical = {"time",
                                               "normal_force",
                                               "tangential_force",
                                               "reaction_force_y",
                                               "kinetic_energy",
                                               "elastic_energy",
                                               "foundation_energy",
                                               "total_energy",
                                               "n_contact",
                                               "n_stick",
                                               "n_slip",
                                               "dofs",
                                               "cells"};
    double                         worst    = 0;
    for (const auto &name : physical)
      {
        const auto c = column(a[0], name);
        if (c == a[0].size())
          return 1;
        double scale = 1e-300, d = 0;
        for (unsigned int r = 1; r < a.size(); ++r)
          {
            const double x = std::stod(a[r][c]), y = std::stod(b[r][c]);
            scale = std::max({scale, std::abs(x), std::abs(y)});
            d     = std::max(d, std::abs(x - y));
          }
        worst = std::max(worst, d / scale);
      }
    return worst;
  }

  /** A run of a scene: what it shows, its directory, scene and settings. */
  struct Scene
  {
    std::string              what;
    std::string              directory;
    std::string              prm;
    std::vector<std::string> settings;
  };

  const std::vector<Scene> scenes = {
    {"MSH 4.1, names", "msh41", example, {}},
    {"MSH 2.2, names",
     "msh22",
     example,
     {"Geometry/Mesh file=gmsh_rail_msh22.msh"}},
    {"MSH 4.1, numbers",
     "numbers",
     example,
     {"Boundary conditions/Clamped=1",
      "Boundary conditions/Contact=2",
      "Boundary conditions/Traction=3"}},
    {"rectangle",
     "rectangle",
     test_tools::scene("barboteu_danan_2016_small.prm"),
     {}}};

  void
  check_runs(const Scene &s, Checks &checks)
  {
    const Outcome o  = run(s.prm, s.directory, overrides(s.settings));
    const bool    ok = o.succeeded() && error_lines(o).empty();
    test_tools::out() << s.what << ": exit code zero, no error: " << yes_no(ok)
                      << std::endl;
    if (!ok)
      std::cerr << s.what << ": " << o.err << std::endl;
    checks.add(ok, s.what + ": runs");
  }

  /** The results of the meshes and of the ways of naming their groups. */
  void
  check_results(Checks &checks)
  {
    const auto series = [](const std::string &d) {
      return test_tools::read_csv(fs::path(d) / "time_series.csv");
    };
    const auto s41 = series("msh41"), s22 = series("msh22"),
               sn = series("numbers"), sr = series("rectangle");
    verdict(checks,
            s41.size() == 10, // the header, row 0 and 8 steps
            "MSH 4.1: 8 steps in time_series.csv",
            "the example ran 8 steps");
    verdict(checks,
            !s41.empty() && s41 == s22,
            "MSH 2.2 and MSH 4.1: the same time_series.csv",
            "MSH 2.2 and 4.1 give the same results");
    verdict(checks,
            !s41.empty() && s41 == sn,
            "physical groups by number and by name: the same time_series.csv",
            "numbers and names give the same results");
    verdict(checks,
            difference(s41, sr) <= 1e-8,
            "rectangle and Gmsh mesh: physical columns agree to 1e-8 of their "
            "scale",
            "the Gmsh mesh and the rectangle agree");
    verdict(checks,
            !s41.empty() && s41.size() > 1 &&
              std::stod(s41.back()[column(s41[0], "n_contact")]) > 0,
            "the rail is in contact at the last step",
            "contact at the last step (the names reached Contact)");
  }

  /** Triangles (Gmsh's default mesh), on two processes: one clear error. */
  void
  check_triangles(Checks &checks)
  {
    test_tools::write_text(
      "triangles.msh",
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$Entities\n0 0 1 0\n1 0 0 0 2 0.1 0 0 0\n$EndEntities\n"
      "$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n2 0 0\n2 0.1 0\n0 0.1 0\n"
      "$EndNodes\n"
      "$Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n2 1 3 4\n$EndElements\n");
    const auto triangles =
      run(example,
          "triangles",
          overrides({"Geometry/Mesh file=" +
                     (fs::current_path() / "triangles.msh").string()}),
          2);
    const auto errors = error_lines(triangles);
    const bool one_error =
      triangles.exited && triangles.code == 1 && errors.size() == 1;
    verdict(checks,
            one_error,
            "triangles on 2 processes: exit code 1, one error line",
            "triangles: exit code 1 and one error line");
    if (!one_error)
      std::cerr << "triangles: " << triangles.err << std::endl;
    for (const std::string word : {"Geometry/Mesh file",
                                   "triangles.msh",
                                   "3-node triangle",
                                   "Gmsh element type 2",
                                   "Mesh.RecombineAll = 1",
                                   "Mesh.SubdivisionAlgorithm = 1"})
      verdict(checks,
              one_line_naming(errors, {word}),
              "  the error names '" + word + "'",
              "triangles: the error names " + word);
    verdict(checks,
            !fs::exists("triangles"),
            "  no output directory",
            "triangles: nothing written");
  }
} // namespace


int
main()
{
  // No MPI here: the runs under mpiexec must not inherit a singleton's
  // MPI environment (as in tests/scenes/checkpoint_restart.cc).
  Checks checks;
  for (const auto &s : scenes)
    check_runs(s, checks);
  check_results(checks);
  check_triangles(checks);
  checks.assert_all();
  return 0;
}
