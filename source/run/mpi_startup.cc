#include <dynamic_contact/run/mpi_startup.h>

#include <mpi.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>

extern char **environ;

namespace DynamicContact
{
  const std::vector<std::string> &
  launch_variables()
  {
    static const std::vector<std::string> names = {
      // Open MPI's mpirun (orterun; prterun in Open MPI 5).
      "OMPI_COMM_WORLD_SIZE",
      "OMPI_COMM_WORLD_RANK",
      "OMPI_UNIVERSE_SIZE",
      "OMPI_MCA_orte_hnp_uri",
      "OMPI_MCA_ess_base_jobid",
      // PMIx and PMI(-2) launchers: srun --mpi=..., MPICH's and Intel
      // MPI's hydra.
      "PMIX_RANK",
      "PMIX_NAMESPACE",
      "PMI_RANK",
      "PMI_SIZE",
      "PMI_FD",
      // Batch systems (a process in a job, started by srun or not).
      "SLURM_PROCID",
      "SLURM_JOB_ID",
      "PBS_JOBID",
      "LSB_JOBID",
      "FLUX_JOB_ID",
      "ALPS_APP_PE",
      "PALS_RANKID"};
    return names;
  }


  namespace
  {
    /** Open MPI's reading of a boolean parameter's value as false. */
    bool
    says_false(std::string value)
    {
      std::transform(value.begin(),
                     value.end(),
                     value.begin(),
                     [](const unsigned char c) { return std::tolower(c); });
      return value == "0" || value == "false" || value == "no" ||
             value == "off" || value == "disabled";
    }
  } // namespace


  std::vector<std::pair<std::string, std::string>>
  open_mpi_singleton_settings(
    const std::map<std::string, std::string> &environment)
  {
    for (const auto &name : launch_variables())
      if (environment.count(name) > 0)
        return {};

    std::vector<std::pair<std::string, std::string>> settings;
    const auto                                       set_unless_given =
      [&](const std::string &name, const std::string &value) {
        if (environment.count(name) == 0)
          settings.emplace_back(name, value);
      };

    set_unless_given("OMPI_MCA_pml", "ob1");

    // Without orted, MPI-IO needs ROMIO; who chose the MPI-IO component
    // keeps orted.
    if (environment.count("OMPI_MCA_io") > 0)
      return settings;
    set_unless_given("OMPI_MCA_ess_singleton_isolated", "1");
    const auto isolated = environment.find("OMPI_MCA_ess_singleton_isolated");
    if (isolated == environment.end() || !says_false(isolated->second))
      set_unless_given("OMPI_MCA_io_romio321_priority", "100");
    return settings;
  }


  std::vector<std::pair<std::string, std::string>>
  set_open_mpi_singleton_defaults()
  {
#if defined(OPEN_MPI) && OPEN_MPI && defined(OMPI_MAJOR_VERSION) && \
  OMPI_MAJOR_VERSION == 4
    std::map<std::string, std::string> environment;
    for (char **entry = environ; entry != nullptr && *entry != nullptr;
         ++entry)
      {
        const std::string text = *entry;
        const auto        eq   = text.find('=');
        if (eq != std::string::npos)
          environment.emplace(text.substr(0, eq), text.substr(eq + 1));
      }
    const auto settings = open_mpi_singleton_settings(environment);
    for (const auto &[name, value] : settings)
      setenv(name.c_str(), value.c_str(), 0);
    return settings;
#else
    // Another MPI (or another Open MPI series, whose parameters have other
    // names): nothing to set.
    return {};
#endif
  }
} // namespace DynamicContact
