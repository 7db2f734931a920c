#ifndef dynamic_contact_well_posedness_h
#define dynamic_contact_well_posedness_h

#include <string>

namespace DynamicContact
{
  /**
   * Whether the theory covers a scene whose friction weakens with the slip
   * rate (doc/theory.md section 1.5): two conditions, each a dimensionless
   * ratio of the scene's data, so that the same scene gives the same
   * numbers in any consistent units.
   *
   * - Radiation damping: R = L S / (rho c_s). When the slip rate of Gamma_3
   *   rises by dw, friction falls by L S dw, and the body answers with a
   *   shear wave that takes up rho c_s dw. Beyond R = 1 the weakening wins
   *   at every wavelength; an elastic body's growth rates then grow without
   *   bound as the wavelength shrinks: the problem is ill-posed (Ranjith &
   *   Rice 2001, Rice, Lapusta & Ranjith 2001; they quote rho c_s / 2 for
   *   two bodies of one material, which share the slip).
   * - The viscosity's coercivity against the weakening (the paper's
   *   Remark 8): G = 2 (L S)^2 T / (rho c2). Testing the difference of two
   *   solutions with itself, the viscosity c2 must absorb the weakening's
   *   boundary term; with the trace inequality of a half-space the
   *   remainder lets the difference grow at most by exp(G) over the run.
   *   Without viscosity (c2 = 0) the paper's Theorems 4 and 6 do not apply.
   *
   * L is the one-sided Lipschitz constant of mu (the largest weakening
   * rate |mu'|), S the largest normal stress p + q the foundation's laws
   * allow (c3 + c4; infinite where a law gives no bound), T the end time.
   */
  class WellPosedness
  {
  public:
    struct Data
    {
      /** L, of mu on the scene's slip rates [0, s_max]. */
      double weakening;
      /** S = c3 + c4; infinite where a law gives no bound. */
      double normal_stress;
      double density;
      /** c_s = sqrt(mu/rho). */
      double shear_wave_speed;
      /** c2 of H(C)(b), 0 for an elastic body. */
      double viscous_coercivity;
      /** T. */
      double end_time;
      /**
       * The coefficient is a state over a slip length (SlipLength): L is
       * the weakening of the steady-sliding law, not an instantaneous one.
       */
      bool slip_length = false;
    };

    explicit WellPosedness(const Data &data)
      : data(data)
    {}

    /** The shear modulus mu = rho c_s^2: the unit of the stresses below. */
    double
    shear_modulus() const;

    /** S / mu (infinite where S is). */
    double
    relative_normal_stress() const;

    /** R = L S / (rho c_s); 0 where L = 0, infinite where S is. */
    double
    radiation_ratio() const;

    /**
     * The normal stress at which R = 1, in units of mu: 1 / (L c_s);
     * infinite where L = 0.
     */
    double
    radiation_critical_stress() const;

    /**
     * G = 2 (L S)^2 T / (rho c2); 0 where L = 0, infinite where c2 = 0 (and
     * L > 0) or S is infinite.
     */
    double
    growth_exponent() const;

    /**
     * The normal stress at which G = 1, in units of mu:
     * sqrt(rho c2 / (2 T)) / (L mu); infinite where L = 0.
     */
    double
    growth_critical_stress() const;

    /**
     * The report of the start-up output and of --validate: a heading and
     * one line per condition, each with its ratio, the factor by which it
     * holds or fails, the normal stress up to which it holds and a
     * sentence of what it means. Every line starts with two spaces and
     * ends with a newline.
     */
    std::string
    report() const;

  private:
    /** The line of the radiation damping condition. */
    std::string
    radiation_line() const;

    /** The line of the viscosity's coercivity (Remark 8). */
    std::string
    viscosity_line() const;

    Data data;
  };
} // namespace DynamicContact

#endif
