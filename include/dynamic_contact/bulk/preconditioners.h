#ifndef dynamic_contact_preconditioners_h
#define dynamic_contact_preconditioners_h

#include <deal.II/matrix_free/matrix_free.h>

#include <dynamic_contact/base/preconditioner_plugin.h>
#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/bulk/bulk_multigrid.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/parameters/parameters.h>

#include <memory>
#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * What a preconditioner of K0 is made from (PreconditionerPlugin::
   * create()): the mesh and K0 where it is stored; for a geometric
   * multigrid also the material and the time scheme K0 is formed with, and
   * the cell data of the mesh's bulk forms where they are set up.
   */
  template <int dim>
  struct PreconditionerInput
  {
    const Discretization<dim> &discretization;
    /** K0; nullptr where it is not stored (applied cell by cell). */
    const Matrix_t                 *matrix   = nullptr;
    const KelvinVoigtMaterial<dim> *material = nullptr;
    const TimeScheme               *scheme   = nullptr;
    /** BulkOperator::cell_data(), if set up. */
    const MatrixFree<dim, double> *cell_data = nullptr;
  };

  /**
   * The name of the algebraic multigrid among the preconditioners: the one
   * of the condensed solver's iterative solves with K0, of 'auto' outside
   * the assembled iterative solver, and where another cannot serve.
   */
  inline const std::string algebraic_multigrid = "AMG";

  /**
   * The preconditioners Preconditioner = auto tries with elements of
   * degree @p degree: those of @p parameters with an auto rank
   * (PreconditionerPlugin::auto_rank(), fastest first) made for that
   * degree.
   */
  std::vector<std::string>
  auto_preconditioners(const Parameters::Solver &parameters,
                       const unsigned int        degree);

  /**
   * The preconditioner Solver/Preconditioner = @p name (a registered one,
   * not auto) with the entries of @p parameters for @p input; the AMG
   * where that one cannot serve on this mesh (PreconditionerPlugin::
   * create()).
   */
  template <int dim>
  std::unique_ptr<BulkPreconditioner>
  create_preconditioner(const Parameters::Solver       &parameters,
                        const std::string              &name,
                        const PreconditionerInput<dim> &input);
} // namespace DynamicContact

#endif
