#include <dynamic_contact/base/timing.h>

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>
#include <vector>

namespace DynamicContact
{
  namespace
  {
    /** The open sections of a timer (innermost last) and the calls of each
     *  section (entries by a TimerSection, not the re-entries after an
     *  inner section). */
    struct Bookkeeping
    {
      std::vector<std::string>            open;
      std::map<std::string, unsigned int> calls;
    };

    std::map<const TimerOutput *, Bookkeeping> &
    bookkeeping()
    {
      static std::map<const TimerOutput *, Bookkeeping> all;
      return all;
    }
  } // namespace


  TimerSection::TimerSection(TimerOutput &timer, const std::string &name)
    : timer(timer)
    , name(name)
  {
    auto &b = bookkeeping()[&timer];
    if (!b.open.empty())
      timer.leave_subsection(b.open.back());
    timer.enter_subsection(name);
    b.open.push_back(name);
    ++b.calls[name];
  }


  TimerSection::~TimerSection()
  {
    auto &b = bookkeeping()[&timer];
    try
      {
        timer.leave_subsection(name);
        if (!b.open.empty())
          b.open.pop_back();
        if (!b.open.empty())
          timer.enter_subsection(b.open.back());
      }
    catch (...)
      {}
  }


  std::string
  timing_table(const TimerOutput &timer, const double total_wall_time)
  {
    const auto  times = timer.get_summary_data(TimerOutput::total_wall_time);
    const auto  it    = bookkeeping().find(&timer);
    double      in_sections = 0;
    std::size_t width       = 24;
    for (const auto &[name, t] : times)
      {
        in_sections += t;
        width = std::max(width, name.size());
      }
    // The processes' lap times are synchronized (their maximum): the
    // sections may exceed rank 0's clock by a little; the total is then
    // their sum.
    const double outside = std::max(0., total_wall_time - in_sections);
    const double total   = in_sections + outside;

    std::ostringstream out;
    const auto         row =
      [&](const std::string &name, const std::string &calls, const double t) {
        out << "  " << std::left << std::setw(width) << name << std::right
            << std::setw(9) << calls << std::fixed << std::setprecision(3)
            << std::setw(11) << t << " s" << std::setprecision(1)
            << std::setw(8) << (total > 0 ? 100 * t / total : 0.) << " %\n";
      };
    out << "Timings (wall clock; each section excludes the sections opened "
           "inside it, the rows add up to the total):\n";
    out << "  " << std::left << std::setw(width) << "section" << std::right
        << std::setw(9) << "calls" << std::setw(13) << "time" << std::setw(10)
        << "share"
        << "\n";
    for (const auto &[name, t] : times)
      {
        unsigned int calls = 0;
        if (it != bookkeeping().end())
          {
            const auto c = it->second.calls.find(name);
            if (c != it->second.calls.end())
              calls = c->second;
          }
        row(name, std::to_string(calls), t);
      }
    row("(outside every section)", "", outside);
    row("total", "", total);
    return out.str();
  }


  void
  forget_timer(const TimerOutput &timer)
  {
    bookkeeping().erase(&timer);
  }
} // namespace DynamicContact
