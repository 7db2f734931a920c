#ifndef dynamic_contact_field_io_h
#define dynamic_contact_field_io_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_state.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/output/output.h>
#include <dynamic_contact/output/output_directory.h>
#include <dynamic_contact/parameters/parameters.h>

#include <functional>
#include <string>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The fields of a run as they are written and read: the contact CSV and
   * the VTU files of a step, a checkpoint of the mesh and the fields (and
   * loading one), and the displacement at a point. The fields are the
   * Simulator's (u and w in master form, the solution on Gamma_3); this
   * class holds references to them and owns nothing.
   */
  template <int dim>
  class FieldIO
  {
  public:
    /** @p friction: whether the scene has friction (the CSV's columns). */
    FieldIO(const RunParameters            &parameters,
            Discretization<dim>            &discretization,
            const KelvinVoigtMaterial<dim> &material,
            const ContactBoundary<dim>     &contact_boundary,
            ContactState<dim>              &contact_state,
            Vector_t                       &u,
            Vector_t                       &w,
            const bool                      friction,
            const MPI_Comm                  comm)
      : parameters(parameters)
      , discretization(discretization)
      , material(material)
      , contact_boundary(contact_boundary)
      , contact_state(contact_state)
      , u(u)
      , w(w)
      , friction(friction)
      , comm(comm)
    {}

    /**
     * Write a checkpoint of the mesh and the fields with the loop's
     * @p state (write_checkpoint in checkpoint.h): the friction forces
     * exactly, as nodal forces saved with the mesh (any number of processes
     * can load them), and with a slip length the coefficient states.
     */
    void
    save_checkpoint(OutputDirectory             &directory,
                    const RunState              &state,
                    const std::string           &parameters_of_run,
                    const unsigned int           keep,
                    const std::function<void()> &before_commit);

    /**
     * Load the mesh and the fields of the checkpoint @p path:
     * @p setup_dofs sets up what depends on the new DoFs before the fields
     * are filled in, @p setup_operators what depends on the mesh before the
     * friction forces go back onto Gamma_3.
     */
    void
    load_checkpoint(const std::string           &path,
                    const std::function<void()> &setup_dofs,
                    const std::function<void()> &setup_operators);

    /** contact_NNNNN.csv of step @p step at time @p t. */
    void
    write_contact_csv(OutputDirectory   &directory,
                      const unsigned int step,
                      const double       t) const;

    /** The VTU files of step @p step at time @p t. */
    void
    write_vtu(VtuWriter<dim>    &writer,
              const unsigned int step,
              const double       t) const;

    /**
     * The displacement at a point of the body (collective). Throws if the
     * point is outside the body.
     */
    Tensor<1, dim>
    point_displacement(const Point<dim> &point) const;

  private:
    const RunParameters            &parameters;
    Discretization<dim>            &discretization;
    const KelvinVoigtMaterial<dim> &material;
    const ContactBoundary<dim>     &contact_boundary;
    ContactState<dim>              &contact_state;
    Vector_t                       &u, &w;
    const bool                      friction;
    MPI_Comm                        comm;
  };
} // namespace DynamicContact

#endif
