#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/run/run_totals.h>
#include <dynamic_contact/time/energy_balance.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <vector>

namespace DynamicContact
{
  namespace
  {
    /** ": s1 s2 ..." for the first ten of @p steps (nothing if none). */
    void
    print_steps(const ConditionalOStream        &pcout,
                const std::vector<unsigned int> &steps)
    {
      if (steps.empty())
        return;
      pcout << ":";
      const std::size_t shown = std::min<std::size_t>(steps.size(), 10);
      for (std::size_t i = 0; i < shown; ++i)
        pcout << " " << steps[i];
      if (shown < steps.size())
        pcout << " ...";
    }


    /**
     * What the run's energy balance shows: whether its largest relative
     * defect is below 1e-8 (balance) and every dissipation term is at least
     * 0, up to round-off (dissipation).
     */
    struct EnergyChecks
    {
      explicit EnergyChecks(const RunState &state)
        : balance(state.max_relative_defect < 1e-8)
        , dissipation(state.min_dissipation >= -EnergyBalanceTerms::roundoff)
      {}

      bool balance;
      bool dissipation;
    };


    /** The line on the energy balance, what @p checks found. */
    void
    print_energy_balance(const ConditionalOStream &pcout,
                         const RunState           &state,
                         const RunParameters      &parameters,
                         const EnergyChecks       &checks)
    {
      pcout << "  energy balance: max relative defect "
            << (checks.balance ?
                  "below 1e-8" :
                  "ABOVE 1e-8 (" + sig6(state.max_relative_defect) + ")")
            << ", every dissipation term >= 0"
            << (parameters.time.scheme->compliance_dissipation_is_signed() ?
                  std::string() :
                  " (the compliance term left out: not sign-definite with " +
                    parameters.time.scheme_name + ")")
            << ": "
            << (checks.dissipation ?
                  "yes" :
                  "NO (" + sig6(state.min_dissipation) + " of the energy)")
            << std::endl;
    }


    /**
     * The run's status, "completed" or "completed with warnings: ..."
     * (unconverged steps, the energy balance, the dissipation), and the
     * warning printed where there are any.
     */
    std::string
    final_status(const ConditionalOStream &pcout,
                 const RunState           &state,
                 const EnergyChecks       &checks)
    {
      std::vector<std::string> warnings;
      if (state.unconverged_steps > 0)
        warnings.push_back(
          std::to_string(state.unconverged_steps) + " step" +
          (state.unconverged_steps > 1 ? "s" : "") +
          " kept with an unconverged convexification loop (max |mu_i - "
          "mu(|w_tau,i|)| = " +
          sig6(state.worst_unconverged) + " > Friction/Coefficient tolerance)");
      if (!checks.balance)
        warnings.push_back("energy balance defect " +
                           sig6(state.max_relative_defect) + " > 1e-8");
      if (!checks.dissipation)
        warnings.push_back("a dissipation term below zero (" +
                           sig6(state.min_dissipation) + " of the energy)");
      std::string status = "completed";
      if (!warnings.empty())
        {
          status += " with warnings: ";
          for (unsigned int i = 0; i < warnings.size(); ++i)
            status += (i ? "; " : "") + warnings[i];
          pcout << "Warning: the run " << status
                << ". The results do not meet the tolerances there."
                << std::endl;
        }
      return status;
    }
  } // namespace


  void
  RunTotals::add(const Step &step)
  {
    cutbacks += step.cutbacks;
    convexification += step.convexification_iterations;
    max_coefficient_residual =
      std::max(max_coefficient_residual, step.coefficient_residual);
    coupled_fallbacks += step.coupled_fallbacks;
    cycling_steps += step.active_set_cycles > 0;
    if (step.contraction_factor >= 1)
      repelling_steps.push_back(step.step);
    max_contraction = std::max(max_contraction, step.contraction_factor);
    if (step.uniqueness_bound >= 0)
      {
        ++bound_steps;
        proven_steps +=
          step.uniqueness_certificate >= 0 && step.uniqueness_certificate < 1;
      }
    max_uniqueness_bound =
      std::max(max_uniqueness_bound, step.uniqueness_bound);
    if (step.solutions > 0)
      {
        ++counted_steps;
        if (step.solutions > 1)
          several_solution_steps.push_back(step.step);
      }
    failed_starts += step.failed_starts;
  }


  void
  RunTotals::add_rows(const std::string &time_series)
  {
    // The end summary covers the steps before the checkpoint too (rank 0
    // holds the rows; only rank 0 prints).
    const auto lines = Utilities::split_string_list(time_series, '\n');
    std::vector<std::string> header;
    for (const auto &line : lines)
      {
        const auto values = Utilities::split_string_list(line, ',');
        if (header.empty())
          {
            header = values;
            continue;
          }
        if (values.size() != header.size() || values[0] == "0")
          continue; // row 0 is the initial state
        // The counts of the end summary, by column name.
        const auto has = [&](const std::string &name) {
          return std::find(header.begin(), header.end(), name) != header.end();
        };
        const auto value = [&](const std::string &name) {
          const auto c = std::find(header.begin(), header.end(), name);
          return c == header.end() ?
                   0. :
                   std::strtod(values[c - header.begin()].c_str(), nullptr);
        };
        add({static_cast<unsigned int>(value("step")),
             static_cast<unsigned int>(value("cutbacks")),
             static_cast<unsigned int>(value("convexification_iterations")),
             value("coefficient_residual"),
             static_cast<unsigned int>(value("coupled_fallbacks")),
             has("uniqueness_bound") ? value("uniqueness_bound") : -1.,
             has("uniqueness_certificate") ? value("uniqueness_certificate") :
                                             -1.,
             has("contraction_factor") ? value("contraction_factor") : -1.,
             static_cast<unsigned int>(value("active_set_cycles")),
             static_cast<unsigned int>(value("solutions")),
             static_cast<unsigned int>(value("failed_starts"))});
      }
  }


  void
  RunTotals::print_uniqueness(const ConditionalOStream &pcout) const
  {
    // What the measures prove (doc/theory.md section 5.2): the bound is a
    // sufficient condition, proven where its certificate is below 1; above
    // 1 it proves nothing.
    pcout << "  uniqueness: one solution proven (sufficient condition rho(C "
             "Lambda) < 1, certified from above) at "
          << proven_steps << " of " << bound_steps
          << " steps evaluated (largest bound " << sig6(max_uniqueness_bound)
          << "; at 1 or more nothing is proven); contraction factor at the "
             "solution >= 1 (the frozen loop may be repelled from it) at "
          << repelling_steps.size() << " step"
          << (repelling_steps.size() == 1 ? "" : "s");
    print_steps(pcout, repelling_steps);
    pcout << " (largest " << sig6(std::max(max_contraction, 0.)) << ")"
          << std::endl;
  }


  void
  RunTotals::print_solution_count(const ConditionalOStream &pcout) const
  {
    // Friction/Count solutions (doc/theory.md section 5.3): two or more
    // distinct verified solutions prove several; one proves nothing.
    pcout << "  solution count: two or more distinct solutions (from the "
             "starts previous, stick, fast slip, coupled; each to a "
             "coefficient residual of Coefficient tolerance/100) at "
          << several_solution_steps.size() << " of " << counted_steps
          << " steps counted";
    print_steps(pcout, several_solution_steps);
    pcout << "; starts that reached no solution: " << failed_starts
          << std::endl;
  }


  std::string
  RunTotals::print_summary(const ConditionalOStream &pcout,
                           const RunState           &state,
                           const RunParameters      &parameters,
                           const bool                friction) const
  {
    pcout << "Completed " << state.step << " steps (t = " << sig6(state.time)
          << " s)";
    if (parameters.output.print_iteration_counts) // see print_progress()
      {
        pcout << ", " << state.total_newton << " Newton iterations (mean "
              << std::fixed << std::setprecision(2)
              << static_cast<double>(state.total_newton) /
                   std::max(state.step, 1u)
              << std::defaultfloat << " per step)";
        if (friction)
          pcout << ", " << convexification << " convexification passes";
      }
    pcout << ".\n";
    const EnergyChecks checks(state);
    print_energy_balance(pcout, state, parameters, checks);
    // The summary: what a user checks before trusting the results.
    pcout << "Summary: results in " << parameters.output.directory << "/\n"
          << "  time step cut-backs: " << cutbacks
          << "; steps kept with an unconverged convexification loop: "
          << state.unconverged_steps
          << "; steps whose Newton iteration ended at stagnation (residual "
             "below the square root of Solver/Newton tolerance): "
          << stagnated_steps;
    // A count of iterations, which follows round-off as they do (see
    // print_progress()).
    if (parameters.output.print_iteration_counts)
      pcout << "; steps whose Newton iteration cycled (came back to active "
               "sets or an iterate it had seen; damped steps from there on): "
            << cycling_steps;
    pcout << "\n"
          << "  largest relative energy balance defect: "
          << scientific(state.max_relative_defect, 2);
    if (friction)
      pcout << "; largest friction-law residual max |mu_i - mu(|w_tau,i|)|: "
            << scientific(max_coefficient_residual, 2)
            << " (Friction/Coefficient tolerance "
            << parameters.friction.coefficient_tolerance << ")";
    pcout << std::endl;
    if (friction && parameters.friction.coupled_linearization &&
        !parameters.friction.law->is_constant())
      pcout << "  coupled linearization: fell back to the frozen loop in "
            << coupled_fallbacks << " step"
            << (coupled_fallbacks == 1 ? "" : "s") << std::endl;
    if (friction && (bound_steps > 0 || max_contraction >= 0))
      print_uniqueness(pcout);
    if (counted_steps > 0)
      print_solution_count(pcout);

    // An honest ending: completed, or completed with what did not hold.
    return final_status(pcout, state, checks);
  }
} // namespace DynamicContact
