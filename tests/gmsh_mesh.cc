// Gmsh meshes (issue 12): the example prm/gmsh_rail.prm (the small paper
// scene on prm/gmsh_rail.msh, MSH 4.1, its boundary conditions naming the
// physical groups 'ends', 'foundation', 'load') runs; the same mesh in MSH
// 2.2 (prm/gmsh_rail_msh22.msh) and the groups given by their numbers give
// the same time_series.csv digit for digit; and the rectangle of
// prm/barboteu_danan_2016_small.prm (the same 32 x 8 cells) agrees to
// round-off. A mesh of triangles on two processes is refused with one
// error naming the file, the element type and how to recombine it, exit
// code 1, nothing written.

#include "program_tools.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace program_tools;

namespace
{
  const std::vector<std::string> few_steps = {"--set",
                                              "Time/End time=0.0625",
                                              "--set",
                                              "Output/Output every=0"};

  Outcome
  run(const std::string       &prm,
      const std::string       &directory,
      std::vector<std::string> more,
      const unsigned int       processes = 0)
  {
    std::vector<std::string> arguments = {prm,
                                          "--set",
                                          "Output/Directory=" + directory};
    arguments.insert(arguments.end(), few_steps.begin(), few_steps.end());
    arguments.insert(arguments.end(), more.begin(), more.end());
    Launch launch;
    launch.name      = directory;
    launch.processes = processes;
    launch.timeout   = 300;
    return execute(arguments, launch);
  }

  /**
   * The largest difference of the physical columns of two time series,
   * relative to the largest magnitude of the column; 1 if the files do not
   * have the same rows and columns.
   */
  double
  difference(const std::vector<std::vector<std::string>> &a,
             const std::vector<std::vector<std::string>> &b)
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
        const auto c = std::find(a[0].begin(), a[0].end(), name) - a[0].begin();
        if (c == static_cast<long>(a[0].size()))
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
} // namespace


int
main()
{
  // No MPI here: the runs under mpiexec must not inherit a singleton's
  // MPI environment (as in tests/checkpoint_restart.cc).
  Checks checks;

  const std::string example = test_tools::scene("gmsh_rail.prm");
  const auto        msh41   = run(example, "msh41", {});
  const auto        msh22 =
    run(example, "msh22", {"--set", "Geometry/Mesh file=gmsh_rail_msh22.msh"});
  const auto numbers = run(example,
                           "numbers",
                           {"--set",
                            "Boundary conditions/Clamped=1",
                            "--set",
                            "Boundary conditions/Contact=2",
                            "--set",
                            "Boundary conditions/Traction=3"});
  const auto rectangle =
    run(test_tools::scene("barboteu_danan_2016_small.prm"), "rectangle", {});

  for (const auto &[name, o] :
       std::vector<std::pair<std::string, const Outcome *>>{
         {"MSH 4.1, names", &msh41},
         {"MSH 2.2, names", &msh22},
         {"MSH 4.1, numbers", &numbers},
         {"rectangle", &rectangle}})
    {
      const bool ok = o->succeeded() && error_lines(*o).empty();
      test_tools::out() << name << ": exit code zero, no error: " << yes_no(ok)
                        << std::endl;
      if (!ok)
        std::cerr << name << ": " << o->err << std::endl;
      checks.add(ok, name + ": runs");
    }

  const auto series = [](const std::string &d) {
    return test_tools::read_csv(fs::path(d) / "time_series.csv");
  };
  const auto s41 = series("msh41"), s22 = series("msh22"),
             sn = series("numbers"), sr = series("rectangle");
  const bool rows = s41.size() == 10; // the header, row 0 and 8 steps
  test_tools::out() << "MSH 4.1: 8 steps in time_series.csv: " << yes_no(rows)
                    << std::endl;
  checks.add(rows, "the example ran 8 steps");
  const bool same_22 = !s41.empty() && s41 == s22;
  test_tools::out() << "MSH 2.2 and MSH 4.1: the same time_series.csv: "
                    << yes_no(same_22) << std::endl;
  checks.add(same_22, "MSH 2.2 and 4.1 give the same results");
  const bool same_numbers = !s41.empty() && s41 == sn;
  test_tools::out()
    << "physical groups by number and by name: the same time_series.csv: "
    << yes_no(same_numbers) << std::endl;
  checks.add(same_numbers, "numbers and names give the same results");
  const double d = difference(s41, sr);
  test_tools::out() << "rectangle and Gmsh mesh: physical columns agree to "
                       "1e-8 of their scale: "
                    << yes_no(d <= 1e-8) << std::endl;
  checks.add(d <= 1e-8, "the Gmsh mesh and the rectangle agree");
  const bool contact =
    !s41.empty() && s41.size() > 1 &&
    std::stod(s41.back()[std::find(s41[0].begin(), s41[0].end(), "n_contact") -
                         s41[0].begin()]) > 0;
  test_tools::out() << "the rail is in contact at the last step: "
                    << yes_no(contact) << std::endl;
  checks.add(contact, "contact at the last step (the names reached Contact)");

  // Triangles (Gmsh's default mesh), on two processes: one clear error.
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
        {"--set",
         "Geometry/Mesh file=" +
           (fs::current_path() / "triangles.msh").string()},
        2);
  const auto errors = error_lines(triangles);
  const bool one_error =
    triangles.exited && triangles.code == 1 && errors.size() == 1;
  test_tools::out() << "triangles on 2 processes: exit code 1, one error "
                       "line: "
                    << yes_no(one_error) << std::endl;
  if (!one_error)
    std::cerr << "triangles: " << triangles.err << std::endl;
  checks.add(one_error, "triangles: exit code 1 and one error line");
  for (const std::string word : {"Geometry/Mesh file",
                                 "triangles.msh",
                                 "3-node triangle",
                                 "Gmsh element type 2",
                                 "Mesh.RecombineAll = 1",
                                 "Mesh.SubdivisionAlgorithm = 1"})
    {
      const bool named =
        errors.size() == 1 && errors[0].find(word) != std::string::npos;
      test_tools::out() << "  the error names '" << word
                        << "': " << yes_no(named) << std::endl;
      checks.add(named, "triangles: the error names " + word);
    }
  const bool nothing = !fs::exists("triangles");
  test_tools::out() << "  no output directory: " << yes_no(nothing)
                    << std::endl;
  checks.add(nothing, "triangles: nothing written");

  checks.assert_all();
  return 0;
}
