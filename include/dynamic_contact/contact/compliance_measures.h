#ifndef dynamic_contact_compliance_measures_h
#define dynamic_contact_compliance_measures_h

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/contact/contact_solver.h>
#include <dynamic_contact/contact/largest_eigenvalue.h>

#include <vector>

namespace DynamicContact
{
  template <int dim>
  class BoundaryCompliance;

  /**
   * What BoundaryCompliance measures from the compliance of K0 on Gamma_3
   * (BoundaryCompliance::apply_k0(), on rank 0 inside on_leader()): the
   * coupled linearization's weakening limits of every node, kept for the K0
   * they were measured with, and the largest eigenvalue of R C R^T that the
   * uniqueness measure asks for. A part of the BoundaryCompliance it is
   * made with, which it reads (a friend).
   */
  template <int dim>
  class ComplianceMeasures
  {
  public:
    using Result = ContactSolveResult;

    explicit ComplianceMeasures(BoundaryCompliance<dim> &compliance);

    /** Forget the limits (after GatheredBoundary::reinit()). */
    void
    reinit();

    /** BoundaryCompliance::weakening_limits() (collective). */
    const std::vector<double> &
    weakening_limits(Result &result);

    /** BoundaryCompliance::radius() (collective). */
    SpectralEstimate
    radius(const std::vector<Tensor<2, dim>> &roots, const bool certify);

  private:
    BoundaryCompliance<dim> &compliance;

    /** weakening_limits() for the K0 they were measured with. */
    std::vector<double> limits;
    TimeScheme          limits_scheme;
  };
} // namespace DynamicContact

#endif
