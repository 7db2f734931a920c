#ifndef dynamic_contact_output_schedule_h
#define dynamic_contact_output_schedule_h

#include <dynamic_contact/parameters/parameters.h>

namespace DynamicContact
{
  /**
   * When a step writes what (Output, Checkpoint): step n, ending at t after
   * a step of length k, the last step of the run or not. An Output/Output
   * times entry is due at the first step that reaches it; the contact CSVs
   * also every Output every steps, the VTU files (unless switched off)
   * every VTU every steps, progress lines every Progress every steps, and
   * checkpoints every Checkpoint/Every steps but not after the last one.
   */
  class OutputSchedule
  {
  public:
    explicit OutputSchedule(const RunParameters &parameters);

    bool
    contact_csv_due(const unsigned int n,
                    const double       t,
                    const double       k,
                    const bool         last) const;
    bool
    vtu_due(const unsigned int n,
            const double       t,
            const double       k,
            const bool         last) const;
    bool
    progress_due(const unsigned int n, const bool last) const;
    bool
    checkpoint_due(const unsigned int n, const bool last) const;

    /** Steps left after @p time at the nominal time step. */
    unsigned int
    remaining_steps(const double time) const;
    /**
     * The VTU files a run at step @p n and @p time will still write (the
     * steps to come at the nominal time step).
     */
    unsigned int
    vtu_files_left(const unsigned int n, const double time) const;

  private:
    const Parameters::Output     &output;
    const Parameters::Checkpoint &checkpoint;
    const double                  time_step;
    const double                  end_time;

    /**
     * Whether an Output/Output times entry falls in the step (t - k, t]
     * (with a round-off allowance: an output time on the time grid belongs
     * to the step ending there).
     */
    bool
    at_output_time(const double t, const double k) const;
    /**
     * The last step, an Output times entry in the step, or every @p every
     * steps (0: not periodically).
     */
    bool
    due(const unsigned int n,
        const double       t,
        const double       k,
        const bool         last,
        const unsigned int every) const;
  };
} // namespace DynamicContact

#endif
