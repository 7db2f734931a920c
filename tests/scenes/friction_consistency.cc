// The friction law holds node by node, to solver tolerance (relative to the
// largest contact pressure, the scale the solver's tolerance refers to), in
// the paper's frictional scene, solved by the frozen convexification loop
// and by the coupled linearization (Friction/Linearization)
// (prm/barboteu_danan_2016_small.prm, mu(s) = 0.5 exp(-2000 s) + 0.5), at
// every step, read back from the contact_NNNNN.csv files the run writes:
//   slip nodes:  |tangential_traction| = mu normal_pressure, the traction
//                opposes w_tau, and mu = mu(|w_tau|) to the loop's tolerance;
//   stick nodes: |tangential_traction| <= mu(0) normal_pressure, w_tau = 0
//                (to 1e-10 of the largest slip rate);
//   free nodes:  no traction.

#include <deal.II/base/utilities.h>

#include "test_tools.h"

#include <map>
#include <sstream>

using namespace DynamicContact;

namespace
{
  /** What the contact CSV files of a run show, over all steps. */
  struct LawMeasures
  {
    std::map<std::string, unsigned int> count;
    double slip_law = 0, slip_coefficient = 0, stick_excess = 0,
           stick_velocity = 0, free_traction = 0, p_max = 0, slip_max = 0;
    bool   opposes = true, one_time = true, time_increases = true;
    double last_time = 0;
  };


  /** mu(s) = 0.5 exp(-2000 s) + 0.5. */
  double
  mu(const double s)
  {
    return 0.5 * std::exp(-2000 * s) + 0.5;
  }


  /** Add the nodes of contact_NNNNN.csv of @p step to @p x. */
  void
  read_step(const std::string &directory,
            const std::string &prefix,
            const unsigned int step,
            LawMeasures       &x)
  {
    char name[64];
    std::snprintf(name, sizeof(name), "/contact_%05u.csv", step);
    const auto rows = test_tools::read_csv(directory + name);
    if (rows.empty())
      test_tools::check(false, prefix + "read " + name);
    if (step == 1)
      test_tools::check(rows[0] == test_tools::split("time,x,y,u_nu,w_nu,"
                                                     "normal_pressure,w_tau,"
                                                     "tangential_traction,mu,"
                                                     "u_x,u_y,state",
                                                     ','),
                        prefix + "contact CSV header");
    // The time of the step, in every row.
    const double time = rows.size() > 1 ? std::stod(rows[1][0]) : 0;
    x.time_increases  = x.time_increases && time > x.last_time;
    x.last_time       = time;
    for (std::size_t r = 1; r < rows.size(); ++r)
      {
        const auto &fields = rows[r];
        x.one_time         = x.one_time && std::stod(fields[0]) == time;
        const double p = std::stod(fields[5]), w_tau = std::stod(fields[6]),
                     t = std::stod(fields[7]), m = std::stod(fields[8]);
        const std::string &state = fields[11];
        ++x.count[state];
        x.p_max = std::max(x.p_max, p);
        if (state == "slip")
          {
            x.slip_law = std::max(x.slip_law, std::abs(std::abs(t) - m * p));
            x.slip_coefficient =
              std::max(x.slip_coefficient, std::abs(m - mu(std::abs(w_tau))));
            x.opposes  = x.opposes && (t * w_tau < 0);
            x.slip_max = std::max(x.slip_max, std::abs(w_tau));
          }
        else if (state == "stick")
          {
            x.stick_excess = std::max(x.stick_excess, std::abs(t) - mu(0) * p);
            x.stick_velocity = std::max(x.stick_velocity, std::abs(w_tau));
          }
        else
          x.free_traction = std::max(x.free_traction, std::abs(t));
      }
  }


  void
  check_law(const std::string &linearization)
  {
    const std::string directory = "output-friction-" + linearization;
    const std::string prefix    = linearization + ": ";
    test_tools::run<2>(test_tools::scene("barboteu_danan_2016_small.prm"),
                       {"Output/Directory=" + directory,
                        "Output/Output every=1",
                        "Friction/Linearization=" + linearization});
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;

    LawMeasures x;
    for (unsigned int step = 1; step <= 128; ++step)
      read_step(directory, prefix, step, x);
    test_tools::check(x.one_time && x.time_increases,
                      prefix +
                        "the time column: one time per file, increasing with "
                        "the step");
    test_tools::check(x.count["slip"] > 100 && x.count["stick"] > 10,
                      prefix + "many slip and stick node-steps");
    test_tools::check(x.slip_law < 1e-8 * x.p_max,
                      prefix + "slip: |traction| = mu p to 1e-8 of the largest "
                               "pressure");
    test_tools::check(x.opposes,
                      prefix + "slip: the traction opposes the slip velocity");
    test_tools::check(x.slip_coefficient < 1e-6,
                      prefix + "slip: mu = mu(|w_tau|) to the coefficient "
                               "tolerance 1e-6");
    test_tools::check(x.stick_excess < 1e-8 * x.p_max,
                      prefix + "stick: |traction| <= mu(0) p");
    test_tools::check(x.stick_velocity < 1e-10 * x.slip_max,
                      prefix +
                        "stick: w_tau = 0 to 1e-10 of the largest slip rate");
    test_tools::check(x.free_traction == 0, prefix + "free: no traction");
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const std::string linearization : {"frozen", "coupled"})
    check_law(linearization);
}
