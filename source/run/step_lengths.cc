#include <dynamic_contact/run/step_lengths.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace DynamicContact
{
  StepLengths::StepLengths(const RunParameters &parameters)
    : parameters(parameters)
  {}


  double
  StepLengths::next(const RunState &state) const
  {
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    double       k  = std::min(state.time_step, T - state.time);
    if (parameters.time.adaptive)
      {
        // Steps end exactly at the Output times and at T; a target less
        // than two steps away is reached in two equal ones (no sliver of a
        // step).
        const double        k_wanted = state.time_step;
        std::vector<double> targets  = parameters.output.output_times;
        targets.push_back(T);
        for (const double target : targets)
          {
            const double left = target - state.time;
            if (left > 1e-9 * k_wanted && left < k + 1e-9 * k_wanted)
              k = left;
            else if (left > 1e-9 * k_wanted && left < 2 * k)
              k = std::min(k, left / 2);
          }
      }
    if (T - state.time - k < 1e-9 * k0) // no sliver of a last step
      k = T - state.time;
    return k;
  }


  std::pair<bool, double>
  StepLengths::controlled(const RunState &state,
                          const double    k,
                          const double    error) const
  {
    // The usual controller: the local error of a scheme of order p scales
    // like k^(p+1).
    const double order = parameters.time.scheme->local_error_order();
    const double factor =
      error > 0 ?
        std::min(2., std::max(0.2, 0.9 * std::pow(error, -1. / order))) :
        2.;
    const double k0    = parameters.time.time_step;
    const double k_min = parameters.time.minimum_time_step;
    // k on the grid Time step * 2^j (rounded down): a new k costs new
    // factorizations of K0, so k changes only by factors of 2 and stays
    // while the estimate allows it.
    const auto on_grid = [k0](const double x) {
      return k0 * std::pow(2., std::floor(std::log2(x / k0) + 1e-9));
    };
    if (error > 1 && k > k_min * (1 + 1e-12))
      return {false, std::max(k_min, on_grid(k * factor))};
    // A step shortened to end at an Output time does not shrink the next
    // one.
    const double k_next = (k < state.time_step && factor >= 1) ?
                            state.time_step :
                            on_grid(k * factor);
    return {true,
            std::min(parameters.time.maximum_time_step,
                     std::max(k_min, k_next))};
  }


  bool
  StepLengths::can_cut_back(const double k) const
  {
    return k / 2 >= parameters.time.minimum_time_step * (1 - 1e-12);
  }


  void
  StepLengths::cut_back(RunState &state, const double k) const
  {
    state.time_step                = k / 2;
    state.good_steps_since_cutback = 0;
  }


  void
  StepLengths::accept(RunState          &state,
                      const double       k,
                      const double       k_next,
                      const unsigned int cutbacks) const
  {
    const double T  = parameters.time.end_time;
    const double k0 = parameters.time.time_step;
    ++state.step;
    state.time += k;
    // Back on the nominal grid (and on T) up to round-off.
    const double n_nominal = std::round(state.time / k0);
    if (std::abs(state.time - n_nominal * k0) < 1e-9 * k0)
      state.time = std::min(n_nominal * k0, T);
    if (std::abs(state.time - T) < 1e-9 * k0)
      state.time = T;
    // The time step grows back after good steps (Time/Adaptive: it follows
    // the error estimate).
    if (parameters.time.adaptive)
      state.time_step = k_next;
    else if (cutbacks == 0 && state.time_step < k0 &&
             ++state.good_steps_since_cutback >= 3)
      {
        state.time_step                = std::min(2 * state.time_step, k0);
        state.good_steps_since_cutback = 0;
      }
  }


  bool
  StepLengths::resume(RunState &state, const std::string &old_step) const
  {
    const double k0 = parameters.time.time_step;
    const bool   step_changed =
      !old_step.empty() && std::strtod(old_step.c_str(), nullptr) != k0;
    if (step_changed)
      {
        state.time_step                = k0;
        state.good_steps_since_cutback = 0;
      }
    else
      state.time_step = std::max(std::min(state.time_step,
                                          parameters.time.adaptive ?
                                            parameters.time.maximum_time_step :
                                            k0),
                                 parameters.time.minimum_time_step);
    return step_changed;
  }


  bool
  StepLengths::at_end(const double time) const
  {
    return time >= parameters.time.end_time - 1e-9 * parameters.time.time_step;
  }
} // namespace DynamicContact
