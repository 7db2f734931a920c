#ifndef dynamic_contact_energy_balance_h
#define dynamic_contact_energy_balance_h

#include <dynamic_contact/bulk_operator.h>
#include <dynamic_contact/contact_boundary.h>
#include <dynamic_contact/foundation.h>
#include <dynamic_contact/contact_law.h>
#include <dynamic_contact/time_scheme.h>

namespace DynamicContact
{
  /**
   * The energy E_n = (rho/2)|w_n|^2 + a_E(u_n, u_n)/2 + sum_i m_i Pi(u_nu,i)
   * of doc/theory.md section 6.
   */
  struct Energy
  {
    double kinetic    = 0;
    double elastic    = 0;
    double foundation = 0;

    double
    total() const
    {
      return kinetic + elastic + foundation;
    }
  };

  /**
   * The terms of the discrete balance E_n - E_{n-1} + D_n = W_n of one step,
   * each computed from the fields (never assumed): every dissipation term
   * is >= 0 for a correct, converged step.
   */
  struct EnergyBalanceTerms
  {
    Energy energy;
    // With the theta-scheme (theta = 1: backward Euler, the paper's terms;
    // theta = 1/2 trapezoidal; doc/theory.md section 6), w_e = theta w_n +
    // (1 - theta) w_{n-1}, and the load f_theta = theta f_n + (1-theta)
    // f_{n-1}:
    double load_work = 0; // W_n = (f_theta, u_n - u_{n-1})
    double inertia   = 0; // (theta - 1/2) rho |w_n - w_{n-1}|^2
    double elastic   = 0; // (theta - 1/2) a_E(u_n - u_{n-1}, u_n - u_{n-1})
    double viscous   = 0; // k a_C(w_e, w_e)
    double compliance = 0; // sum m_i [P (u_n - u_{n-1}) - (Pi(u_n) - Pi(u_{n-1}))],
                           // P = p(u_n) (theta = 1) or the discrete gradient (0)
    double damping   = 0; // k sum m_i q(w_e,nu) w_e,nu
    double friction  = 0; // k sum lambda_i . w_e,tau,i
    double defect    = 0; // E_n - E_{n-1} + D_n - W_n

    double
    dissipation() const
    {
      return inertia + elastic + viscous + compliance + damping + friction;
    }

    /** The smallest of the dissipation terms. */
    double
    min_dissipation_term() const;

    /**
     * Every dissipation term is >= 0 up to the round-off of its evaluation,
     * roundoff times scale(): a quadratic form like (1/2) a_E(du, du) of a
     * nearly rigid du (a sliding block) is computed as a difference of large
     * numbers. A real violation is of the order of the scale.
     */
    static constexpr double roundoff = 1e-12;

    /**
     * The size of the quantities that balance: the defect relative to it
     * measures the balance.
     */
    double
    scale(const double previous_energy) const;
  };


  template <int dim>
  class EnergyBalance
  {
  public:
    EnergyBalance(const BulkOperator<dim> &    bulk,
                  const ContactBoundary<dim> &contact_boundary,
                  const Foundation &          foundation,
                  const double                density,
                  const MPI_Comm              comm);

    /** E(u, w), with the nodal penetrations of u computed here. */
    Energy
    energy(const Vector_t &u, const Vector_t &w) const;

    /**
     * All terms of step n, from u_{n-1}, w_{n-1}, u_n, w_n, the load vector
     * f_n (f_theta), the step's scheme (k, theta) and the node states of
     * the converged solve;
     * @p previous_energy is E_{n-1}.
     */
    EnergyBalanceTerms
    step_terms(const Vector_t &                         u_old,
               const Vector_t &                         w_old,
               const Vector_t &                         u,
               const Vector_t &                         w,
               const Vector_t &                         load,
               const TimeScheme &                       scheme,
               const std::vector<ContactNodeState<dim>> &states,
               const double previous_energy) const;

  private:
    const BulkOperator<dim> &    bulk;
    const ContactBoundary<dim> &contact_boundary;
    const Foundation &          foundation;
    const double                density;
    const MPI_Comm              comm;
    mutable Vector_t            difference;
  };
} // namespace DynamicContact

#endif
