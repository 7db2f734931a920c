// Adaptive time stepping (Time/Adaptive, doc/theory.md section 2.5) on the
// manufactured solution (prm/manufactured_2d.prm, the exact solution
// known): the run starts with a step far too large (Time step = 0.4 of
// T = 0.8), which the controller rejects; every accepted step meets the
// tolerance (or is at the minimum step); steps end exactly at
// the Output times; a tolerance 10 times smaller gives a smaller error
// (against the exact solution) with more steps. Both schemes with an
// estimate: bathe and backward Euler.

#include "test_tools.h"

#include <cmath>

using namespace DynamicContact;

struct Result
{
  double       error = 0; // max_n error_theorem6
  unsigned int steps = 0, rejected = 0;
  double       k_min = 1e300, k_max = 0, worst_estimate = 0;
  bool         output_times_hit = false;
};

Result
adaptive_run(const std::string &scheme, const double tolerance)
{
  const std::string name =
    (scheme == "backward Euler" ? std::string("euler") : scheme);
  auto simulator =
    test_tools::run<2>(test_tools::scene("manufactured_2d.prm"),
                       {"Output/Directory=output-adaptive-time-" + name + "-" +
                          test_tools::digits(tolerance, 1),
                        "Geometry/Global refinements=3",
                        "Finite element/Polynomial degree=2",
                        "Time/Scheme=" + scheme,
                        "Time/Time step=0.4",
                        "Time/Minimum time step=1e-4",
                        "Time/Adaptive=true",
                        "Time/Adaptive tolerance=" +
                          test_tools::digits(tolerance, 2),
                        "Output/Output times=0.3, 0.5"});
  Result r;
  bool   hit_03 = false, hit_05 = false;
  for (const auto &row : simulator->time_series())
    if (row.step > 0)
      {
        ++r.steps;
        r.error = std::max(r.error, row.errors.strain + row.errors.velocity);
        r.rejected += row.rejected;
        const double k = row.time_step;
        r.k_min        = std::min(r.k_min, k);
        r.k_max        = std::max(r.k_max, k);
        if (k > 1e-4 * (1 + 1e-9))
          r.worst_estimate = std::max(r.worst_estimate, row.time_error);
        hit_03 = hit_03 || std::abs(row.time - 0.3) < 1e-12;
        hit_05 = hit_05 || std::abs(row.time - 0.5) < 1e-12;
      }
  r.output_times_hit = hit_03 && hit_05;
  return r;
}

void
study(const std::string &scheme, const double tolerance)
{
  test_tools::out() << "--- Time/Scheme = " << scheme << std::endl;
  const Result coarse = adaptive_run(scheme, tolerance);
  const Result fine   = adaptive_run(scheme, tolerance / 10);
  for (const Result *r : {&coarse, &fine})
    {
      const std::string tol =
        test_tools::digits(r == &coarse ? tolerance : tolerance / 10, 1);
      test_tools::check(r->rejected > 0,
                        "tolerance " + tol + ": steps were rejected");
      test_tools::check(r->worst_estimate <=
                          (r == &coarse ? tolerance : tolerance / 10),
                        "tolerance " + tol +
                          ": every accepted step meets the tolerance");
      test_tools::check(r->output_times_hit,
                        "tolerance " + tol +
                          ": steps end exactly at the Output times");
    }
  test_tools::check(fine.steps > 3 * coarse.steps / 2,
                    "a tolerance 10 times smaller takes over 1.5 times as "
                    "many steps");
  test_tools::check(fine.error < coarse.error,
                    "a smaller tolerance gives a smaller error");
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  study("bathe", 1e-3);
  study("backward Euler", 1e-2);
}
