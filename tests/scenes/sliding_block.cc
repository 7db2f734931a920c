// A block pressed by P and sheared by T on the foundation, constant
// Coulomb friction mu (prm/sliding_block.prm, prm/sliding_block_3d.prm):
//   T > mu P: the block slides with the acceleration (|T| - mu P)/(rho H),
//             along T (in 3D T is oblique: the slip direction is not an axis),
//             every contact node slipping;
//   T < mu P: it sticks: no slip velocity, no acceleration, every node stuck.
// Both Newton implementations in 3D; the .mpirun=2 variant runs on two
// processes and must give the same output.

#include "test_tools.h"

using namespace DynamicContact;

template <int dim>
void
check_block(const std::string       &name,
            const double             T,
            std::vector<std::string> overrides)
{
  const double P = 1e6, mu = 0.5, rho = 1000, H = 0.2, L = 1;
  const double area = (dim == 3 ? L * L : L);
  overrides.push_back("Output/Directory=output-" + name);
  overrides.push_back(
    "Boundary conditions/Traction function/Function constants=P=1e6, T=" +
    std::to_string(T));
  auto simulator =
    test_tools::run<dim>(test_tools::scene(dim == 2 ? "sliding_block.prm" :
                                                      "sliding_block_3d.prm"),
                         overrides);
  const auto &last = simulator->time_series().back();

  // The shear direction.
  Tensor<1, dim> direction;
  if (dim == 2)
    direction[0] = 1;
  else
    {
      direction[0]       = 0.6;
      direction[dim - 1] = 0.8;
    }
  const Tensor<1, dim> a = last.forces.inertia / (rho * H * area);

  test_tools::check(test_tools::close(last.normal_force, P * area, 1e-8),
                    name + ": normal force P |Gamma_3| once settled");
  if (T > mu * P)
    {
      const double expected = (T - mu * P) / (rho * H);
      test_tools::check((a - expected * direction).norm() <= 1e-8 * expected,
                        name + ": slides with (|T| - mu P)/(rho H) along T");
      test_tools::check(last.statistics.n_slip == last.statistics.n_contact &&
                          last.statistics.n_stick == 0,
                        name + ": every contact node slips");
      test_tools::check(test_tools::close(last.tangential_force,
                                          mu * P * area,
                                          1e-8),
                        name + ": friction force mu P |Gamma_3|");
    }
  else
    {
      double max_slip = 0;
      for (const auto &s : simulator->simulator().node_states())
        max_slip = std::max(max_slip, s.slip_rate);
      max_slip = Utilities::MPI::max(max_slip, MPI_COMM_WORLD);
      test_tools::check(max_slip < 1e-10, name + ": no slip velocity");
      test_tools::check(a.norm() < 1e-8 * T / (rho * H),
                        name + ": no acceleration");
      test_tools::check(last.statistics.n_stick == last.statistics.n_contact &&
                          last.statistics.n_slip == 0,
                        name + ": every contact node sticks");
      // The friction forces (vector sum) hold the shear.
      Tensor<1, dim> friction;
      for (const auto &s : simulator->simulator().node_states())
        friction += s.friction_force;
      for (unsigned int d = 0; d < dim; ++d)
        friction[d] = Utilities::MPI::sum(friction[d], MPI_COMM_WORLD);
      test_tools::check((friction - T * area * direction).norm() <=
                          1e-8 * T * area,
                        name + ": the friction forces balance the shear");
    }
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_block<2>("slide_2d", 6e5, {});
  check_block<2>("stick_2d", 4e5, {});
  check_block<3>("slide_3d", 6e5, {});
  check_block<3>("slide_3d_assembled",
                 6e5,
                 {"Solver/Contact solver=assembled"});
  check_block<3>("stick_3d", 4e5, {});
}
