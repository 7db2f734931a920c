#ifndef dynamic_contact_error_norms_h
#define dynamic_contact_error_norms_h

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/bulk/scene.h>

namespace DynamicContact
{
  /**
   * The errors of doc/theory.md section 7 at one time, against the scene's
   * exact solution (u, u'):
   *   strain   = ||eps(u_h - u)||_L2          (the norm of V, eq. (23)),
   *   velocity = ||w_h - u'||_L2              (the norm of H),
   *   energy   = (rho ||w_h - u'||^2 + a_E(u_h - u, u_h - u))^(1/2).
   * The Theorem 6 error is max_n (strain + velocity).
   */
  struct Errors
  {
    double strain   = 0;
    double velocity = 0;
    double energy   = 0;
  };

  /**
   * @p u, @p w ghosted, with the constrained entries filled in. The exact
   * gradients come from the parsed expressions by finite differences.
   */
  template <int dim>
  Errors
  compute_errors(const Discretization<dim>      &discretization,
                 const KelvinVoigtMaterial<dim> &material,
                 const Scene<dim>               &scene,
                 const double                    t,
                 const Vector_t                 &u,
                 const Vector_t                 &w);
} // namespace DynamicContact

#endif
