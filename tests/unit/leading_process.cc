// LeadingProcess (the condensed solver's dense work on rank 0 alone): on 3
// processes, the work's requests are served by every process in order, the
// leader's values reach every process, and a failure of the work ends run()
// on every process with the same exception (a StepFailure with its message
// and Newton iterations, any other error as std::runtime_error with its
// message); a failure of a request's serving function, which every process
// runs, leaves every process by its own exception, and the next run() works.

#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/leading_process.h>

#include "test_tools.h"

#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace DynamicContact;

namespace
{
  /** One line per process, printed by rank 0 in rank order. */
  void
  report(const std::string &case_name, const std::string &line)
  {
    const auto lines = Utilities::MPI::gather(MPI_COMM_WORLD, line, 0);
    test_tools::out() << case_name << '\n';
    for (unsigned int r = 0; r < lines.size(); ++r)
      test_tools::out() << "  rank " << r << ": " << lines[r] << '\n';
  }

  /** The requests served on this process, as "( 1 2 )( )...". */
  std::vector<std::string> served;

  /** The requests served since the last call; forgets them. */
  std::string
  served_text()
  {
    std::string s;
    for (const auto &x : served)
      s += x;
    served.clear();
    return s;
  }

  /** Serve a request: note it; fail on a request that starts with 99. */
  void
  serve(const std::vector<unsigned int> &l)
  {
    std::string s = "(";
    for (const unsigned int i : l)
      s += " " + std::to_string(i);
    served.push_back(s + " )");
    if (!l.empty() && l[0] == 99)
      throw std::runtime_error("serving failed");
  }

  /** How lead.run(@p work) ended on this process. */
  std::string
  outcome_of(LeadingProcess &lead, const std::function<void()> &work)
  {
    try
      {
        lead.run(work);
        return "no exception";
      }
    catch (const StepFailure &e)
      {
        return std::string("StepFailure '") + e.what() + "', " +
               std::to_string(e.newton_iterations) + " iterations";
      }
    catch (const std::exception &e)
      {
        return std::string("error '") + e.what() + "'";
      }
  }

  /** 1. Requests in order, then the leader's values on every process. */
  void
  requests_and_shared_values(LeadingProcess &lead)
  {
    unsigned int worked = 0;
    lead.run([&]() {
      ++worked;
      lead.request({1, 2});
      lead.request({});
      lead.request({5});
    });
    std::vector<double> values;
    struct
    {
      unsigned int n;
      double       x;
      bool         b;
    } record{0, 0., false};
    if (lead.leads())
      {
        values = {0.5, -1.25, 3e100};
        record = {7, 2.5, true};
      }
    lead.share(values);
    lead.share(record);
    std::ostringstream s;
    s << "leads " << lead.leads() << ", worked " << worked << ", served "
      << served_text() << ", values";
    for (const double v : values)
      s << ' ' << v;
    s << ", record " << record.n << ' ' << record.x << ' ' << record.b;
    report("requests and shared values", s.str());
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  LeadingProcess                   lead(MPI_COMM_WORLD, serve);

  requests_and_shared_values(lead);

  // 2. A StepFailure of the work after a request.
  const std::string step_failure = outcome_of(lead, [&]() {
    lead.request({3});
    throw StepFailure("the Newton iteration did not converge", 7);
  });
  report("a StepFailure of the work",
         step_failure + ", served " + served_text());

  // 3. Another error of the work.
  report("another error of the work",
         outcome_of(lead, []() { throw std::logic_error("a bad table"); }));

  // 4. The serving function fails on every process; then a normal run.
  const std::string serving_failure = outcome_of(lead, [&]() {
    lead.request({99});
    lead.request({4}); // not reached
  });
  const std::string served_then     = served_text();
  lead.run([&]() { lead.request({6}); });
  report("a failure of the serving function, then a normal run",
         serving_failure + ", served " + served_then + "; then served " +
           served_text());
}
