// What the options no scene sets are for, each shown on the small paper
// scene (prm/barboteu_danan_2016_small.prm, its first 0.25 s, or its
// adaptive variant):
// - a function's constants and variable names are substituted: the same
//   series as the literal expression;
// - Friction/Complementarity constant and Friction/Relaxation change the
//   path of the solvers, not the solution (each frozen-coefficient problem
//   has one; the loop's fixed point does not depend on the relaxation: the
//   same to the loop's tolerance), and
//   the relaxation below 1 takes more convexification passes;
// - Solver/Condensed/Provisional passes = false gives the same solution, with
// more
//   solves with K0; Solver/Condensed/Limit = 0 makes the plan assemble;
//   the iterative linear solver to Solver/Linear tolerance agrees with the
//   direct one, and one capped by Solver/Maximum linear iterations stops
//   the run with an error that names the cap; Solver/AMG/Aggregation =
//   plain gives the same solution with more Krylov iterations (on a mesh
//   refined twice: the multigrid has coarse levels there);
// - Friction/Uniqueness monitor = always measures the bound with the
//   assembled solver, never measures nothing (and has no column);
// - Friction/Maximum slip rate is the range the law is checked on;
// - Foundation/Normal damping/Only in contact = true: damping acts only at
//   penetrating nodes, and the energy balance still closes;
// - Time/Maximum time step bounds the adaptive steps;
// - Mesh refinement/Cell budget caps the adaptive mesh (and its solver plan
//   stays); a Condensed/Limit that the adapted mesh's contact boundary
//   crosses changes the plan, and log.txt has the new one; the error indicator
//   with both fractions 0 leaves the mesh as it is, with a refine fraction
//   it refines; contact following refines within its Window of the
//   penetrating nodes.

#include <deal.II/base/mpi.h>

#include <dynamic_contact/parameters/parameters.h>

#include "test_tools.h"

#include <regex>

using namespace DynamicContact;

namespace
{
  using test_tools::check;
  using Series = std::vector<StepRecord<2>>;

  const std::string scene = test_tools::scene("barboteu_danan_2016_small.prm");
  const std::string adaptive_scene =
    test_tools::scene("barboteu_danan_2016_adaptive_small.prm");

  Series
  series(const std::string              &name,
         const std::vector<std::string> &overrides,
         const std::string              &file = scene)
  {
    auto o = overrides;
    o.push_back("Output/Directory=output-" + name);
    o.insert(o.begin(), "Time/End time=0.25");
    return test_tools::run<2>(file, o)->time_series();
  }

  template <typename F>
  unsigned int
  sum(const Series &s, const F &f)
  {
    unsigned int total = 0;
    for (const auto &row : s)
      total += f(row);
    return total;
  }

  using Statistics = StepSolver<2>::Statistics;
  // The counters of the solvers' work that the options change.
  constexpr auto passes = &Statistics::convexification_iterations;
  constexpr auto solves = &Statistics::bulk_solves; // with K0
  constexpr auto krylov = &Statistics::linear_iterations;

  /** The sum of the counter @p counter over the steps of @p s. */
  unsigned int
  total(const Series &s, unsigned int Statistics::*counter)
  {
    return sum(s, [counter](const StepRecord<2> &r) {
      return r.statistics.*counter;
    });
  }

  /** The number of steps that measured the uniqueness bound. */
  unsigned int
  measured_bounds(const Series &s)
  {
    return sum(s, [](const StepRecord<2> &r) {
      return r.statistics.uniqueness_bound >= 0 ? 1u : 0u;
    });
  }

  /** The message of the error a run stops with ("" if none). */
  std::string
  error_of(const std::string &name, const std::vector<std::string> &overrides)
  {
    try
      {
        series(name, overrides);
      }
    catch (const std::exception &e)
      {
        return e.what();
      }
    return "";
  }

  /** Whether log.txt of the run @p name contains @p text. */
  bool
  log_says(const std::string &name, const std::string &text)
  {
    return test_tools::read_text("output-" + name + "/log.txt").find(text) !=
           std::string::npos;
  }

  // The assembled contact solver with the iterative linear solver.
  const std::vector<std::string> iterative_solver = {
    "Solver/Contact solver=assembled",
    "Solver/Linear solver=iterative",
    "Solver/Linear tolerance=1e-12"};

  void
  check_function_constants(const Series &reference)
  {
    const auto literal =
      series("literal",
             {"Initial conditions/Velocity/Function expression=0.01*x; 0"});
    const auto with_constant =
      series("constant",
             {"Initial conditions/Velocity/Function constants=v0=0.01",
              "Initial conditions/Velocity/Function expression=v0*x; 0"});
    const auto renamed =
      series("renamed",
             {"Initial conditions/Velocity/Variable names=X,Y,T",
              "Initial conditions/Velocity/Function expression=0.01*X; 0"});
    const auto kinetic = test_tools::quantity<2>("kinetic_energy");
    check(kinetic.of(literal.front()) > 0 && kinetic.of(reference.front()) == 0,
          "the initial velocity is set (kinetic energy at t = 0)");
    check(test_tools::largest_difference(with_constant, literal) == 0,
          "Function constants: the same series as the literal expression");
    check(test_tools::largest_difference(renamed, literal) == 0,
          "Variable names: the same series as with x, y, t");
  }

  /** Options that change the path of the solvers: the same solution. */
  void
  check_solver_paths(const Series &reference)
  {
    using test_tools::largest_difference;
    const auto c_t =
      series("complementarity", {"Friction/Complementarity constant=1e14"});
    check(largest_difference(c_t, reference) < 1e-8,
          "Friction/Complementarity constant: the same solution to 1e-8");
    const auto relaxed = series("relaxed", {"Friction/Relaxation=0.7"});
    // Both loops stop within Friction/Convexification tolerance and
    // Coefficient tolerance (1e-6) of the same fixed point.
    check(largest_difference(relaxed, reference) < 1e-6,
          "Friction/Relaxation = 0.7: the same solution to the loop's "
          "tolerance, 1e-6");
    check(total(relaxed, passes) > total(reference, passes),
          "Friction/Relaxation = 0.7: more convexification passes");
    const auto whole =
      series("whole", {"Solver/Condensed/Provisional passes=false"});
    check(
      largest_difference(whole, reference) < 1e-8,
      "Solver/Condensed/Provisional passes = false: the same solution to 1e-8");
    check(total(whole, solves) > total(reference, solves),
          "Solver/Condensed/Provisional passes = false: more solves with K0");
    const auto assembled = series("limit", {"Solver/Condensed/Limit=0"});
    check(largest_difference(assembled, reference) < 1e-8,
          "Solver/Condensed/Limit = 0: the same solution to 1e-8");
    check(log_says("limit", "solver plan: assembled"),
          "Solver/Condensed/Limit = 0: the plan assembles");
    const auto iterative = series("iterative", iterative_solver);
    check(largest_difference(iterative, reference) < 1e-8,
          "Solver/Linear solver = iterative: the same solution to 1e-8");
    check(total(iterative, krylov) > 0,
          "Solver/Linear solver = iterative: Krylov iterations counted");
  }

  /** Plain aggregation: the same solution, more Krylov iterations (on a
   *  mesh refined twice: the multigrid has coarse levels there). */
  void
  check_amg_aggregation()
  {
    std::vector<Series> aggregations;
    for (const std::string aggregation : {"smoothed", "plain"})
      {
        std::vector<std::string> overrides = {"Geometry/Global refinements=2"};
        overrides.insert(overrides.end(),
                         iterative_solver.begin(),
                         iterative_solver.end());
        overrides.push_back("Solver/AMG/Aggregation=" + aggregation);
        aggregations.push_back(series("aggregation-" + aggregation, overrides));
      }
    check(test_tools::largest_difference(aggregations[1], aggregations[0]) <
            1e-8,
          "Solver/AMG/Aggregation = plain: the same solution to 1e-8");
    check(total(aggregations[1], krylov) > total(aggregations[0], krylov),
          "Solver/AMG/Aggregation = plain: more Krylov iterations");
    check(log_says("aggregation-plain", "plain aggregation"),
          "Solver/AMG/Aggregation = plain: the solver plan says so");
  }

  /**
   * The linear solver's cap: CG on K0 (the condensed solver with the
   * iterative linear solver) that cannot converge in 2 iterations fails
   * the step, and at the smallest time step the run stops naming the cap.
   */
  void
  check_linear_cap()
  {
    const std::string error =
      error_of("linear-cap",
               {"Geometry/Global refinements=2", // AMG not a direct solve
                "Solver/Contact solver=condensed",
                "Solver/Linear solver=iterative",
                "Solver/Maximum linear iterations=2",
                "Time/Minimum time step=0.00390625"});
    check(error.find("Solver/Maximum linear iterations = 2") !=
            std::string::npos,
          "Solver/Maximum linear iterations = 2: the run stops naming it");
  }

  void
  check_uniqueness_monitor()
  {
    const auto always = series("monitor-always",
                               {"Solver/Contact solver=assembled",
                                "Friction/Uniqueness monitor=always"});
    const auto never =
      series("monitor-never", {"Friction/Uniqueness monitor=never"});
    check(measured_bounds(always) > 0,
          "Uniqueness monitor = always: measured with the assembled solver");
    check(measured_bounds(never) == 0 &&
            test_tools::read_text("output-monitor-never/time_series.csv")
                .find("uniqueness_bound") == std::string::npos,
          "Uniqueness monitor = never: nothing measured, no column");
  }

  /** The slip-rate range of the law's start-up check. */
  void
  check_slip_rate_range()
  {
    const std::vector<std::string> law = {
      "Friction/Law=expression",
      "Friction/Expression/Function expression=0.5-0.01*s"};
    const std::string error = error_of("range-default", law);
    check(error.find("Friction/Maximum slip rate") != std::string::npos,
          "Friction/Maximum slip rate = auto (the P-wave speed): mu < 0 "
          "beyond 50 m/s refused");
    auto narrow = law;
    narrow.push_back("Friction/Maximum slip rate=10");
    check(error_of("range-narrow", narrow).empty(),
          "Friction/Maximum slip rate = 10: the same law runs");
  }

  /**
   * Damping only in contact: with true, damping acts only at penetrating
   * nodes; with false (eq. (17) as written) also at nodes that approach
   * the foundation without touching it.
   */
  void
  check_damping_only_in_contact(const bool only)
  {
    const std::string flag = only ? "true" : "false";
    auto              loop =
      test_tools::make<2>(scene,
                          {"Time/End time=0.25",
                           "Foundation/Normal damping/Only in contact=" + flag,
                           "Output/Directory=output-only-in-contact-" + flag});
    loop->initialize();
    unsigned int damping_alone = 0;
    do
      for (const auto &state : loop->simulator().node_states())
        if (state.normal.damping_active && !state.normal.compliance_active)
          ++damping_alone;
    while (loop->advance());
    loop->finish();
    damping_alone       = Utilities::MPI::sum(damping_alone, MPI_COMM_WORLD);
    double worst_defect = 0;
    for (const auto &row : loop->time_series())
      worst_defect = std::max(worst_defect, row.relative_energy_defect());
    check(only ? damping_alone == 0 : damping_alone > 0,
          "Only in contact = " + flag + ": damping " +
            (only ? "never" : "also") + " acts without penetration");
    check(worst_defect < 1e-8,
          "Only in contact = " + flag + ": the energy balance closes to 1e-8");
  }

  /** Adaptive time steps bounded by Maximum time step. */
  void
  check_maximum_time_step()
  {
    const std::vector<std::string> adaptive          = {"Time/Scheme=bathe",
                                                        "Time/Adaptive=true",
                                                        "Time/Adaptive tolerance=0.1",
                                                        "Time/Time step=0.00390625"};
    auto                           bounded_overrides = adaptive;
    bounded_overrides.push_back("Time/Maximum time step=0.0078125");
    const auto bounded = series("maximum-step", bounded_overrides);
    const auto free    = series("free-step", adaptive);
    const auto largest = [](const Series &s) {
      double k = 0;
      for (const auto &row : s)
        k = std::max(k, row.time_step);
      return k;
    };
    check(largest(free) > 0.0078125 * (1 + 1e-12),
          "Time/Adaptive without a bound: steps longer than 0.0078125 s");
    check(largest(bounded) > 0 && largest(bounded) <= 0.0078125 * (1 + 1e-12),
          "Time/Maximum time step = 0.0078125: no longer step");
  }

  /** Mesh refinement: the cell budget, and the plan of an adapted mesh. */
  void
  check_cell_budget()
  {
    const auto budget =
      series("budget", {"Mesh refinement/Cell budget=256"}, adaptive_scene);
    const auto other_meshes = sum(budget, [](const StepRecord<2> &r) {
      return r.cells == 256 ? 0u : 1u;
    });
    check(other_meshes == 0,
          "Cell budget = 256: the uniform mesh of the minimum level");

    // A solver plan that an adapted mesh changes goes into log.txt, with
    // the step it applies from: in the adaptive scene's first 0.25 s dim x
    // contact nodes grows from 38 to 42, across a Condensed/Limit of 41. A
    // run whose plan stays (the budget above) has no such line.
    series("plan-change", {"Solver/Condensed/Limit=41"}, adaptive_scene);
    const std::string changed =
      test_tools::read_text("output-plan-change/log.txt");
    check(std::regex_search(
            changed,
            std::regex(R"((^|\n)  solver plan from step [0-9]+ \(mesh )"
                       R"(adapted at t = [^)]+\): assembled \(iterative\))")),
          "a plan changed by remeshing: log.txt has the new one");
    check(!log_says("budget", "solver plan from step"),
          "a plan unchanged by remeshing: log.txt has no new one");
  }

  /** The error indicator with Refine fraction @p refine, no coarsening. */
  Series
  error_indicator(const std::string &name, const std::string &refine)
  {
    return series(name,
                  {"Mesh refinement/Strategy=error indicator",
                   "Mesh refinement/Error indicator/Refine fraction=" + refine,
                   "Mesh refinement/Error indicator/Coarsen fraction=0"},
                  adaptive_scene);
  }

  /**
   * Contact following: the finest level (2) within Window of the
   * penetrating nodes, under the load at x = c t; the top of the body
   * (0.1 m above the contact boundary) only with a window that reaches it.
   */
  void
  check_contact_following(const double window)
  {
    const std::string w = test_tools::digits(window, 1);
    auto              loop =
      test_tools::make<2>(adaptive_scene,
                          {"Time/End time=0.25",
                           "Mesh refinement/Strategy=contact following",
                           "Mesh refinement/Contact following/Window=" + w,
                           "Output/Directory=output-contact-following-" + w});
    loop->run();
    const double x = 2. * loop->time();
    check(test_tools::level_at(loop->simulator(), Point<2>(x, 0.001)) == 2,
          "Contact following, Window = " + w +
            ": the finest level at the contact under the load");
    check(test_tools::level_at(loop->simulator(), Point<2>(x, 0.099)) ==
            (window > 0.1 ? 2 : 1),
          "Contact following, Window = " + w + ": the top " +
            (window > 0.1 ? "refined too" : "at the minimum level"));
  }

  /** The error indicator with both fractions 0 leaves the mesh as it is,
   *  with a refine fraction it refines; contact following in between. */
  void
  check_refinement_strategies()
  {
    const auto frozen    = error_indicator("indicator-frozen", "0");
    const auto refining  = error_indicator("indicator-refining", "0.3");
    bool       unchanged = true;
    double     most      = 0;
    for (const auto &row : frozen)
      unchanged = unchanged && row.cells == frozen.front().cells;
    for (const auto &row : refining)
      most = std::max(most, static_cast<double>(row.cells));
    check(unchanged, "Error indicator with both fractions 0: mesh unchanged");
    for (const double window : {0.01, 0.2})
      check_contact_following(window);
    check(most > frozen.front().cells,
          "Error indicator, Refine fraction = 0.3: the mesh is refined");
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const auto                       reference = series("reference", {});
  check_function_constants(reference);
  check_solver_paths(reference);
  check_amg_aggregation();
  check_linear_cap();
  check_uniqueness_monitor();
  check_slip_rate_range();
  for (const bool only : {true, false})
    check_damping_only_in_contact(only);
  check_maximum_time_step();
  check_cell_budget();
  check_refinement_strategies();
}
