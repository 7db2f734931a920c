#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/output/resume.h>

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <vector>

namespace DynamicContact
{
  std::string
  newest_good_checkpoint(const std::string        &directory,
                         const MPI_Comm            comm,
                         const ConditionalOStream &pcout)
  {
    // The newest checkpoint whose files match its manifest; damaged ones
    // are named and passed over.
    const auto  checkpoints = list_checkpoints(directory, comm);
    std::string latest;
    std::string damaged;
    for (const auto &name : checkpoints)
      {
        const std::string problem =
          verify_checkpoint(directory + "/" + name, comm);
        if (problem.empty())
          {
            latest = directory + "/" + name;
            break;
          }
        damaged += (damaged.empty() ? "" : "; ") + name + ": " + problem;
        pcout << "Warning: the checkpoint " << directory << "/" << name
              << " is damaged: " << problem << "; it is not used." << std::endl;
      }
    if (checkpoints.empty())
      throw CollectiveError("--resume: there is no complete checkpoint in "
                            "Output/Directory '" +
                            directory +
                            "' (the interrupted run needs Checkpoint/Every "
                            "> 0).");
    if (latest.empty())
      throw CollectiveError(
        "--resume: no checkpoint in Output/Directory '" + directory +
        "' can be used, every one is "
        "damaged (" +
        damaged + "). Nothing was changed; start a new run.");
    return latest;
  }


  void
  check_resumable(const std::string   &latest,
                  const RunState      &saved,
                  const std::string   &parameters_of_run,
                  const RunParameters &parameters,
                  const MPI_Comm       comm)
  {
    // The same problem, or a refusal that says what differs.
    const auto differences =
      scene_differences(read_checkpoint_parameters(latest, comm),
                        parameters_of_run);
    if (!differences.empty())
      {
        std::string list;
        for (const auto &d : differences)
          list += (list.empty() ? "" : "; ") + d;
        throw CollectiveError(
          "--resume: the scene differs from that of the checkpoint '" + latest +
          "' in " + std::to_string(differences.size()) +
          (differences.size() == 1 ? " entry: " : " entries: ") + list +
          ". A resumed run continues the same problem; only Time/End time "
          "(later), Time/Time step, Time/Minimum time step, Solver, Output, "
          "Checkpoint and the convexification loop's settings may change "
          "(README, 'What can go wrong'). Nothing was changed.");
      }
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    if (T < saved.time - 1e-9 * k0)
      throw CollectiveError("--resume: Time/End time = " + sig6(T) +
                            " s is before the time of the checkpoint '" +
                            latest + "' (t = " + sig6(saved.time) +
                            " s). Nothing was changed.");
  }


  void
  take_over_results_after(OutputDirectory   &output_directory,
                          const std::string &kept,
                          const unsigned int step,
                          const MPI_Comm     comm)
  {
    collectively_on_rank_zero(comm, [&]() {
      output_directory.claim("time_series.csv");
      replace_file(output_directory.file("time_series.csv"), kept, true);
      static const std::regex result(
        R"((contact|solution|contact_surface)_([0-9]{5,})\.(csv|pvtu|[0-9]+\.vtu))");
      std::vector<std::string> superseded;
      for (const auto &name : output_directory.owned())
        {
          std::smatch m;
          if (std::regex_match(name, m, result) &&
              std::stoul(m[2].str()) > step)
            superseded.push_back(name);
        }
      output_directory.remove(superseded);
    });
  }
} // namespace DynamicContact
