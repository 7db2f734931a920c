#ifndef dynamic_contact_resume_h
#define dynamic_contact_resume_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/output/output_directory.h>
#include <dynamic_contact/parameters/parameters.h>

#include <string>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * --resume: the newest checkpoint of @p directory whose files match its
   * manifest; damaged ones are named on @p pcout and passed over. Refuses
   * (CollectiveError) if there is none, or every one is damaged.
   */
  std::string
  newest_good_checkpoint(const std::string        &directory,
                         const MPI_Comm            comm,
                         const ConditionalOStream &pcout);

  /**
   * --resume: refuse (CollectiveError, saying what differs) a checkpoint
   * @p latest of another scene than @p parameters_of_run, or whose time
   * (@p saved) is after Time/End time.
   */
  void
  check_resumable(const std::string   &latest,
                  const RunState      &saved,
                  const std::string   &parameters_of_run,
                  const RunParameters &parameters,
                  const MPI_Comm       comm);

  /**
   * --resume (collective): time_series.csv becomes @p kept (its rows up to
   * the checkpoint), and the results of the interrupted continuation after
   * step @p step (contact CSVs, VTU pieces and records) are removed.
   */
  void
  take_over_results_after(OutputDirectory   &output_directory,
                          const std::string &kept,
                          const unsigned int step,
                          const MPI_Comm     comm);
} // namespace DynamicContact

#endif
