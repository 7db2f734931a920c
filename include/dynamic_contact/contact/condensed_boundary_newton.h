#ifndef dynamic_contact_condensed_boundary_newton_h
#define dynamic_contact_condensed_boundary_newton_h

#include <dynamic_contact/contact/boundary_compliance.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/reduced_system.h>

#include <vector>

namespace DynamicContact
{
  /**
   * The data of the condensed solver's current solve at every node of
   * Gamma_3 (GatheredBoundary's order): what the linearization of a node
   * needs beside the iterate.
   */
  template <int dim>
  struct BoundaryStepData
  {
    /** The step's (k, theta). */
    TimeScheme scheme;
    /** u_{n-1} and w_{n-1}. */
    std::vector<Tensor<1, dim>> u_old, w_old;
    /** The friction coefficients. */
    FrictionCoefficients mu;
    /** w_free = K0'^{-1} b for the last b. */
    std::vector<Tensor<1, dim>> w_free;
    /**
     * resolvable_force() of the last b: the floor of the force scale of
     * the law residual on Gamma_3 (WholeSystemNewton::force_scale).
     */
    double force_scale = 0;
  };


  /** The nodal values of @p v at every node of @p gathered (collective). */
  template <int dim>
  inline std::vector<Tensor<1, dim>>
  gather_nodal_values(const GatheredBoundary<dim> &gathered,
                      const ContactBoundary<dim>  &boundary,
                      const Vector_t              &v)
  {
    return gathered.gather(boundary.values(v));
  }


  /**
   * Phase 1 of the condensed solver (CondensedSolver): a
   * globalized_newton() iteration on Gamma_3 alone, w_Gamma = w_free - C g
   * (no solve with K0' but for new columns of C), on rank 0, which holds
   * C; it finds the active sets. It also linearizes every node at an
   * iterate, which phase 2 (CondensedWholeSystem) uses too. It reads the
   * current solve's data (BoundaryStepData) that the solver keeps.
   */
  template <int dim>
  class CondensedBoundaryNewton
  {
  public:
    using Result  = ContactSolveResult;
    using Iterate = BoundaryIterate<dim>;

    /** On the parts of the condensed solver (which must outlive this). */
    CondensedBoundaryNewton(const ContactProblem<dim>   &problem,
                            const GatheredBoundary<dim> &gathered,
                            BoundaryCompliance<dim>     &compliance,
                            ReducedSystem<dim>          &reduced,
                            const BoundaryStepData<dim> &data)
      : problem(problem)
      , gathered(gathered)
      , compliance(compliance)
      , reduced(reduced)
      , data(data)
    {}

    /** Linearize every node at it.w, it.lambda (the current solve's data). */
    void
    linearize(Iterate &it) const;

    /**
     * Phase 1 on the current solve's data from @p it, to the relative
     * residual max(Newton tolerance, @p tolerance); @p w_scale is the
     * velocity its equilibrium residual is relative to.
     */
    void
    solve(Iterate     &it,
          const double w_scale,
          const double tolerance,
          Result      &result);

  private:
    /** Phase 1 as globalized_newton() sees it (defined in the .cc). */
    class BoundaryProblem;

    const ContactProblem<dim>   &problem;
    const GatheredBoundary<dim> &gathered;
    BoundaryCompliance<dim>     &compliance;
    ReducedSystem<dim>          &reduced;
    const BoundaryStepData<dim> &data;
  };
} // namespace DynamicContact

#endif
