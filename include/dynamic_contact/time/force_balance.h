#ifndef dynamic_contact_force_balance_h
#define dynamic_contact_force_balance_h

#include <deal.II/base/tensor.h>

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/face_load_quadrature.h>
#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/laws/contact_law.h>
#include <dynamic_contact/laws/material.h>

namespace DynamicContact
{
  /**
   * The total forces on the body at step n (per unit depth in 2D), each as
   * the force the body feels:
   *   applied  = int_Omega f_0 + int_Gamma_2 f_2 (+ int_Gamma_3 s, the source
   *              of manufactured solutions), at the scheme's time,
   *   contact  = -sum_i (N_i nu_i + lambda_i)   (from the foundation),
   *   reaction = from the clamped and roller boundaries,
   *   inertia  = int_Omega rho (w_n - w_{n-1})/k,
   * with applied + contact + reaction = inertia (Newton's second law for
   * the whole body, which the discrete equations satisfy exactly).
   */
  template <int dim>
  struct ForceBalance
  {
    Tensor<1, dim> applied;
    Tensor<1, dim> contact;
    Tensor<1, dim> reaction;
    Tensor<1, dim> inertia;
  };

  /**
   * Computes the ForceBalance of a step at the cost of a few boundary cells:
   * the inertia from the weights int_Omega phi_i (once per mesh), the
   * reaction from the cells that touch a supported DoF, the applied force
   * from the traction faces (and all cells only if there is a body force).
   */
  template <int dim>
  class ForceBalanceEvaluator
  {
  public:
    ForceBalanceEvaluator(const Discretization<dim>      &discretization,
                          const KelvinVoigtMaterial<dim> &material,
                          const Scene<dim>               &scene)
      : discretization(discretization)
      , material(material)
      , scene(scene)
      , face_quadrature(discretization)
    {}

    /** After a change of the mesh. */
    void
    reinit();

    /**
     * For the step from t - k to t of the theta-scheme: the stress at
     * @p u_theta, @p w_theta (theta-averages of the two ends), the loads
     * theta f(t) + (1 - theta) f(t - k), the inertia from @p w and @p w_old.
     * All ghosted, with the constrained entries filled in
     * (Discretization::expand).
     */
    ForceBalance<dim>
    compute(const ContactBoundary<dim>               &boundary,
            const std::vector<ContactNodeState<dim>> &states,
            const double                              t,
            const TimeScheme                         &scheme,
            const Vector_t                           &u_theta,
            const Vector_t                           &w_theta,
            const Vector_t                           &w,
            const Vector_t                           &w_old) const;

  private:
    /**
     * Into @p b: the applied forces (body force and surface loads of the
     * scheme's equation at t) and the reactions of the supports from the
     * cells (the weak form's residual at supported DoFs).
     */
    void
    body_forces(const double       t,
                const TimeScheme  &scheme,
                const Vector_t    &u,
                const Vector_t    &w_theta,
                const Vector_t    &w,
                const Vector_t    &w_old,
                ForceBalance<dim> &b) const;

    /** face_values = the step's surface load on each loaded face. */
    void
    integrate_face_loads(const double t, const TimeScheme &scheme) const;

    const Discretization<dim>      &discretization;
    const KelvinVoigtMaterial<dim> &material;
    const Scene<dim>               &scene;
    /** int_Omega phi_i for every owned DoF i. */
    Vector_t volume_weights;
    /** Component of every owned DoF. */
    std::vector<unsigned char> component;
    /**
     * Index of every owned DoF among the local entries of a ghosted vector
     * (Discretization::reinit_ghosted): the inertia sum reads the entries
     * directly instead of looking each global index up.
     */
    std::vector<int> ghosted_index;
    /**
     * The locally owned cells that body_forces() visits (once per mesh):
     * those with a supported DoF (their residual is a reaction) or a load.
     */
    struct CellWork
    {
      typename DoFHandler<dim>::active_cell_iterator cell;
      bool                                           has_support;
    };
    std::vector<CellWork> cells;
    /** Their loaded faces, and the index of each face's cell in cells. */
    std::vector<typename FaceLoadQuadrature<dim>::Face> faces;
    std::vector<unsigned int>                           face_cell;
    FaceLoadQuadrature<dim>                             face_quadrature;
    mutable std::vector<Vector<double>> face_values, old_face_values;
  };
} // namespace DynamicContact

#endif
