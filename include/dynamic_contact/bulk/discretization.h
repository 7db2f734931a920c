#ifndef dynamic_contact_discretization_h
#define dynamic_contact_discretization_h

#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/affine_constraints.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/parameters/parameters.h>

#include <memory>
#include <vector>

class Epetra_Import;

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The discrete space: distributed mesh, Q_p^dim elements for the
   * displacement and velocity, a scalar Q_p space on the same mesh for nodal
   * output fields, the owned and relevant index sets, and the constraints
   * that do not change within a mesh: hanging nodes, then clamped and roller
   * conditions on top (all homogeneous).
   *
   * Convention for all solution vectors: they are stored in "master form",
   * with every constrained entry zero; the matrices are condensed with the
   * same constraints, so that x^T M x is the exact discrete norm.
   * expand() fills in the constrained entries for anything that evaluates
   * the finite element function (output, transfer between meshes).
   */
  template <int dim>
  class Discretization
  {
  public:
    Discretization(const MPI_Comm comm, const unsigned int degree);

    /** Distribute DoFs and build the constraints for the current mesh. */
    void
    setup_dofs(const Parameters::BoundaryConditions &boundary_conditions);

    /**
     * Add the clamped and roller conditions of the last setup_dofs() for
     * a DoF handler of the same element on this mesh or on a coarser one
     * (the levels of the geometric multigrid) to @p constraints (not
     * closed).
     */
    void
    add_boundary_constraints(const DoFHandler<dim>     &dof_handler,
                             AffineConstraints<double> &constraints) const;

    /**
     * What the mesh (with p4est's forest), the DoF handlers with their
     * index sets, and the constraints hold on this process (deal.II's
     * memory_consumption()).
     */
    void
    memory_consumption(MemoryItems &items) const;

    /** The minimal cell diameter over all processes. */
    double
    minimal_cell_diameter() const;

    /**
     * A vector of locally owned entries, zero. Every such vector of a mesh
     * shares one Epetra map (and communicator object) with all others, so
     * that assigning one to another is a copy: vectors with maps of their
     * own are exchanged through an Epetra_Import built anew at each
     * assignment.
     */
    void
    reinit_owned(Vector_t &v) const
    {
      Vector_t fresh(owned_prototype);
      v.swap(fresh);
    }

    /** A ghosted vector (owned and locally relevant entries), zero. */
    void
    reinit_ghosted(Vector_t &v) const
    {
      Vector_t fresh(ghosted_prototype);
      v.swap(fresh);
    }

    /**
     * From a vector in master form, a ghosted vector with the constrained
     * entries filled in (hanging nodes interpolated). Collective. The
     * exchange pattern of the owned and relevant entries is built once per
     * mesh, and the constraints are applied only where some of them is not
     * a plain zero (hanging nodes, roller conditions): the entries of a
     * clamped DoF are zero in master form already.
     */
    void
    expand(const Vector_t &master_form, Vector_t &ghosted) const;

    /**
     * @p function interpolated into @p vector (owned entries) in master
     * form: the constrained entries set to zero.
     */
    void
    interpolate(const Function<dim> &function, Vector_t &vector) const;

    /** The same, into a new ghosted vector. */
    Vector_t
    expanded(const Vector_t &master_form) const
    {
      Vector_t ghosted;
      reinit_ghosted(ghosted);
      expand(master_form, ghosted);
      return ghosted;
    }

    /**
     * FEValues of the vector element fe with the mapping, at @p quadrature
     * (which it copies) with @p flags.
     */
    FEValues<dim>
    cell_values(const Quadrature<dim> &quadrature,
                const UpdateFlags      flags) const
    {
      return FEValues<dim>(mapping, fe, quadrature, flags);
    }

    MPI_Comm                                  comm;
    parallel::distributed::Triangulation<dim> triangulation;
    FESystem<dim>                             fe;
    FE_Q<dim>                                 scalar_fe;
    DoFHandler<dim>                           dof_handler;
    DoFHandler<dim>                           scalar_dof_handler;
    MappingQ1<dim>                            mapping;

    IndexSet locally_owned;
    IndexSet locally_relevant;
    IndexSet scalar_locally_owned;
    IndexSet scalar_locally_relevant;

    /** Hanging-node constraints only. */
    AffineConstraints<double> hanging_node_constraints;
    /** Hanging nodes, clamped and roller conditions. */
    AffineConstraints<double> constraints;

  private:
    /** The clamped and roller boundaries of the last setup_dofs(). */
    Parameters::BoundaryConditions boundary_conditions;
    /**
     * Whether some constraint on some process is more than "this entry is
     * zero" (set by setup_dofs()).
     */
    bool constraints_need_distribute = true;
    /** Zero vectors whose maps the others share (see reinit_owned()). */
    Vector_t owned_prototype, ghosted_prototype;
    /** Owned to relevant entries, built by the first expand() of a mesh. */
    mutable std::shared_ptr<Epetra_Import> owned_to_relevant;
  };


  /**
   * Carries vectors in master form across a change of the mesh of a
   * Discretization, by refinement and coarsening or through a checkpoint
   * (p4est serialization): prepare() expands the fields (hanging nodes
   * filled in) and hands them to parallel::distributed::SolutionTransfer;
   * after the new mesh's setup_dofs, finish() resizes the fields to it,
   * interpolates (or deserializes) and brings them back to master form.
   */
  template <int dim, typename VectorType>
  class FieldTransfer
  {
  public:
    FieldTransfer(const Discretization<dim>       &discretization,
                  const std::vector<VectorType *> &fields)
      : discretization(discretization)
      , fields(fields)
      , transfer(discretization.dof_handler)
    {}

    /** Before refinement, or (@p serialization) before Triangulation::save. */
    void
    prepare(const bool serialization = false)
    {
      std::vector<const VectorType *> input;
      ghosted.clear();
      ghosted.reserve(fields.size());
      for (const VectorType *field : fields)
        {
          ghosted.push_back(discretization.expanded(*field));
          input.push_back(&ghosted.back());
        }
      if (serialization)
        transfer.prepare_for_serialization(input);
      else
        transfer.prepare_for_coarsening_and_refinement(input);
    }

    /**
     * After refinement, or (@p serialization) after Triangulation::load,
     * and after the DoFs and constraints of the new mesh are set up.
     */
    void
    finish(const bool serialization = false)
    {
      for (VectorType *field : fields)
        discretization.reinit_owned(*field);
      std::vector<VectorType *> output(fields);
      if (serialization)
        transfer.deserialize(output);
      else
        transfer.interpolate(output);
      for (VectorType *field : fields)
        discretization.constraints.set_zero(*field);
    }

  private:
    const Discretization<dim>                               &discretization;
    const std::vector<VectorType *>                          fields;
    std::vector<VectorType>                                  ghosted;
    parallel::distributed::SolutionTransfer<dim, VectorType> transfer;
  };
} // namespace DynamicContact

#endif
