#include <dynamic_contact/output/output_schedule.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  OutputSchedule::OutputSchedule(const RunParameters &parameters)
    : output(parameters.output)
    , checkpoint(parameters.checkpoint)
    , time_step(parameters.time.time_step)
    , end_time(parameters.time.end_time)
  {}


  bool
  OutputSchedule::at_output_time(const double t, const double k) const
  {
    const double allowance = 1e-12 * std::max(std::abs(t), k);
    for (const double t_out : output.output_times)
      if (t_out <= t + allowance && t_out > t - k + allowance)
        return true;
    return false;
  }


  bool
  OutputSchedule::due(const unsigned int n,
                      const double       t,
                      const double       k,
                      const bool         last,
                      const unsigned int every) const
  {
    return last || at_output_time(t, k) || (every > 0 && n % every == 0);
  }


  bool
  OutputSchedule::contact_csv_due(const unsigned int n,
                                  const double       t,
                                  const double       k,
                                  const bool         last) const
  {
    return due(n, t, k, last, output.output_every);
  }


  bool
  OutputSchedule::vtu_due(const unsigned int n,
                          const double       t,
                          const double       k,
                          const bool         last) const
  {
    return output.write_vtu && due(n, t, k, last, output.vtu_every);
  }


  bool
  OutputSchedule::progress_due(const unsigned int n, const bool last) const
  {
    const unsigned int every = output.progress_every;
    return every > 0 && (n % every == 0 || last);
  }


  bool
  OutputSchedule::checkpoint_due(const unsigned int n, const bool last) const
  {
    return checkpoint.every > 0 && n % checkpoint.every == 0 && !last;
  }


  unsigned int
  OutputSchedule::remaining_steps(const double time) const
  {
    return static_cast<unsigned int>(
      std::ceil((end_time - time) / time_step - 1e-9));
  }


  unsigned int
  OutputSchedule::vtu_files_left(const unsigned int n, const double time) const
  {
    const unsigned int last    = n + remaining_steps(time);
    unsigned int       n_files = 0;
    for (unsigned int m = n + 1; m <= last; ++m)
      n_files += vtu_due(m, time + (m - n) * time_step, time_step, m == last);
    return n_files;
  }
} // namespace DynamicContact
