#ifndef dynamic_contact_slip_length_h
#define dynamic_contact_slip_length_h

#include <dynamic_contact/base/time_scheme.h>

#include <string>
#include <utility>

namespace DynamicContact
{
  class FrictionLaw;


  /**
   * The slip-rate law with a slip length (Friction/Slip length L > 0,
   * doc/theory.md section 1.6): the coefficient is a state mu~ of each node
   * of Gamma_3 that relaxes towards mu(s) over the slip L,
   *   d mu~/dt = -((s + v*)/L) (mu~ - mu(s)),
   * v* the Reference slip rate (the state relaxes at rest too where v* > 0).
   * A theta-step of length k from the state m at its start, with the slip
   * rate s of its effective velocity held over the step, ends with the
   * exact solution of that equation,
   *   mu~_n = mu(s) + (m - mu(s)) E,   E = exp(-k (s + v*)/L),
   * and its friction acts with the state at the effective time,
   *   mu_e = theta mu~_n + (1 - theta) m,
   * which lies between m and mu(s) for any k (no time-step limit of its
   * own, no overshoot). L = 0 is the law itself: mu_e = mu(s).
   */
  class SlipLength
  {
  public:
    SlipLength(const double slip_length = 0, const double reference_rate = 0)
      : L(slip_length)
      , v_ref(reference_rate)
    {}

    /** L > 0: the coefficient is a state of the node. */
    bool
    active() const
    {
      return L > 0;
    }

    /** The state mu~_n at the end of the step (mu(s) without a length). */
    double
    end_state(const FrictionLaw &law,
              const double       m,
              const double       s,
              const TimeScheme  &scheme) const;

    /**
     * The coefficient mu_e the step acts with at the slip rate @p s from
     * the state @p m, and its derivative in s (the coupled linearization):
     *   d mu_e/ds = theta ((1 - E) mu'(s) - (m - mu(s)) E k/L).
     */
    std::pair<double, double>
    step_coefficient(const FrictionLaw &law,
                     const double       m,
                     const double       s,
                     const TimeScheme  &scheme) const;

    /**
     * An upper bound of the one-sided Lipschitz constant in s of mu_e on
     * [0, s_max] for a law with constant @p lipschitz and largest value
     * @p mu_max there: max(lipschitz, mu_max k/L) (the bound of
     * doc/theory.md section 5.2 with the step's law).
     */
    double
    step_lipschitz_constant(const double      lipschitz,
                            const double      mu_max,
                            const TimeScheme &scheme) const;

    /** E.g. "slip length L = 0.1, reference slip rate v* = 0". */
    std::string
    description() const;

  private:
    double L, v_ref;
  };
} // namespace DynamicContact

#endif
