// A block pressed uniformly onto the foundation with roller sides
// (prm/pressed_block.prm): uniaxial strain, analytic steady state.
//   penetration      u_nu = P/c_nu                at every contact node,
//   top displacement -u_y = P/c_nu + P H/M,       M = lambda + 2 mu,
// to 1e-8 relative, in plane strain, plane stress and 3D, with both Newton
// implementations.

#include "test_tools.h"

using namespace DynamicContact;

template <int dim>
void
check_block(const std::string &name, std::vector<std::string> overrides)
{
  const double P = 1e7, c_nu = 1e10, H = 0.5, E = 1e9, kappa = 0.3;
  const bool   plane_stress =
    std::find(overrides.begin(),
              overrides.end(),
              "Material/Plane model=plane stress") != overrides.end();
  const double M           = (dim == 2 && plane_stress) ?
                               E / (1 - kappa * kappa) :
                               E * (1 - kappa) / ((1 + kappa) * (1 - 2 * kappa));
  const double penetration = P / c_nu;
  const double top         = P / c_nu + P * H / M;

  overrides.push_back("Output/Directory=output-" + name);
  auto simulator =
    test_tools::run<dim>(test_tools::scene(dim == 2 ? "pressed_block.prm" :
                                                      "pressed_block_3d.prm"),
                         overrides);

  double      worst  = 0;
  const auto &nodes  = simulator->simulator().contact().nodes();
  const auto &states = simulator->simulator().node_states();
  for (unsigned int i = 0; i < nodes.size(); ++i)
    worst =
      std::max(worst,
               std::abs(states[i].normal.u_nu - penetration) / penetration);
  worst = Utilities::MPI::max(worst, MPI_COMM_WORLD);
  test_tools::check(worst <= 1e-8,
                    name + ": penetration P/c_nu at every node to 1e-8");

  double worst_top = 0;
  for (const double x : {0., 0.3, 0.5, 1.})
    {
      Point<dim> p;
      p[0] = x;
      p[1] = H;
      if (dim == 3)
        p[2] = 0.25;
      const double u_y =
        simulator->simulator().fields().point_displacement(p)[1];
      worst_top        = std::max(worst_top, std::abs(-u_y - top) / top);
    }
  test_tools::check(worst_top <= 1e-8,
                    name + ": top displacement P/c_nu + P H/M to 1e-8");
  const auto &last = simulator->time_series().back();
  test_tools::check(test_tools::close(last.normal_force,
                                      P * (dim == 3 ? 0.5 : 1.),
                                      1e-8),
                    name + ": total normal force P |Gamma_3| to 1e-8");
}


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_block<2>("plane_strain", {});
  check_block<2>("plane_stress", {"Material/Plane model=plane stress"});
  check_block<2>("assembled", {"Solver/Contact solver=assembled"});
  check_block<3>("3d", {});
  check_block<3>("3d_assembled", {"Solver/Contact solver=assembled"});
}
