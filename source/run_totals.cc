#include <dynamic_contact/energy_balance.h>
#include <dynamic_contact/error_messages.h>
#include <dynamic_contact/run_totals.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <vector>

namespace DynamicContact
{
  void
  RunTotals::add(const unsigned int cutbacks,
                 const unsigned int convexification_iterations,
                 const double       coefficient_residual)
  {
    this->cutbacks += cutbacks;
    convexification += convexification_iterations;
    max_coefficient_residual =
      std::max(max_coefficient_residual, coefficient_residual);
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
        const auto value = [&](const std::string &name) {
          const auto c = std::find(header.begin(), header.end(), name);
          return c == header.end() ?
                   0. :
                   std::strtod(values[c - header.begin()].c_str(), nullptr);
        };
        add(static_cast<unsigned int>(value("cutbacks")),
            static_cast<unsigned int>(value("convexification_iterations")),
            value("coefficient_residual"));
      }
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
    const bool balance = state.max_relative_defect < 1e-8;
    const bool dissipation =
      state.min_dissipation >= -EnergyBalanceTerms::roundoff;
    pcout << "  energy balance: max relative defect "
          << (balance ? "below 1e-8" :
                        "ABOVE 1e-8 (" + sig6(state.max_relative_defect) + ")")
          << ", every dissipation term >= 0"
          << (parameters.time.scheme == Parameters::Time::Scheme::sdirk ?
                " (the compliance term left out: not sign-definite with "
                "sdirk)" :
                "")
          << ": "
          << (dissipation ?
                "yes" :
                "NO (" + sig6(state.min_dissipation) + " of the energy)")
          << std::endl;
    // The summary: what a user checks before trusting the results.
    pcout << "Summary: results in " << parameters.output.directory << "/\n"
          << "  time step cut-backs: " << cutbacks
          << "; steps kept with an unconverged convexification loop: "
          << state.unconverged_steps
          << "; steps whose Newton iteration ended at stagnation (residual "
             "below the square root of Solver/Newton tolerance): "
          << stagnated_steps << "\n"
          << "  largest relative energy balance defect: "
          << scientific(state.max_relative_defect, 2);
    if (friction)
      pcout << "; largest friction-law residual max |mu_i - mu(|w_tau,i|)|: "
            << scientific(max_coefficient_residual, 2)
            << " (Friction/Coefficient tolerance "
            << parameters.friction.coefficient_tolerance << ")";
    pcout << std::endl;

    // An honest ending: completed, or completed with what did not hold.
    std::vector<std::string> warnings;
    if (state.unconverged_steps > 0)
      warnings.push_back(
        std::to_string(state.unconverged_steps) + " step" +
        (state.unconverged_steps > 1 ? "s" : "") +
        " kept with an unconverged convexification loop (max |mu_i - "
        "mu(|w_tau,i|)| = " +
        sig6(state.worst_unconverged) + " > Friction/Coefficient tolerance)");
    if (!balance)
      warnings.push_back("energy balance defect " +
                         sig6(state.max_relative_defect) + " > 1e-8");
    if (!dissipation)
      warnings.push_back("a dissipation term below zero (" +
                         sig6(state.min_dissipation) + " of the energy)");
    std::string status = "completed";
    if (!warnings.empty())
      {
        status += " with warnings: ";
        for (unsigned int i = 0; i < warnings.size(); ++i)
          status += (i ? "; " : "") + warnings[i];
        pcout << "Warning: the run " << status
              << ". The results do not meet the tolerances there." << std::endl;
      }
    return status;
  }
} // namespace DynamicContact
