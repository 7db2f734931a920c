#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/parameters/well_posedness_report.h>
#include <dynamic_contact/run/model_checks.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace DynamicContact
{
  void
  check_friction_law(const RunParameters &parameters)
  {
    // Finite and >= 0 on [0, s_max], and not increasing unless asked for
    // (the convexification loop does not converge for an increasing mu:
    // README, "What can go wrong").
    const std::shared_ptr<const FrictionLaw> &friction_law =
      parameters.friction.law;
    if (!friction_law)
      return;
    const double      s_max = parameters.friction.maximum_slip_rate;
    const std::string name =
      "Friction/" +
      PluginRegistry<FrictionLaw>::subsection(parameters.friction.law_name) +
      ": " + friction_law->description();
    const std::vector<double> s = FrictionLaw::sample_points(s_max);
    std::vector<double>       mu(s.size());
    for (unsigned int i = 0; i < s.size(); ++i)
      {
        mu[i] = friction_law->value(s[i]);
        if (!std::isfinite(mu[i]))
          throw CollectiveError(name + " is not finite at the slip rate s = " +
                                sig6(s[i]) + " (" + scientific(mu[i]) + ").");
      }
    friction_law->check_nonnegative(s_max);
    if (parameters.friction.allow_velocity_strengthening)
      return;
    double mu_max = 0; // the largest |mu| so far
    for (unsigned int i = 1; i < s.size(); ++i)
      {
        mu_max = std::max(mu_max, std::abs(mu[i - 1]));
        if (mu[i] - mu[i - 1] > 1e-9 * std::max(1., mu_max))
          throw CollectiveError(
            name + " increases with the slip rate (mu(" + sig6(s[i - 1]) +
            ") = " + sig6(mu[i - 1]) + ", mu(" + sig6(s[i]) +
            ") = " + sig6(mu[i]) +
            "): a velocity-strengthening law. The convexification "
            "loop (doc/theory.md section 4) freezes mu at the last "
            "slip rate; with an increasing mu a node then alternates "
            "between stick and slip and the loop does not converge, "
            "not even with the smallest time step. Set "
            "Friction/Velocity strengthening = allow to run it "
            "anyway (such steps are kept and reported: run_status "
            "'completed with warnings').");
      }
  }


  template <int dim>
  void
  check_scene_functions(const RunParameters      &parameters,
                        const Scene<dim>         &scene,
                        const Triangulation<dim> &triangulation,
                        const MPI_Comm            comm,
                        const bool                initial_conditions)
  {
    const double        T     = parameters.time.end_time;
    const double        k     = parameters.time.time_step;
    std::vector<double> times = {0., std::min(k, T), T};
    for (unsigned int i = 1; i < 16; ++i)
      times.push_back(T * i / 16.);
    check_collectively(
      comm, scene.non_finite_value(triangulation, times, initial_conditions));
  }


  template <int dim>
  void
  print_model(const ConditionalOStream       &pcout,
              const RunParameters            &parameters,
              const KelvinVoigtMaterial<dim> &material,
              const bool                      has_friction)
  {
    const FrictionLaw *friction_law = parameters.friction.law.get();
    pcout << "  material: rho = " << material.density()
          << ", lambda = " << sig6(material.lambda())
          << ", mu = " << sig6(material.mu())
          << (material.has_viscosity() ? ", viscous" : ", elastic (C = 0)")
          << '\n';
    pcout << "  friction: "
          << (has_friction ? friction_law->description() : std::string("none"));
    if (has_friction)
      pcout << ", one-sided Lipschitz constant on the slip rates [0, "
            << sig6(parameters.friction.maximum_slip_rate) << "]: "
            << sig6(friction_law->one_sided_lipschitz_constant(
                 parameters.friction.maximum_slip_rate))
            << (friction_law->is_constant() ? " (constant: one pass)" : "");
    if (has_friction && parameters.friction.slip_length.active())
      pcout << "; the coefficient a state of each node with "
            << parameters.friction.slip_length.description();
    pcout << '\n';
    pcout << well_posedness_report<dim>(parameters);
  }


  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                          \
  template void check_scene_functions(const RunParameters &,      \
                                      const Scene<dim> &,         \
                                      const Triangulation<dim> &, \
                                      const MPI_Comm,             \
                                      const bool);                \
  template void print_model(const ConditionalOStream &,           \
                            const RunParameters &,                \
                            const KelvinVoigtMaterial<dim> &,     \
                            const bool);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
