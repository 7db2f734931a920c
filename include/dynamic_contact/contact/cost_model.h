#ifndef dynamic_contact_cost_model_h
#define dynamic_contact_cost_model_h

#include <deal.II/base/types.h>

#include <dynamic_contact/parameters/parameters.h>

#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * The ways of solving a step the cost model knows (the solver plan's
   * choices for Solver/Contact solver = auto).
   */
  enum class CostedSolver
  {
    /** The condensed solver with K0 factorized by CHOLMOD, one process. */
    condensed,
    /** The condensed solver, the whole CHOLMOD factor on every process. */
    condensed_on_every_process,
    /** The condensed solver, K0 factorized by MUMPS over the processes. */
    condensed_distributed,
    /** The assembled solver, GMRES with algebraic multigrid. */
    assembled
  };

  /**
   * One timer section a solver spends its time in, as a power law fitted to
   * the benchmarks (benchmarks/cost-model): time = coefficient *
   * x^exponent, x the bulk DoFs or dim x the contact nodes, paid once per
   * bulk matrix K0 or per step, on 1 or 2 processes.
   */
  struct CostTerm
  {
    unsigned int dim;
    CostedSolver solver;
    unsigned int processes;
    const char  *section;
    bool         once_per_matrix;
    bool         of_contact_boundary;
    double       coefficient;
    double       exponent;

    double
    time(const double n_dofs, const double contact_size) const;
  };

  /** The meshes measured for a way of solving: bulk DoFs, least and most. */
  struct CostRange
  {
    unsigned int dim;
    CostedSolver solver;
    double       smallest;
    double       largest;
  };

  /** The fitted terms (source/contact/cost_model_table.cc, generated). */
  extern const std::vector<CostTerm> cost_model_terms;
  /** The meshes of the fit per way of solving (generated with the terms). */
  extern const std::vector<CostRange> cost_model_ranges;

  /**
   * The predicted cost of a way of solving: seconds paid once per bulk
   * matrix K0 (factorizations, the compliance of Gamma_3, the AMG) and per
   * step, on the machine the model was calibrated on. Not calibrated: no
   * term for this dimension and way.
   */
  struct SolverCost
  {
    bool   calibrated = false;
    double once       = 0;
    double per_step   = 0;

    /** The cost of @p steps steps with one K0. */
    double
    total(const double steps) const
    {
      return once + steps * per_step;
    }
  };

  /**
   * The cost of solving with @p solver a problem of @p n_dofs bulk DoFs and
   * @p contact_size = dim x contact nodes on @p n_processes processes. The
   * model is calibrated on 1 and 2 processes; beyond, every term's ratio
   * from 1 to 2 processes, clamped to [1/2, 1], is taken again at every
   * doubling (work shared at best halves it), and the condensed solver's
   * dense work on Gamma_3, which every process repeats, grows by 1.3 per
   * doubling (the processes share the memory bandwidth: measured on 16
   * cores, benchmarks/results/every_process_16cores.txt).
   */
  SolverCost
  predicted_cost(const CostedSolver                    solver,
                 const unsigned int                    dim,
                 const dealii::types::global_dof_index n_dofs,
                 const unsigned int                    contact_size,
                 const unsigned int                    n_processes);

  /**
   * The fewest bulk DoFs of a mesh the model was fitted on in @p dim
   * dimensions (0 without a fit). Below it the model is not used: fixed
   * costs rule there, and the condensed solver was the faster on the
   * smallest meshes measured.
   */
  double
  smallest_costed_mesh(const unsigned int dim);

  /**
   * The most bulk DoFs of a mesh @p solver was measured on in @p dim
   * dimensions (0 if none).
   */
  double
  largest_costed_mesh(const unsigned int dim, const CostedSolver solver);

  /**
   * The preconditioners Solver/Preconditioner of @p parameters allows with
   * elements of degree @p degree: the one set, or for 'auto' those with an
   * auto rank (PreconditionerPlugin::auto_rank(), fastest first) made for
   * that degree.
   */
  std::vector<std::string>
  preconditioner_candidates(const Parameters::Solver &parameters,
                            const unsigned int        degree);

  /**
   * The peak memory, in bytes, of the largest process of a run of the
   * assembled iterative solver with @p preconditioner on a mesh of
   * @p n_dofs bulk DoFs of elements of degree @p degree on @p n_processes
   * processes (benchmarks/memory at 10^6 DoFs): the program itself, and
   * per DoF the mesh, the vectors and the GMRES basis, and the
   * preconditioner's share (PreconditionerPlugin::memory(): K0 and its
   * sparsity pattern where it is stored, from the entries of a row; the
   * hierarchy, with the AMG's transient peak while it is built; for the
   * geometric multigrid its levels and its coarsest level of
   * @p coarse_dofs DoFs).
   */
  double
  predicted_memory(const PreconditionerPlugin           &preconditioner,
                   const unsigned int                    dim,
                   const unsigned int                    degree,
                   const dealii::types::global_dof_index n_dofs,
                   const unsigned int                    n_processes,
                   const double                          coarse_dofs);

  /** "1.23 GB" or "456 MB": a predicted memory for the log. */
  std::string
  memory_string(const double bytes);

  /** "1.23 s" or "45 ms": a predicted time for the log. */
  std::string
  cost_string(const double seconds);
} // namespace DynamicContact

#endif
