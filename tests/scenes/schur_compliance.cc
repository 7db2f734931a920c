// The condensed solver on several processes: with Solver/Direct solver
// package = auto and a small K0 every process factorizes the whole K0 by
// CHOLMOD (the solver plan says so) and takes the compliance of Gamma_3
// from the factor's trailing block, as one process does; with MUMPS
// (Amesos_Mumps) it takes it in 3D from the Schur complement that a
// distributed MUMPS factorization returns (BulkSolver::inverse_block),
// where that agrees with the solves to a tenth of the Newton tolerance,
// and in 2D from dim solves per node. On the 3D rail (rail_3d_small.prm,
// 20 x 2 x 2) and the small paper scene each path must give the answers of
// one process (computed here on rank 0 alone) to 1e-8 of each column's
// peak, and take the compliance as said. Where MUMPS factorizes K0 over
// the processes, Solver/Condensed/Limit on several processes decides
// between the condensed and the assembled solver.

#include "test_tools.h"

#include <algorithm>

using namespace DynamicContact;

namespace
{
  template <int dim>
  void
  compare(const std::string &scene,
          const std::string &name,
          const std::string &package,
          const bool         schur)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    const std::vector<std::string> overrides = {
      "Time/End time=0.046875",
      "Solver/Contact solver=condensed",
      "Solver/Direct solver package=" + package,
      "Output/Directory=output-" + name};
    auto with_details = overrides;
    with_details.push_back("Output/Solver details=true");
    const auto parallel =
      test_tools::run<dim>(test_tools::scene(scene), with_details)
        ->time_series();
    if (rank != 0)
      return;
    auto serial_overrides = overrides;
    serial_overrides.back() += "-serial";
    const auto serial = test_tools::run<dim>(test_tools::scene(scene),
                                             serial_overrides,
                                             MPI_COMM_SELF)
                          ->time_series();
    double worst = 0;
    for (const char *column :
         {"normal_force", "tangential_force", "kinetic_energy"})
      {
        const auto q    = test_tools::quantity<dim>(column);
        double     peak = 0;
        for (const auto &record : serial)
          peak = std::max(peak, std::abs(q.of(record)));
        for (unsigned int n = 1; n < std::min(serial.size(), parallel.size());
             ++n)
          worst = std::max(worst,
                           std::abs(q.of(parallel[n]) - q.of(serial[n])) /
                             std::max(peak, 1e-300));
      }
    test_tools::check(parallel.size() == 7 && serial.size() == 7,
                      name + ": 6 steps on several processes and on one");
    test_tools::check(worst < 1e-8,
                      name + ": the answers of one process to 1e-8");
    const std::string log = test_tools::read_text("output-" + name + "/log.txt");
    const bool        whole_factor =
      log.find("factorization: CHOLMOD on every process") != std::string::npos;
    test_tools::check(whole_factor == (package == "auto"),
                      name + ": CHOLMOD on every process " +
                        (package == "auto" ? "(auto)" : "not taken"));
    const bool from_schur =
      log.find("the inverse of its Schur complement") != std::string::npos;
    test_tools::check(from_schur == schur,
                      name + ": the compliance " +
                        (schur ? "from a Schur complement" : "by solves"));
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  compare<3>("rail_3d_small.prm", "rail", "auto", true);
  compare<3>("rail_3d_small.prm", "rail-mumps", "Amesos_Mumps", true);
  compare<2>("barboteu_danan_2016_small.prm", "paper", "auto", true);
  compare<2>("barboteu_danan_2016_small.prm",
             "paper-mumps",
             "Amesos_Mumps",
             false);

  // Solver/Condensed/Limit on several processes: with K0 factorized by
  // MUMPS over the processes, Contact solver = auto takes the condensed
  // solver while dim x contact nodes (66 here) is at most the limit ('auto'
  // is 1000 in 2D), else the assembled one.
  for (const std::string limit : {"auto", "0"})
    {
      test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                         {"Time/End time=0.015625",
                          "Solver/Direct solver package=Amesos_Mumps",
                          "Solver/Condensed/Limit on several processes=" +
                            limit,
                          "Output/Directory=output-limit-" + limit});
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
        continue;
      const std::string plan = limit == "0" ? "assembled" : "condensed";
      test_tools::check(
        test_tools::read_text("output-limit-" + limit + "/log.txt")
            .find("solver plan: " + plan) != std::string::npos,
        "Condensed/Limit on several processes = " + limit + ": " + plan);
    }
}
