#ifndef dynamic_contact_model_checks_h
#define dynamic_contact_model_checks_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <dynamic_contact/bulk/scene.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/parameters/parameters.h>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * @name The model, checked before anything is written and described in
   * the run's header
   */
  /** @{ */

  /**
   * The friction law of Friction (if any) on the slip rates [0, Friction/
   * Maximum slip rate]: finite, >= 0, and not increasing unless Friction/
   * Velocity strengthening = allow. A violation is a CollectiveError that
   * names the law's subsection.
   */
  void
  check_friction_law(const RunParameters &parameters);

  /**
   * The functions of @p scene sampled where and when the run uses them (on
   * the mesh @p triangulation; the loads at 0, the first step, T and 16
   * times between; the initial conditions with @p initial_conditions): a
   * NaN or infinity is a CollectiveError that names the function.
   */
  template <int dim>
  void
  check_scene_functions(const RunParameters      &parameters,
                        const Scene<dim>         &scene,
                        const Triangulation<dim> &triangulation,
                        const MPI_Comm            comm,
                        const bool                initial_conditions);

  /**
   * The material and friction lines of the header, and the well-posedness
   * report (well_posedness_report()); @p has_friction as the step solver
   * sees it (a friction law that is not zero).
   */
  template <int dim>
  void
  print_model(const ConditionalOStream       &out,
              const RunParameters            &parameters,
              const KelvinVoigtMaterial<dim> &material,
              const bool                      has_friction);
  /** @} */
} // namespace DynamicContact

#endif
