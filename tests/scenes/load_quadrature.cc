// A wheel load narrower than the cells (FaceLoadQuadrature): the rail's
// patch, g = F exp(-psi (x - c t)^2) exp(-psi_z (z - z0)^2), about 1.6 cm
// wide across the rail, on 20 x 2 x 2 cells of 5 cm across. After one step
// the applied force of the force balance (the same face integrals as the
// load vector) equals the exact integral of the load to 1e-6, with Q1 and
// Q2 and in 2D (a patch of 1 cm on cells of 12.5 cm); with
// Load quadrature tolerance = 0 (one Gauss rule of degree + 2 points per
// direction) it is short by more than 1e-3. The load vector and the force
// balance agree: the step's forces balance (applied + foundation +
// supports = inertia) to 1e-8 of the applied force.

#include <deal.II/base/mpi.h>

#include "test_tools.h"

#include <cmath>

using namespace DynamicContact;

namespace
{
  // The rail scene's load constants (prm/rail_3d.prm).
  constexpr double F = 1e10, psi = 50, c = 2, psi_z = 2000, z0 = 0.05;

  /** int_a^b exp(-p (x - m)^2) dx. */
  double
  gaussian_integral(const double p,
                    const double m,
                    const double a,
                    const double b)
  {
    const double s = std::sqrt(p);
    return std::sqrt(M_PI / p) / 2 *
           (std::erf(s * (b - m)) - std::erf(s * (a - m)));
  }

  /**
   * One step of @p scene with @p overrides; the relative error of the
   * applied force's y component against @p exact, and the step's force
   * balance defect relative to the applied force.
   */
  template <int dim>
  std::pair<double, double>
  one_step(const std::string              &scene,
           const std::vector<std::string> &overrides,
           const std::function<double(double)> &exact)
  {
    auto run = test_tools::make<dim>(test_tools::scene(scene), overrides);
    run->initialize();
    run->advance();
    const auto   &record  = run->time_series().back();
    const auto   &f       = record.forces;
    const double  applied = f.applied[1];
    const double  error   = std::abs(applied - exact(record.time)) /
                         std::abs(exact(record.time));
    double defect = 0;
    for (unsigned int d = 0; d < dim; ++d)
      defect =
        std::max(defect,
                 std::abs(f.applied[d] + f.contact[d] + f.reaction[d] -
                          f.inertia[d]));
    return {error, defect / std::abs(applied)};
  }

  void
  report(const std::string                &what,
         const std::pair<double, double> &result,
         const bool                        resolved)
  {
    if (resolved)
      test_tools::check(result.first < 1e-6,
                        what + ": applied force exact to 1e-6");
    else
      test_tools::check(result.first > 1e-3,
                        what + ": one Gauss rule is short by more than 1e-3");
    test_tools::check(result.second < 1e-8,
                      what + ": forces balance to 1e-8");
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string                k = "Time/End time=0.0078125";

  const auto rail = [](const double t) {
    return -F * gaussian_integral(psi, c * t, 0, 2) *
           gaussian_integral(psi_z, z0, 0, 0.1);
  };
  for (const std::string tolerance : {"1e-6", "0"})
    report("3D, Q1, 20 x 2 x 2, tolerance " + tolerance,
           one_step<3>("rail_3d.prm",
                       {"Geometry/Repetitions=20, 2, 2",
                        "Boundary conditions/Load quadrature tolerance=" +
                          tolerance,
                        k,
                        "Output/Directory=output-q1"},
                       rail),
           tolerance != "0");
  report("3D, Q2, 10 x 1 x 1",
         one_step<3>("rail_3d.prm",
                     {"Geometry/Repetitions=10, 1, 1",
                      "Finite element/Polynomial degree=2",
                      k,
                      "Output/Directory=output-q2"},
                     rail),
         true);

  // 2D: the paper's load narrowed to psi = 20000 (about 1 cm) on 16 x 4.
  const double psi_2d  = 20000;
  const auto   paper = [&](const double t) {
    return -F * gaussian_integral(psi_2d, c * t + 0.5, 0, 2);
  };
  for (const std::string tolerance : {"1e-6", "0"})
    report("2D, Q1, 16 x 4, tolerance " + tolerance,
           one_step<2>(
             "barboteu_danan_2016_small.prm",
             {"Geometry/Repetitions=16, 4",
              "Boundary conditions/Traction function/Function constants="
              "F=1e10, psi=20000, c=2",
              "Boundary conditions/Traction function/Function expression="
              "0; -F*exp(-psi*(x-c*t-0.5)^2)",
              "Boundary conditions/Load quadrature tolerance=" + tolerance,
              k,
              "Output/Directory=output-2d"},
             paper),
           tolerance != "0");
}
