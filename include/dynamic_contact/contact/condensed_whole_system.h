#ifndef dynamic_contact_condensed_whole_system_h
#define dynamic_contact_condensed_whole_system_h

#include <dynamic_contact/contact/boundary_compliance.h>
#include <dynamic_contact/contact/condensed_boundary_newton.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/reduced_system.h>
#include <dynamic_contact/contact/whole_system_newton.h>

#include <optional>
#include <utility>
#include <vector>

namespace DynamicContact
{
  /**
   * The condensed solver's work on the whole body (CondensedSolver): the
   * free response w_free = K0'^{-1} b, kept for the passes of a step
   * (which share b), and phase 2: from the phase-1 iterate, w = K0'^{-1}
   * (b - sum P^T g), then the whole-system Newton iteration, whose Newton
   * steps it solves by the same condensation (the LinearBackend role: a
   * solve with K0', a dense solve and a solve with K0' or a sum of stored
   * columns each). It owns the vectors of the size of the mesh.
   */
  template <int dim>
  class CondensedWholeSystem : public LinearBackend<dim>
  {
  public:
    using Result  = ContactSolveResult;
    using Iterate = BoundaryIterate<dim>;
    /**
     * The nodal forces g (every node) and the nodes with a force of a
     * provisional pass.
     */
    using PassForces =
      std::pair<std::vector<Tensor<1, dim>>, std::vector<unsigned int>>;

    /**
     * On the parts of the condensed solver (which must outlive this); the
     * free response at the nodes goes into @p data.
     */
    CondensedWholeSystem(const ContactProblem<dim>          &problem,
                         const GatheredBoundary<dim>        &gathered,
                         BoundaryCompliance<dim>            &compliance,
                         ReducedSystem<dim>                 &reduced,
                         const CondensedBoundaryNewton<dim> &boundary_newton,
                         BoundaryStepData<dim>              &data)
      : problem(problem)
      , gathered(gathered)
      , compliance(compliance)
      , reduced(reduced)
      , boundary_newton(boundary_newton)
      , data(data)
    {}

    /** For a new mesh: the vectors, and no free response. */
    void
    reinit();

    /** The free response is out of date (K0' changed). */
    void
    invalidate_free_response()
    {
      free_response_valid = false;
    }

    /**
     * w_free = K0'^{-1} b, unless b is the last one (the passes of a step
     * share it); true if it was (collective).
     */
    bool
    update_free_response(const Vector_t &rhs, Result &result);

    /** w_free = K0'^{-1} b for the last b. */
    const Vector_t &
    free_velocity() const
    {
      return free_response;
    }

    /** The last b. */
    const Vector_t &
    last_rhs() const
    {
      return cached_rhs;
    }

    /**
     * From the phase-1 iterate @p it: w = K0'^{-1}(b - sum P^T g), then
     * phase 2 (the whole-system Newton iteration) on @p step (its b the
     * last one), to Solver/Newton tolerance (no step where the start
     * already meets it). With @p previous, also the velocity of the
     * earlier provisional pass @p previous_pass.
     */
    void
    polish(const Iterate                   &it,
           const ContactStep<dim>          &step,
           const std::optional<PassForces> &previous_pass,
           std::vector<Tensor<1, dim>>     &lambda,
           Vector_t                        &w,
           Result                          &result,
           Vector_t                        *previous = nullptr);

    /** The whole-system Newton step by condensation (phase 2). */
    void
    newton_step(const WholeSystemNewton<dim>  &system,
                const WholeSystemIterate<dim> &x,
                WholeSystemIterate<dim>       &full,
                Result                        &result) override;

  private:
    const ContactProblem<dim>          &problem;
    const GatheredBoundary<dim>        &gathered;
    BoundaryCompliance<dim>            &compliance;
    ReducedSystem<dim>                 &reduced;
    const CondensedBoundaryNewton<dim> &boundary_newton;
    BoundaryStepData<dim>              &data;

    Vector_t solution, right_hand_side, residual, increment, scratch;

    /** K0'^{-1} b for the last b (the passes of a step share it). */
    Vector_t free_response, cached_rhs;
    bool     free_response_valid = false;

    /** v += factor sum_i P_i^T f_i over the owned nodes (f at every node). */
    void
    add_nodal_forces(const std::vector<Tensor<1, dim>> &f,
                     const double                       factor,
                     Vector_t                          &v) const;
  };
} // namespace DynamicContact

#endif
