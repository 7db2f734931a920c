#ifndef dynamic_contact_assembled_stiffness_h
#define dynamic_contact_assembled_stiffness_h

#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/contact/contact_solver.h>

#include <memory>
#include <vector>

namespace DynamicContact
{
  /**
   * K0 as the assembled solver (AssembledSolver) uses it, each part kept
   * for the K0 (mesh and time scheme) it was made for: the multigrid of K0
   * (BulkAMG, or the geometric one of Solver/Preconditioner), the
   * preconditioner of the iterative Newton solve and of the solves with K0
   * here; K0's blocks at the owned contact nodes; solves with K0 by CG; and
   * what those solves give: the coupled linearization's weakening limits
   * (WeakeningLimit) and the compliance radius (Lanczos).
   */
  template <int dim>
  class AssembledStiffness
  {
  public:
    /** On @p problem (which must outlive this). */
    explicit AssembledStiffness(const ContactProblem<dim> &problem)
      : problem(problem)
    {}

    /** For a new mesh: nothing kept. */
    void
    reinit();

    /** BulkOperator::newton_blocks() at the nodes, unless K0 is unchanged. */
    const std::vector<Tensor<2, dim>> &
    nodal_blocks();

    /** The multigrid of the current K0, built unless it is. */
    const BulkPreconditioner &
    preconditioner();

    /**
     * x = K0^{-1} b by CG with the AMG of K0, to @p tolerance relative to
     * |b| (constrained entries zero).
     */
    void
    solve(const Vector_t &b, Vector_t &x, const double tolerance);

    /**
     * The coupled linearization's limits of the owned nodes
     * (WeakeningLimit), measured if K0 changed (collective).
     */
    const std::vector<double> &
    weakening_limits();

    /**
     * By solves with K0 (CG, preconditioned with the AMG of K0); no upper
     * bound (the entries of C are not at hand).
     */
    SpectralEstimate
    compliance_radius(const std::vector<Tensor<2, dim>> &roots);

    /** The multigrid, if built. */
    void
    memory_consumption(MemoryItems &items) const;

  private:
    const ContactProblem<dim> &problem;

    /** Build the AMG of the current K0 unless it is built. */
    void
    prepare_preconditioner();

    // The multigrid of K0 (algebraic or geometric), for the time step it was
    // built for.
    std::unique_ptr<BulkPreconditioner> multigrid;
    TimeScheme                          multigrid_scheme;
    /** K0's blocks at the owned nodes, for the K0 they were taken from. */
    std::vector<Tensor<2, dim>> bulk_blocks;
    TimeScheme                  blocks_scheme;
    /** The weakening limits, for the K0 they were measured with. */
    std::vector<double> limits;
    TimeScheme          limits_scheme;
  };
} // namespace DynamicContact

#endif
