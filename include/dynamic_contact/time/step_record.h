#ifndef dynamic_contact_step_record_h
#define dynamic_contact_step_record_h

#include <dynamic_contact/bulk/error_norms.h>
#include <dynamic_contact/output/output.h>
#include <dynamic_contact/time/energy_balance.h>
#include <dynamic_contact/time/force_balance.h>
#include <dynamic_contact/time/step_solver.h>

#include <cmath>
#include <string>

namespace DynamicContact
{
  /** Columns name_x, name_y (, name_z) of a vector. */
  template <int dim>
  void
  add_vector_columns(TimeSeriesRow        &row,
                     const std::string    &name,
                     const Tensor<1, dim> &v)
  {
    const char *axes[] = {"_x", "_y", "_z"};
    for (unsigned int d = 0; d < dim; ++d)
      row.add(name + axes[d], v[d]);
  }

  /**
   * Everything a row of time_series.csv says about a step (doc/output.md),
   * as typed values: it travels from the step (Simulator::do_time_step,
   * StepIntegrator::step) to the time loop, the progress line, the end summary,
   * the tests, and the CSV writer, the only place where it becomes text
   * (row()).
   */
  template <int dim>
  struct StepRecord
  {
    unsigned int                         step             = 0;
    double                               time             = 0;
    double                               time_step        = 0;
    double                               normal_force     = 0;
    double                               tangential_force = 0;
    ForceBalance<dim>                    forces;
    EnergyBalanceTerms                   terms;
    double                               previous_energy = 0;
    typename StepSolver<dim>::Statistics statistics;
    double                               remesh_energy_change = 0;
    unsigned int                         cutbacks             = 0;
    unsigned long long                   dofs                 = 0;
    unsigned long long                   cells                = 0;
    bool                                 has_errors           = false;
    Errors                               errors;
    /**
     * The uniqueness measures are columns (a slip-rate dependent law,
     * Friction/Uniqueness monitor not never).
     */
    bool uniqueness_monitor = false;
    /** The solution count is a column (Friction/Count solutions). */
    bool solution_count = false;
    /** Time/Adaptive: the step's error estimate and its rejected tries. */
    bool         adaptive_time = false;
    double       time_error    = 0;
    unsigned int rejected      = 0;

    /** |E_n - E_{n-1} + D_n - W_n| relative to the energy scale. */
    double
    relative_energy_defect() const
    {
      return std::abs(terms.defect) / terms.scale(previous_energy);
    }

    /** The smallest dissipation term relative to the energy scale. */
    double
    relative_min_dissipation() const
    {
      return terms.min_dissipation_term() / terms.scale(previous_energy);
    }

    /** The row of time_series.csv, columns in their order. */
    TimeSeriesRow
    row() const
    {
      TimeSeriesRow r;
      r.add_integer("step", step);
      r.add("time", time);
      r.add("time_step", time_step);
      r.add_integer("cutbacks", cutbacks);
      r.add("normal_force", normal_force);
      r.add("tangential_force", tangential_force);
      add_vector_columns(r, "applied_force", forces.applied);
      add_vector_columns(r, "reaction_force", forces.reaction);
      add_vector_columns(r, "inertia_force", forces.inertia);
      r.add("kinetic_energy", terms.energy.kinetic);
      r.add("elastic_energy", terms.energy.elastic);
      r.add("foundation_energy", terms.energy.foundation);
      r.add("total_energy", terms.energy.total());
      r.add("load_work", terms.load_work);
      r.add("dissipation", terms.dissipation());
      r.add("dissipation_inertia", terms.inertia);
      r.add("dissipation_elastic", terms.elastic);
      r.add("dissipation_viscous", terms.viscous);
      r.add("dissipation_compliance", terms.compliance);
      r.add("dissipation_damping", terms.damping);
      r.add("friction_dissipation", terms.friction);
      r.add("energy_balance_defect", terms.defect);
      r.add("relative_energy_defect", relative_energy_defect());
      r.add("relative_min_dissipation", relative_min_dissipation());
      r.add("remesh_energy_change", remesh_energy_change);
      r.add_integer("newton_iterations", statistics.newton_iterations);
      r.add_integer("convexification_iterations",
                    statistics.convexification_iterations);
      r.add_integer("convexification_converged",
                    statistics.convexification_converged ? 1 : 0);
      r.add("coefficient_residual", statistics.coefficient_residual);
      r.add_integer("coupled_fallbacks", statistics.coupled_fallbacks);
      if (uniqueness_monitor)
        {
          // doc/theory.md section 5.2; -1 where not evaluated.
          r.add("uniqueness_bound", statistics.uniqueness_bound);
          r.add("uniqueness_certificate", statistics.uniqueness_certificate);
          r.add("contraction_factor", statistics.contraction_factor);
        }
      if (solution_count)
        {
          // doc/theory.md section 5.3.
          r.add_integer("solutions", statistics.solutions);
          r.add("solution_spread", statistics.solution_spread);
          r.add_integer("failed_starts", statistics.failed_starts);
        }
      r.add_integer("factorizations", statistics.factorizations);
      r.add_integer("active_set_cycles", statistics.cycles);
      r.add_integer("line_search_steps", statistics.line_search_steps);
      r.add_integer("linear_iterations", statistics.linear_iterations);
      r.add_integer("n_contact", statistics.n_contact);
      r.add_integer("n_stick", statistics.n_stick);
      r.add_integer("n_slip", statistics.n_slip);
      r.add_integer("dofs", dofs);
      r.add_integer("cells", cells);
      if (adaptive_time)
        {
          r.add("time_error_estimate", time_error);
          r.add_integer("rejected_steps", rejected);
        }
      if (has_errors)
        {
          // doc/theory.md section 7; Theorem 6's error is the maximum over the
          // steps of error_theorem6.
          r.add("error_strain", errors.strain);
          r.add("error_velocity", errors.velocity);
          r.add("error_theorem6", errors.strain + errors.velocity);
          r.add("error_energy", errors.energy);
        }
      return r;
    }
  };
} // namespace DynamicContact

#endif
