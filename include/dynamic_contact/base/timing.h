#ifndef dynamic_contact_timing_h
#define dynamic_contact_timing_h

#include <deal.II/base/timer.h>

#include <string>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * A section of the run's TimerOutput that excludes the sections opened
   * inside it: while an inner TimerSection is open, the enclosing one is
   * left (deal.II's TimerOutput::Scope would let both run, so that nested
   * sections are counted twice and the percentages of deal.II's summary add
   * up to more than 100 %). The sections of a run are thus disjoint, and
   * timing_table() lists them with the time outside every section, adding
   * up to the wall time. Every section of the program is opened with this
   * class. Like TimerOutput::Scope it is entered and left by every process
   * together (TimerOutput synchronizes the processes' lap times).
   */
  class TimerSection
  {
  public:
    TimerSection(TimerOutput &timer, const std::string &name);
    ~TimerSection();
    TimerSection(const TimerSection &) = delete;
    TimerSection &
    operator=(const TimerSection &) = delete;

  private:
    TimerOutput      &timer;
    const std::string name;
  };

  /**
   * The table of the sections of @p timer (opened with TimerSection): calls,
   * wall time and share of @p total_wall_time for each, and the time
   * outside every section; the rows add up to the total.
   */
  std::string
  timing_table(const TimerOutput &timer, const double total_wall_time);

  /** Forget the bookkeeping of @p timer (before it is destroyed). */
  void
  forget_timer(const TimerOutput &timer);
} // namespace DynamicContact

#endif
