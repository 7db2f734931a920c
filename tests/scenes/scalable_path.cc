// The scalable contact solver (Solver/Contact solver = assembled: the sparse
// Newton system of the whole body, owned data only) against the condensed
// one (dense tables on Gamma_3) on the scenes with known answers and on the
// paper's and the rail's small scenes: their time series agree to 1e-8,
// with the iterative linear solver (GMRES, AMG of K0, stick constraints by
// projection) and with the direct one. The condensed solver is also run with
// its iterative bulk solver (CG with the same AMG). The assembled solver's
// provisional passes give the answers of passes solved in full, in fewer
// Newton iterations, on a rail large enough to need them. The .mpirun=2 variant
// runs everything on two processes and must print the same.

#include "test_tools.h"

using namespace DynamicContact;

template <int dim>
std::vector<StepRecord<dim>>
series(const std::string       &prm,
       const std::string       &name,
       const std::string       &solver,
       const std::string       &linear,
       std::vector<std::string> overrides)
{
  overrides.push_back("Solver/Contact solver=" + solver);
  overrides.push_back("Solver/Linear solver=" + linear);
  overrides.push_back("Output/Directory=output-" + name + "-" + solver + "-" +
                      linear);
  return test_tools::run<dim>(test_tools::scene(prm), overrides)->time_series();
}

template <int dim>
void
compare(const std::string                                      &prm,
        const std::string                                      &name,
        const std::vector<std::pair<std::string, std::string>> &paths,
        const std::vector<std::string>                         &overrides = {})
{
  const auto reference =
    series<dim>(prm, name, "condensed", "direct", overrides);
  for (const auto &[solver, linear] : paths)
    {
      const auto other = series<dim>(prm, name, solver, linear, overrides);
      test_tools::check(other.size() == reference.size(),
                        name + ", " + solver + "/" + linear +
                          ": same number of steps");
      if (other.size() != reference.size())
        continue;
      const double worst = test_tools::largest_difference(reference, other);
      unsigned int linear_its = 0;
      for (unsigned int n = 1; n < reference.size(); ++n)
        linear_its += other[n].statistics.linear_iterations;
      test_tools::check(worst < 1e-8,
                        name + ", " + solver + "/" + linear +
                          ": agrees with condensed/direct to 1e-8");
      if (linear == "iterative" && solver == "assembled")
        test_tools::check(linear_its > 0,
                          name + ", " + solver + "/" + linear +
                            ": the Krylov solver ran");
    }
}

/**
 * Solver/Assembled/Provisional passes: on the rail's first 4 steps on 60 x 6
 * x 6 cells (where a pass after the first starts far enough from its
 * solution that one Newton step does not reach the Newton tolerance), the
 * passes stopped short give the same answers as every pass solved to the
 * Newton tolerance, to 1e-8, in fewer Newton iterations.
 */
void
provisional_passes()
{
  std::vector<std::vector<StepRecord<3>>> runs;
  std::vector<unsigned int>               newton;
  for (const std::string setting : {"true", "false"})
    {
      runs.push_back(
        series<3>("rail_3d.prm",
                  "provisional-" + setting,
                  "assembled",
                  "direct",
                  {"Geometry/Repetitions=30, 3, 3",
                   "Geometry/Global refinements=1",
                   "Time/End time=0.03125",
                   "Solver/Assembled/Provisional passes=" + setting}));
      newton.push_back(0);
      for (unsigned int n = 1; n < runs.back().size(); ++n)
        newton.back() += runs.back()[n].statistics.newton_iterations;
    }
  test_tools::check(test_tools::largest_difference(runs[0], runs[1]) < 1e-8,
                    "Solver/Assembled/Provisional passes: the same answers as "
                    "false, to 1e-8");
  test_tools::check(newton[0] < newton[1],
                    "Solver/Assembled/Provisional passes: fewer Newton "
                    "iterations than false");
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize                       mpi(argc, argv, 1);
  const std::vector<std::pair<std::string, std::string>> sparse = {
    {"assembled", "iterative"}, {"assembled", "direct"}};
  compare<2>("pressed_block.prm", "pressed_2d", sparse);
  compare<3>("pressed_block_3d.prm",
             "pressed_3d",
             {{"assembled", "iterative"}});
  compare<2>(
    "sliding_block.prm",
    "slide_2d",
    sparse,
    {"Boundary conditions/Traction function/Function constants=P=1e6, T=6e5"});
  compare<2>(
    "sliding_block.prm",
    "stick_2d",
    {{"assembled", "iterative"}},
    {"Boundary conditions/Traction function/Function constants=P=1e6, T=4e5"});
  compare<3>(
    "sliding_block_3d.prm",
    "slide_3d",
    {{"assembled", "iterative"}},
    {"Boundary conditions/Traction function/Function constants=P=1e6, T=6e5"});
  compare<2>("barboteu_danan_2016_small.prm",
             "paper_small",
             {{"assembled", "iterative"}, {"condensed", "iterative"}});
  compare<3>("rail_3d_small.prm", "rail_small", {{"assembled", "iterative"}});
  provisional_passes();
}
