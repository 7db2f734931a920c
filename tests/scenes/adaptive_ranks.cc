// With adaptive refinement following the moving load, two processes give
// the same time_series.csv as one, to 1e-8 relative: the run on one process
// (MPI_COMM_SELF of rank 0) and the run on both (MPI_COMM_WORLD) are
// compared column by column. The mesh decisions (load following) are
// geometric, so both meshes are the same; the friction loop's tolerances
// are tightened to 1e-10 so that its stopping point (which round-off may
// move by one pass) does not limit the agreement.

#include "test_tools.h"

using namespace DynamicContact;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const std::vector<std::string> overrides = {
    "Friction/Convexification tolerance=1e-10",
    "Friction/Coefficient tolerance=1e-10"};

  std::vector<StepRecord<2>> serial;
  if (rank == 0)
    {
      auto o = overrides;
      o.push_back("Output/Directory=output-one");
      serial = test_tools::run<2>(test_tools::scene(
                                    "barboteu_danan_2016_adaptive_small.prm"),
                                  o,
                                  MPI_COMM_SELF)
                 ->time_series();
    }
  MPI_Barrier(MPI_COMM_WORLD);
  auto o = overrides;
  o.push_back("Output/Directory=output-all");
  const auto parallel =
    test_tools::run<2>(
      test_tools::scene("barboteu_danan_2016_adaptive_small.prm"), o)
      ->time_series();
  if (rank != 0)
    return 0;

  test_tools::out() << "processes: "
                    << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
                    << std::endl;
  test_tools::check(serial.size() == parallel.size() && serial.size() == 129,
                    "same number of steps");
  bool   same_mesh = true;
  double worst     = 0;
  for (unsigned int n = 0; n < serial.size(); ++n)
    {
      same_mesh = same_mesh && serial[n].cells == parallel[n].cells &&
                  serial[n].dofs == parallel[n].dofs;
      for (const char *column : {"normal_force",
                                 "tangential_force",
                                 "kinetic_energy",
                                 "elastic_energy",
                                 "foundation_energy",
                                 "load_work",
                                 "dissipation",
                                 "remesh_energy_change",
                                 "reaction_force_y"})
        {
          const auto   q = test_tools::quantity<2>(column);
          const double a = q.of(serial[n]), b = q.of(parallel[n]);
          const double scale = q.force ?
                                 std::max(std::abs(a), 1e3) :
                                 std::max(serial[n].terms.energy.total(), 1.);
          worst              = std::max(worst, std::abs(a - b) / scale);
        }
    }
  test_tools::check(same_mesh, "the same adaptive meshes at every step");
  test_tools::check(worst < 1e-8,
                    "every step's forces and energies agree to 1e-8");
  bool adapted = false;
  for (const auto &row : serial)
    adapted = adapted || row.remesh_energy_change != 0;
  test_tools::check(adapted, "the mesh was adapted during the run");
}
