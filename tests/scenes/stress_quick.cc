// The stress suite in its quick mode, as `benchmarks/stress --quick` runs
// it (every scene of prm/stress/ at the sizes of prm/stress/quick.txt): a
// near-rigid foundation, a steep friction drop, a huge and a tiny time step,
// a load near the critical speed, a nearly incompressible body (Q1, Q2), a
// long horizon, an impact and a 3D scene whose tangential load turns. For
// each scene the script checks that the run completes, that nothing is NaN
// or infinite, the energy balance at every step with every dissipation term
// >= 0, the friction law node by node at every step, and the scene's own
// purpose (the bounce, the bounded energy and the balance without drift,
// the turning slip). This test prints its verdicts (no numbers: they are
// in stress_quick.csv) and fails if any check fails.

#include "program_tools.h"

using namespace program_tools;

int
main()
{
  const Outcome o = run_benchmark_script("stress",
                                         {"--quick",
                                          "--verdicts",
                                          "--work-dir",
                                          "stress-runs",
                                          "--csv",
                                          "stress_quick.csv"},
                                         "stress");
  test_tools::out() << o.out;
  if (!o.err.empty())
    test_tools::out() << "stderr:\n" << o.err;

  // Every scene of prm/stress/ gave its verdicts.
  unsigned int n_scenes = 0;
  for (const auto &entry :
       fs::directory_iterator(fs::path(REPOSITORY_DIR) / "prm" / "stress"))
    n_scenes += (entry.path().extension() == ".prm");
  unsigned int n_completed = 0;
  for (const auto &line : lines_of(o.out))
    n_completed += (line.find(": OK     completed") != std::string::npos);
  Checks checks;
  checks.add(n_scenes >= 10, "prm/stress/ holds the ten scenes");
  checks.add(n_completed == n_scenes, "every scene completed");
  checks.add(o.succeeded(), "benchmarks/stress --quick: every check passed");
  checks.assert_all();
}
