#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/run/step_attempts.h>

#include <algorithm>
#include <string>

namespace DynamicContact
{
  namespace
  {
    /**
     * Collective: nothing that is not finite reaches a file. Throws
     * NonFiniteValue naming the columns of @p row (of step @p n, ending at
     * @p t) that are not finite on some process.
     */
    void
    check_finite(const TimeSeriesRow &row,
                 const unsigned int   n,
                 const double         t,
                 const MPI_Comm       comm)
    {
      std::string bad;
      for (const auto &[name, value] : row.columns())
        if (value.find("nan") != std::string::npos ||
            value.find("inf") != std::string::npos)
          bad += (bad.empty() ? "" : ", ") + name;
      bad = collective_message(comm, bad);
      if (!bad.empty())
        throw NonFiniteValue("step " + std::to_string(n) + " (t = " + sig6(t) +
                             " s) produced values that are not "
                             "finite: " +
                             bad);
    }
  } // namespace


  template <int dim>
  StepRecord<dim>
  StepAttempts<dim>::take(const double remesh_energy_change, double &k)
  {
    double                k_next = 0;
    const StepRecord<dim> record =
      try_until_accepted(remesh_energy_change, k, k_next);
    accept(record, k, k_next);
    return record;
  }


  template <int dim>
  void
  StepAttempts<dim>::stop_with_last_good_state(const std::string &message)
  {
    files.write_last_good_state();
    std::string m = message;
    while (!m.empty() && m.back() == '.')
      m.pop_back();
    throw CollectiveError(m + ". The last good state (step " +
                          std::to_string(state.step) + ") is written to '" +
                          parameters.output.directory + "'.");
  }


  template <int dim>
  StepRecord<dim>
  StepAttempts<dim>::try_until_accepted(const double remesh_energy_change,
                                        double      &k,
                                        double      &k_next)
  {
    // A step the solver cannot solve is retried from the last good state
    // with half the time step, down to Time/Minimum time step; a step
    // whose error estimate is too large (Time/Adaptive) with a shorter one.
    const auto   good     = simulator.restore_point();
    unsigned int cutbacks = 0, rejected = 0;
    k_next = state.time_step;
    for (;;)
      {
        k = step_lengths.next(state);
        try
          {
            StepRecord<dim> record =
              simulator.do_time_step(state.step + 1,
                                     state.time + k,
                                     k,
                                     remesh_energy_change,
                                     cutbacks,
                                     rejected,
                                     !step_lengths.can_cut_back(k));
            check_finite(record.row(), state.step + 1, state.time + k, comm);
            if (parameters.time.adaptive)
              {
                const auto [accepted, k_new] =
                  step_lengths.controlled(state,
                                          k,
                                          record.time_error /
                                            parameters.time.adaptive_tolerance);
                if (!accepted)
                  {
                    // Rejected: again from the last good state.
                    simulator.restore(good);
                    state.time_step = k_new;
                    ++rejected;
                    continue;
                  }
                k_next = k_new;
              }
            return record;
          }
        catch (const NonFiniteValue &e)
          {
            simulator.restore(good);
            stop_with_last_good_state(e.what());
          }
        catch (const StepFailure &failure)
          {
            simulator.restore(good);
            if (!step_lengths.can_cut_back(k))
              // Stop, with the last good state written out (fields and a
              // checkpoint to continue from with other settings).
              stop_with_last_good_state(
                "step " + std::to_string(state.step + 1) +
                " (from t = " + sig6(state.time) +
                " s) could not be solved even with the minimum time step "
                "(Time/Minimum time step = " +
                sig6(parameters.time.minimum_time_step) +
                " s): " + failure.what());
            step_lengths.cut_back(state, k);
            ++cutbacks;
            report.print_cut_back(failure.what());
          }
      }
  }


  template <int dim>
  void
  StepAttempts<dim>::accept(const StepRecord<dim> &record,
                            const double           k,
                            const double           k_next)
  {
    step_lengths.accept(state, k, k_next, record.cutbacks);

    const auto &statistics = record.statistics;
    totals.add(
      {state.step,
       record.cutbacks,
       statistics.convexification_iterations,
       statistics.coefficient_residual,
       statistics.coupled_fallbacks,
       record.uniqueness_monitor ? statistics.uniqueness_bound : -1.,
       record.uniqueness_monitor ? statistics.uniqueness_certificate : -1.,
       record.uniqueness_monitor ? statistics.contraction_factor : -1.,
       statistics.cycles,
       statistics.solutions,
       statistics.failed_starts});
    if (simulator.newton_residual() > parameters.solver.newton_tolerance)
      ++totals.stagnated_steps;
    state.max_relative_defect =
      std::max(state.max_relative_defect, record.relative_energy_defect());
    state.min_dissipation =
      std::min(state.min_dissipation, record.relative_min_dissipation());
    state.total_newton += statistics.newton_iterations;
    if (!statistics.convexification_converged)
      {
        ++state.unconverged_steps;
        state.worst_unconverged =
          std::max(state.worst_unconverged, statistics.coefficient_residual);
        report.warn_unconverged(statistics.coefficient_residual);
      }
  }


  template class StepAttempts<2>;
  template class StepAttempts<3>;
} // namespace DynamicContact
