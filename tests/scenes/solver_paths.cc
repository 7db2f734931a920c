// The two implementations of the semismooth Newton step (condensation onto
// Gamma_3, and the assembled sparse system with stick rows) solve the same
// Newton systems: their time series agree to solver tolerance, without and
// with the paper's friction law.

#include "test_tools.h"

using namespace DynamicContact;

void
compare(const std::string &name, const std::vector<std::string> &overrides)
{
  std::vector<std::vector<StepRecord<2>>> series;
  for (const std::string solver : {"condensed", "assembled"})
    {
      auto o = overrides;
      o.push_back("Solver/Contact solver=" + solver);
      o.push_back("Output/Directory=output-" + name + "-" + solver);
      series.push_back(
        test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                           o)
          ->time_series());
    }
  test_tools::check(series[0].size() == series[1].size(),
                    name + ": same number of steps");
  const double worst = test_tools::largest_difference(series[0], series[1]);
  test_tools::check(worst < 1e-8,
                    name + ": condensed and assembled agree to 1e-8");
  unsigned int stick = 0, slip = 0;
  for (const auto &row : series[0])
    {
      stick += row.statistics.n_stick;
      slip += row.statistics.n_slip;
    }
  if (name == "friction")
    test_tools::check(stick > 0 && slip > 0,
                      name + ": both stick and slip nodes occur");
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  compare("frictionless", {"Friction/Law=none"});
  compare("friction", {});
}
