// The Open MPI settings of a one-process start (mpi_startup.h):
// - open_mpi_singleton_settings() on environments made by hand: started
//   without a launcher, the three settings; a launcher's or a batch
//   system's variable (mpirun, PMIx, PMI, Slurm, ...), nothing; a value the
//   user set is never replaced, and a user's choice of the MPI-IO component
//   (OMPI_MCA_io) or OMPI_MCA_ess_singleton_isolated=0 keeps the daemon
//   (and OMPIO);
// - the program as a user starts it: by itself it runs with the ob1 PML
//   (Open MPI's own report, OMPI_MCA_pml_base_verbose), and the cm PML is
//   never opened; a PML the user names wins (OMPI_MCA_pml=bogus: MPI_Init
//   fails naming it); with OMPI_MCA_ess_singleton_isolated=0 it still runs.
// That a one-process run writes and reads the MPI-IO checkpoints of a
// distributed mesh with these settings is checked by checkpoint_restart
// (its one-process runs of the adaptive scene).
//
// This test does not initialize MPI itself: an MPI singleton puts its
// daemon's PMIx variables into its environment, which a program it starts
// would take for a launcher's.

#include <dynamic_contact/run/mpi_startup.h>

#include "program_tools.h"

#include <map>
#include <string>
#include <vector>

using namespace program_tools;
using DynamicContact::open_mpi_singleton_settings;

namespace
{
  std::string
  settings_text(const std::map<std::string, std::string> &environment)
  {
    std::string text;
    for (const auto &[name, value] : open_mpi_singleton_settings(environment))
      text += (text.empty() ? "" : " ") + name + "=" + value;
    return text.empty() ? "(none)" : text;
  }

  /** An environment: the variables added to a plain one, what is set. */
  struct Case
  {
    std::string                        what;
    std::map<std::string, std::string> added;
    std::string                        expected;
  };

  std::vector<Case>
  cases()
  {
    const std::string all =
      "OMPI_MCA_pml=ob1 OMPI_MCA_ess_singleton_isolated=1 "
      "OMPI_MCA_io_romio321_priority=100";
    std::vector<Case> cases = {
      {"no launcher", {}, all},
      {"mpirun", {{"OMPI_COMM_WORLD_SIZE", "1"}}, "(none)"},
      {"mpirun (hnp uri)", {{"OMPI_MCA_orte_hnp_uri", "x"}}, "(none)"},
      {"PMIx launcher", {{"PMIX_RANK", "0"}}, "(none)"},
      {"PMI launcher", {{"PMI_RANK", "0"}}, "(none)"},
      {"Slurm job", {{"SLURM_JOB_ID", "12"}}, "(none)"},
      {"user's pml",
       {{"OMPI_MCA_pml", "ucx"}},
       "OMPI_MCA_ess_singleton_isolated=1 "
       "OMPI_MCA_io_romio321_priority=100"},
      {"user's isolated=1",
       {{"OMPI_MCA_ess_singleton_isolated", "1"}},
       "OMPI_MCA_pml=ob1 OMPI_MCA_io_romio321_priority=100"},
      {"user's isolated=0",
       {{"OMPI_MCA_ess_singleton_isolated", "0"}},
       "OMPI_MCA_pml=ob1"},
      {"user's isolated=false",
       {{"OMPI_MCA_ess_singleton_isolated", "False"}},
       "OMPI_MCA_pml=ob1"},
      {"user's io", {{"OMPI_MCA_io", "ompio"}}, "OMPI_MCA_pml=ob1"},
      {"user's romio priority",
       {{"OMPI_MCA_io_romio321_priority", "5"}},
       "OMPI_MCA_pml=ob1 OMPI_MCA_ess_singleton_isolated=1"},
      {"user's pml, isolated and priority",
       {{"OMPI_MCA_pml", "ob1"},
        {"OMPI_MCA_ess_singleton_isolated", "1"},
        {"OMPI_MCA_io_romio321_priority", "100"}},
       "(none)"}};
    for (const auto &name : DynamicContact::launch_variables())
      cases.push_back({"launch variable " + name, {{name, ""}}, "(none)"});
    return cases;
  }

  /** 1. The choice, as a function of the environment. */
  void
  check_settings(Checks &checks)
  {
    const std::map<std::string, std::string> plain = {{"HOME", "/home/u"},
                                                      {"PATH", "/usr/bin"}};
    for (const auto &c : cases())
      {
        auto environment = plain;
        environment.insert(c.added.begin(), c.added.end());
        const std::string got = settings_text(environment);
        test_tools::out() << c.what << ": " << got << std::endl;
        checks.add(got == c.expected, c.what + ": sets '" + c.expected + "'");
      }
  }

  /**
   * 2. The program as a user starts it: without a launcher, and outside a
   * batch job even if the test runs in one (env -u).
   */
  Outcome
  by_itself(const std::string              &name,
            const std::vector<std::string> &environment)
  {
    std::vector<std::string> arguments;
    for (const auto &variable : DynamicContact::launch_variables())
      {
        arguments.push_back("-u");
        arguments.push_back(variable);
      }
    arguments.push_back(DYNAMIC_CONTACT_EXECUTABLE);
    arguments.push_back("--version");
    Launch launch;
    launch.name        = name;
    launch.environment = environment;
    launch.program     = "env";
    return execute(arguments, launch);
  }

  /** Whether the run printed the version. */
  bool
  runs(const Outcome &o)
  {
    return o.succeeded() && o.out.rfind("dynamic-contact ", 0) == 0;
  }

  void
  check_program(Checks &checks)
  {
    std::ostream &out = test_tools::out();
    {
      const Outcome o = by_itself("plain", {"OMPI_MCA_pml_base_verbose=10"});
      const bool    ob1 =
        o.err.find("select: component ob1 selected") != std::string::npos;
      const bool cm_opened = o.err.find("component cm") != std::string::npos;
      out << "by itself: exit code " << o.code
          << ", ob1 selected: " << yes_no(ob1)
          << ", cm opened: " << yes_no(cm_opened) << std::endl;
      checks.add(runs(o), "by itself: --version runs");
      checks.add(ob1 && !cm_opened,
                 "by itself: the ob1 PML, the cm PML never opened");
    }
    {
      const Outcome o     = by_itself("bogus_pml", {"OMPI_MCA_pml=bogus"});
      const bool    named = o.err.find("bogus") != std::string::npos;
      out << "OMPI_MCA_pml=bogus: exit code non-zero: " << yes_no(o.code != 0)
          << ", the error names it: " << yes_no(named) << std::endl;
      checks.add(o.exited && o.code != 0 && named,
                 "the user's OMPI_MCA_pml wins (MPI_Init fails naming "
                 "'bogus')");
    }
    {
      const Outcome o =
        by_itself("daemon", {"OMPI_MCA_ess_singleton_isolated=0"});
      out << "OMPI_MCA_ess_singleton_isolated=0: exit code " << o.code
          << std::endl;
      checks.add(runs(o),
                 "with OMPI_MCA_ess_singleton_isolated=0 (the daemon) "
                 "--version runs");
    }
  }
} // namespace


int
main()
{
  Checks checks;
  check_settings(checks);
  check_program(checks);
  checks.assert_all();
}
