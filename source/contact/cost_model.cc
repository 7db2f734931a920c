#include <dynamic_contact/contact/cost_model.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <sstream>

namespace DynamicContact
{
  double
  CostTerm::time(const double n_dofs, const double contact_size) const
  {
    const double x = of_contact_boundary ? contact_size : n_dofs;
    return x > 0 ? coefficient * std::pow(x, exponent) : 0.;
  }


  namespace
  {
    /**
     * How much longer the condensed solver's work on Gamma_3 takes per
     * doubling of the processes beyond the two of the calibration: the
     * processes share the memory bandwidth. Measured on a 16-core machine,
     * the rail 80 x 8 x 8 with every process taking part: the boundary
     * Newton took 14.1, 19.5 and 24.7 s on 4, 8 and 16 processes while
     * every process repeated it (1.32 per doubling), and 12.1 and 15.3 s on
     * 4 and 8 with rank 0 alone iterating while the others polled without
     * pause (1.26; benchmarks/results/every_process_16cores.txt). The
     * waiting processes now sleep between polls (LeadingProcess), not yet
     * measured there.
     */
    constexpr double replicated_contention = 1.3;


    /** The one-process way of solving that @p solver shares its work with. */
    CostedSolver
    on_one_process(const CostedSolver solver)
    {
      return solver == CostedSolver::assembled ? CostedSolver::assembled :
                                                  CostedSolver::condensed;
    }


    /** The term of @p section for this dimension, way and processes. */
    const CostTerm *
    find_term(const unsigned int dim,
              const CostedSolver solver,
              const unsigned int processes,
              const char        *section)
    {
      for (const auto &term : cost_model_terms)
        if (term.dim == dim && term.solver == solver &&
            term.processes == processes &&
            std::strcmp(term.section, section) == 0)
          return &term;
      return nullptr;
    }
  } // namespace


  SolverCost
  predicted_cost(const CostedSolver                    solver,
                 const unsigned int                    dim,
                 const dealii::types::global_dof_index n_dofs,
                 const unsigned int                    contact_size,
                 const unsigned int                    n_processes)
  {
    SolverCost         cost;
    const unsigned int calibrated_processes = std::min(n_processes, 2u);
    // Doublings beyond the two processes measured.
    const double doublings =
      n_processes > 2 ? std::log2(n_processes / 2.) : 0.;
    const double n = static_cast<double>(n_dofs);
    for (const auto &term : cost_model_terms)
      {
        if (term.dim != dim || term.solver != solver ||
            term.processes != calibrated_processes)
          continue;
        cost.calibrated = true;
        double time     = term.time(n, contact_size);
        if (doublings > 0)
          {
            const CostTerm *one =
              find_term(dim, on_one_process(solver), 1, term.section);
            const double t1    = one ? one->time(n, contact_size) : 0.;
            const double ratio = t1 > 0 ? std::clamp(time / t1, 0.5, 1.) : 1.;
            time *= std::pow(ratio, doublings);
            // The dense work on Gamma_3 that every process repeats.
            if (solver != CostedSolver::assembled && term.of_contact_boundary)
              time *= std::pow(replicated_contention, doublings);
          }
        (term.once_per_matrix ? cost.once : cost.per_step) += time;
      }
    return cost;
  }


  double
  smallest_costed_mesh(const unsigned int dim)
  {
    double smallest = 0;
    for (const auto &range : cost_model_ranges)
      if (range.dim == dim)
        smallest = smallest > 0 ? std::min(smallest, range.smallest) :
                                  range.smallest;
    return smallest;
  }


  double
  largest_costed_mesh(const unsigned int dim, const CostedSolver solver)
  {
    for (const auto &range : cost_model_ranges)
      if (range.dim == dim && range.solver == solver)
        return range.largest;
    return 0.;
  }


  std::string
  cost_string(const double seconds)
  {
    std::ostringstream s;
    if (seconds < 1)
      s << std::lround(seconds * 1000) << " ms";
    else
      s << std::setprecision(3) << seconds << " s";
    return s.str();
  }
} // namespace DynamicContact
