#ifndef dynamic_contact_step_lengths_h
#define dynamic_contact_step_lengths_h

#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/parameters/parameters.h>

#include <string>
#include <utility>

namespace DynamicContact
{
  /**
   * The rules for the length of each step of a run (Time): the nominal
   * Time/Time step k0, halved by a cut-back after a step the solver could
   * not solve (down to Time/Minimum time step) and growing back after good
   * steps, or with Time/Adaptive the controller's length on the grid
   * k0 * 2^j; steps that end exactly at the Output times and at T; the time
   * of an accepted step snapped back to the nominal grid. The TimeLoop
   * keeps the RunState; these functions read it or update its time, step,
   * time step and cut-back count, and nothing else.
   */
  class StepLengths
  {
  public:
    explicit StepLengths(const RunParameters &parameters);

    /**
     * The length k of the next try from @p state: its time step, shortened
     * to end at the Output times and at T (Time/Adaptive), no sliver of a
     * step.
     */
    double
    next(const RunState &state) const;

    /**
     * Time/Adaptive's controller after a step of @p k from @p state whose
     * error estimate is @p error (relative to the tolerance): whether the
     * step is accepted, and the next k (of the next step, or of the next
     * try of a rejected one), on the grid Time step * 2^j.
     */
    std::pair<bool, double>
    controlled(const RunState &state, const double k, const double error) const;

    /** Whether a step of size @p k that fails may be retried with k/2
     *  (Time/Minimum time step). */
    bool
    can_cut_back(const double k) const;

    /** A try of @p k failed: the next one is k/2, and the time step grows
     *  back only after good steps again. */
    void
    cut_back(RunState &state, const double k) const;

    /**
     * After an accepted step of @p k, tried with @p cutbacks cut-backs: the
     * next step and its time (back on the nominal grid and on T up to
     * round-off), the next time step (@p k_next with Time/Adaptive, else
     * doubled after three good steps, up to Time/Time step).
     */
    void
    accept(RunState          &state,
           const double       k,
           const double       k_next,
           const unsigned int cutbacks) const;

    /**
     * --resume from a checkpoint written with Time/Time step @p old_step
     * (its text; empty if unknown): a new time step is honoured from the
     * checkpoint on (returns true); otherwise the cut-back state goes on,
     * within the time steps allowed now.
     */
    bool
    resume(RunState &state, const std::string &old_step) const;

    /** Whether @p time is the end time up to round-off: the run is over. */
    bool
    at_end(const double time) const;

  private:
    const RunParameters &parameters;
  };
} // namespace DynamicContact

#endif
