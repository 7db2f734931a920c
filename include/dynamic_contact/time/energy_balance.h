#ifndef dynamic_contact_energy_balance_h
#define dynamic_contact_energy_balance_h

#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/bulk/bulk_operator.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/laws/contact_law.h>
#include <dynamic_contact/laws/foundation.h>

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
    double compliance =
      0; // sum m_i [P (u_n - u_{n-1}) - (Pi(u_n) - Pi(u_{n-1}))],
         // P = p(u_n) (theta = 1), the discrete gradient (theta = 1/2:
         // 0), TimeScheme::compliance_force in between
    double damping  = 0; // k sum m_i q(w_e,nu) w_e,nu
    double friction = 0; // k sum lambda_i . w_e,tau,i
    /**
     * k sum |lambda_i| |w_e,tau,i| over the stick nodes: there w_e,tau = 0
     * holds to the Newton tolerance only, so that part of the friction
     * term is the solver's residual, of either sign. The friction term
     * counts as >= 0 (min_dissipation_term()) if it is above -slack; a slip
     * node whose force does work against its slip is no part of it.
     */
    double friction_slack = 0;
    double defect   = 0; // E_n - E_{n-1} + D_n - W_n
    /**
     * Whether the compliance term is >= 0 by the theory: true for the
     * one-step schemes and the Bathe scheme (p nondecreasing), false for
     * the SDIRK scheme, whose end state combines the stages so that a node
     * entering or leaving contact within the step can give it either sign
     * (doc/theory.md section 6); min_dissipation_term() then leaves it out.
     */
    bool compliance_sign_definite = true;

    double
    dissipation() const
    {
      return inertia + elastic + viscous + compliance + damping + friction;
    }

    /** defect = E_n - E_{n-1} + D_n - W_n, once every other term is set. */
    void
    close(const double previous_energy)
    {
      defect = energy.total() - previous_energy + dissipation() - load_work;
    }

    /**
     * The smallest of the dissipation terms that the theory makes >= 0
     * (all six, or all but the compliance term: compliance_sign_definite).
     */
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


  /**
   * The balance of one step of the Bathe scheme (Time/Scheme = bathe, with
   * its spectral radius at infinity rho_inf; doc/theory.md sections 2.4
   * and 6) from those of its sub-steps: @p first (trapezoidal, from
   * E_{n-1} to E_{n-1/2} = first.energy), the energy @p extrapolated of
   * x_bar = (1 + a) x_{n-1/2} - a x_{n-1} (a = 1/3 at rho_inf = 0),
   * @p second (the theta-step from x_bar to x_n, theta = 1 at rho_inf = 0,
   * its load work (f_theta, u_n - u_bar)), and @p extrapolation_work =
   * (f_theta, u_bar - u_{n-1/2}). The load work of the step is that along
   * u_{n-1} -> u_{n-1/2} -> u_bar -> u_n,
   *   W_n = first.load_work + extrapolation_work + second.load_work,
   * the physical terms (viscous, damping, friction, compliance) add up,
   * and the extrapolation's change of the total potential energy,
   * E(x_bar) - E(x_{n-1/2}) - (f_theta, u_bar - u_{n-1/2}), which no force
   * does, is booked against the sub-steps' numerical terms:
   *   inertia = (theta - 1/2)(rho |w_n - w_bar|^2
   *                           + a_E(u_n - u_bar, u_n - u_bar))
   *             - (E(x_bar) - E(x_{n-1/2}) - (f_theta, u_bar - u_{n-1/2})),
   * the scheme's whole numerical dissipation (elastic = 0), so that
   * E_n - E_{n-1} + D_n = W_n holds exactly. It is >= 0 for an undamped
   * linear system under a constant load (mode by mode, about the static
   * state, the step does not increase the energy); with damping or a load
   * that changes in time it can be < 0 (doc/theory.md section 6 shows that
   * no consistent booking avoids that); that it is >= 0 in a run is
   * checked, not assumed (tests/energy_balance, tests/spectral_radius).
   */
  EnergyBalanceTerms
  bathe_terms(const EnergyBalanceTerms &first,
              const Energy             &extrapolated,
              const EnergyBalanceTerms &second,
              const double              extrapolation_work,
              const double              previous_energy);


  /**
   * The balance of one step of the SDIRK scheme (Time/Scheme = sdirk;
   * doc/theory.md sections 2.6 and 6) from those of its two
   * backward-Euler stages of gamma k: @p first from y_{n-1} (energy
   * @p previous_energy, of which foundation energy @p old_foundation) to
   * Y1, @p second from y_hat (energy @p hat_energy) to Y2, and the energy
   * @p end_energy of y_n. The step's work and
   * physical dissipation are the stages' times @p weight = 1/(2 gamma)
   * (b_i k over the stage's gamma k): W_n = k sum_i b_i (f_i, W_i), the
   * viscous, damping and friction terms alike; the compliance term is the
   * stages' compliance power k sum_i b_i p(U_i) W_i minus the change of
   * the foundation energy over the step (>= 0 where no node crosses the
   * foundation's threshold within the step and p is linear, as in the
   * paper; measured otherwise), and the numerical dissipation
   *   inertia = @p numerical = (gamma - 1/4)/(2 gamma^2)
   *             |(Y1 - y_{n-1}) - (Y2 - y_hat)|_E^2 >= 0
   * (elastic = 0), so that E_n - E_{n-1} + D_n = W_n holds exactly.
   */
  EnergyBalanceTerms
  sdirk_terms(const EnergyBalanceTerms &first,
              const EnergyBalanceTerms &second,
              const double              previous_energy,
              const double              old_foundation,
              const Energy             &hat_energy,
              const Energy             &end_energy,
              const double              numerical,
              const double              weight);


  template <int dim>
  class EnergyBalance
  {
  public:
    EnergyBalance(const BulkOperator<dim>    &bulk,
                  const ContactBoundary<dim> &contact_boundary,
                  const Foundation           &foundation,
                  const double                density,
                  const MPI_Comm              comm)
      : bulk(bulk)
      , contact_boundary(contact_boundary)
      , foundation(foundation)
      , density(density)
      , comm(comm)
    {}

    /** E(u, w), with the nodal penetrations of u computed here. */
    Energy
    energy(const Vector_t &u, const Vector_t &w) const;

    /** The foundation part sum_i m_i Pi(u_nu,i) of E (collective). */
    double
    foundation_energy(const Vector_t &u) const;

    /**
     * All terms of step n, from u_{n-1}, w_{n-1}, u_n, w_n, the load vector
     * f_n (f_theta), the step's scheme (k, theta) and the node states of
     * the converged solve;
     * @p previous_energy is E_{n-1}.
     */
    EnergyBalanceTerms
    step_terms(const Vector_t                           &u_old,
               const Vector_t                           &w_old,
               const Vector_t                           &u,
               const Vector_t                           &w,
               const Vector_t                           &load,
               const TimeScheme                         &scheme,
               const std::vector<ContactNodeState<dim>> &states,
               const double                              previous_energy) const;

  private:
    const BulkOperator<dim>    &bulk;
    const ContactBoundary<dim> &contact_boundary;
    const Foundation           &foundation;
    const double                density;
    const MPI_Comm              comm;
    mutable Vector_t            difference;
  };
} // namespace DynamicContact

#endif
