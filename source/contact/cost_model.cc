#include <dynamic_contact/bulk/preconditioners.h>
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
     * processes share the memory bandwidth. Fitted to the boundary
     * Newton's time on 4, 8 and 16 processes of a 16-core machine, the rail
     * 80 x 8 x 8 with every process taking part, both while every process
     * repeated it and while rank 0 alone iterated and the others polled
     * without pause: benchmarks/results/every_process_16cores.txt. The
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


  std::vector<std::string>
  preconditioner_candidates(const Parameters::Solver &parameters,
                            const unsigned int        degree)
  {
    if (parameters.preconditioner != "auto")
      return {parameters.preconditioner};
    return auto_preconditioners(parameters, degree);
  }


  namespace
  {
    /**
     * The memory model's coefficients, fitted to benchmarks/memory on one
     * process with Q1 elements: benchmarks/results/memory.csv (the 3D rail,
     * 1 048 707 DoFs) and memory_2d.csv (the 2D paper's scene, 132 098
     * DoFs).
     */
    struct MemoryCoefficients
    {
      /**
       * Bytes per DoF of the mesh, DoF handlers, constraints, the cells'
       * data of the bulk forms, the step's vectors, the GMRES basis and
       * what the memory table does not itemize (MPI's buffers, the heap's
       * slack).
       */
      double rest;
      /**
       * The AMG's hierarchy (ML, smoothed aggregation, rigid-body modes)
       * and what it holds besides while it is built (the peak), per byte
       * of K0 and its pattern.
       */
      double amg;
      /**
       * Bytes per DoF of the geometric multigrid's coarser levels (their
       * cells' data, vectors and Chebyshev diagonals).
       */
      double gmg_levels;
      /**
       * Bytes per DoF of the multigrid's coarsest level where it is
       * factorized (KLU).
       */
      double gmg_coarsest;
    };

    MemoryCoefficients
    memory_coefficients(const unsigned int dim)
    {
      // Quotients of the rows (MB) of the files above, one process (the
      // AMG run, the GMG's rows from the GMG run). 3D, memory.csv:
      // rest = the mesh, DoF handlers, constraints, bulk forms, GMRES
      // basis, the step's vectors and what is not itemized (less its fixed
      // part, in program_bytes), over the DoFs; amg = the AMG of K0 and the
      // peak resident above resident now, over K0 and its pattern;
      // gmg_levels = the GMG of K0 over the DoFs (the finest level on the
      // bulk forms' cell data; the coarsest, 10 x 1 x 1 cells, negligible;
      // its factorization per DoF taken from 2D).
      if (dim == 3)
        return {980e6 / 1048707,
                (943. + 1554.) / 941.,
                142e6 / 1048707,
                61e6 / 33282};
      // 2D, memory_2d.csv: rest as in 3D (a larger GMRES basis per DoF:
      // the paper's cells are 20 times longer than high, so GMRES takes
      // more iterations); amg = the AMG of K0 over K0 and its pattern, its
      // peak no higher; the GMG of K0: its levels as in 3D per DoF, the
      // rest the coarsest level's factorization (33 282 DoFs, KLU).
      return {178e6 / 132098, 48.9 / 28.9, 142e6 / 1048707, 61e6 / 33282};
    }

    /**
     * The program, its libraries and MPI before the mesh (the row
     * "program, libraries, MPI (at start)" of memory.csv), and what the
     * memory table leaves unitemized on a small mesh, per process.
     */
    constexpr double program_bytes = 180e6;
    /**
     * Bytes per stored entry of K0: its value and, in the shared sparsity
     * pattern, its column (the rows "bulk matrix K0" and "sparsity
     * pattern" of memory.csv over the 3D rail's 1 048 707 rows of at most
     * 81 entries).
     */
    constexpr double bytes_per_entry = 11.1;
    /**
     * The DoFs one process shares with its neighbours as ghosts grow its
     * share by 1 + this / (its DoFs)^(1/dim): fitted to the 3D rail on 16
     * processes, 65 544 DoFs each: the largest process's peak in the
     * 16-process rows of memory.csv (tests/cost_model checks the model
     * against every row of peak resident there and in memory_2d.csv).
     */
    constexpr double ghost_share = 15.;
  } // namespace


  double
  predicted_memory(const PreconditionerPlugin           &preconditioner,
                   const unsigned int                    dim,
                   const unsigned int                    degree,
                   const dealii::types::global_dof_index n_dofs,
                   const unsigned int                    n_processes,
                   const double                          coarse_dofs)
  {
    const MemoryCoefficients c = memory_coefficients(dim);
    // A node of an element of degree p couples on average with p + 2
    // nodes in each direction (2p + 1 at the cells' vertices, p + 1
    // within), dim components each.
    PreconditionerMemoryTerms terms;
    terms.dim         = dim;
    terms.n_dofs      = static_cast<double>(n_dofs);
    terms.coarse_dofs = coarse_dofs;
    terms.matrix =
      bytes_per_entry * dim * std::pow(degree + 2., static_cast<double>(dim));
    terms.amg                        = c.amg;
    terms.levels                     = c.gmg_levels;
    terms.factorized_coarsest        = c.gmg_coarsest;
    const PreconditionerMemory share = preconditioner.memory(terms);
    const double               per_process =
      static_cast<double>(n_dofs) / std::max(n_processes, 1u);
    const double per_dof = c.rest + share.per_dof;
    const double fixed   = program_bytes + share.fixed;
    const double ghosts =
      n_processes > 1 && per_process > 0 ?
        1 + ghost_share / std::pow(per_process, 1. / dim) :
        1.;
    return fixed + per_process * per_dof * ghosts;
  }


  std::string
  memory_string(const double bytes)
  {
    std::ostringstream s;
    if (bytes < 1e9)
      s << std::lround(bytes / 1e6) << " MB";
    else
      s << std::setprecision(3) << bytes / 1e9 << " GB";
    return s.str();
  }
} // namespace DynamicContact
