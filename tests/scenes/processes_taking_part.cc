// Solver/Minimum DoFs per process: a scene too small for the processes it
// is started on runs on the first of them only, and the others wait for it
// and end with it.
//
// prm/barboteu_danan_2016_small.prm (594 DoFs) for 16 steps, started on 3
// processes:
// - with the default (20000 DoFs per process) 1 of the 3 takes part: the
//   run says so, completes, and its time_series.csv is the one of a run on
//   one process, byte for byte;
// - with 250 DoFs per process 2 of the 3 take part, with 0 all 3 (no such
//   line): the answers agree with one process to 1e-8 of each column's peak;
// - an error of the processes that take part (an output directory below a
//   file) ends every process with exit code 1 and one error message, no
//   hang (a time limit ends a hang as a failure).

#include "program_tools.h"

#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace program_tools;
using test_tools::out;

namespace
{
  Outcome
  run(const std::string              &directory,
      const unsigned int              processes,
      const std::vector<std::string> &more = {})
  {
    Launch launch;
    launch.name          = directory.substr(directory.rfind('/') + 1);
    launch.processes     = processes;
    launch.every_process = false;
    launch.timeout       = 300;
    return execute(with(with({test_tools::scene(
                                 "barboteu_danan_2016_small.prm"),
                               "--set",
                               "Output/Directory=" + directory,
                               "--set",
                               "Time/End time=0.125",
                               "--set",
                               "Output/Output every=0"},
                              quiet),
                         more),
                   launch);
  }

  /** The line of the screen output that names the processes taking part
   *  ("none" without one). */
  std::string
  taking_part(const Outcome &o)
  {
    for (const auto &l : lines_of(o.out))
      if (l.find("processes take part") != std::string::npos)
        return trim(l);
    return "none";
  }
} // namespace


int
main()
{
  // No MPI here: the runs under mpiexec must not inherit a singleton's
  // MPI environment.
  Checks checks;

  const Outcome one = run("one", 0);
  checks.add(one.exited && one.code == 0, "the run on one process completes");

  const Outcome fewest = run("fewest", 3);
  out() << "3 processes, the default: " << taking_part(fewest) << std::endl;
  checks.add(fewest.exited && fewest.code == 0 &&
               trim(read_text("fewest/run_status")) == "completed",
             "on 3 processes with the default it completes");
  checks.add(taking_part(fewest).rfind("1 of 3 processes take part", 0) == 0,
             "the default takes 1 of the 3 processes and says so");
  checks.add(read_text("fewest/time_series.csv") ==
               read_text("one/time_series.csv"),
             "its time series is the one of a run on one process, byte for "
             "byte");
  checks.add(read_text("fewest/log.txt").find(
                 ", 1 MPI process (of 3 started), started ") !=
               std::string::npos,
             "its log's provenance line names the 1 process of the 3 started");

  for (const std::string minimum : {"250", "0"})
    {
      const std::string directory = "minimum_" + minimum;
      const Outcome     o = run(directory,
                            3,
                            {"--set",
                             "Solver/Minimum DoFs per process=" + minimum});
      out() << "3 processes, Minimum DoFs per process = " << minimum << ": "
            << taking_part(o) << std::endl;
      checks.add(o.exited && o.code == 0,
                 "Minimum DoFs per process = " + minimum + ": it completes");
      checks.add(taking_part(o) ==
                   (minimum == "0" ?
                      std::string("none") :
                      "2 of 3 processes take part (about 594 DoFs in the "
                      "initial mesh, Solver/Minimum DoFs per process = 250); "
                      "the others wait for them."),
                 "Minimum DoFs per process = " + minimum +
                   ": the processes that take part (2 of 3, or all)");
      checks.add(read_text(directory + "/log.txt")
                     .find(minimum == "0" ? ", 3 MPI processes, started " :
                                            ", 2 MPI processes (of 3 "
                                            "started), started ") !=
                   std::string::npos,
                 "Minimum DoFs per process = " + minimum +
                   ": the provenance line names the processes");
      checks.add(differing_columns("one", directory, 16, 1e-8).empty(),
                 "Minimum DoFs per process = " + minimum +
                   ": the answers of one process to 1e-8");
    }

  test_tools::write_text("a_file", "not a directory\n");
  const Outcome failed = run("a_file/results", 3);
  const auto    errors = error_lines(failed);
  out() << "an output directory below a file, 3 processes: exit code "
        << failed.code << ", " << errors.size() << " error line(s)"
        << std::endl;
  checks.add(failed.exited && failed.code == 1,
             "an error of the process that takes part ends every process "
             "with exit code 1 (no hang)");
  checks.add(errors.size() == 1 &&
               errors[0].find("Output/Directory") != std::string::npos,
             "one error message, naming Output/Directory");

  checks.assert_all();
}
