#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/time/solution_uniqueness.h>

#include <algorithm>
#include <string>
#include <vector>

namespace DynamicContact
{
  namespace
  {
    /**
     * The starts of Friction/Count solutions (doc/theory.md section 5.3):
     * the loop's own (w_{n-1} and the step's start state), every node
     * sticking, every node slipping fast, and the coupled linearization.
     */
    enum class Start
    {
      previous,
      stick,
      fast_slip,
      coupled
    };

    const char *
    start_name(const Start start)
    {
      switch (start)
        {
          case Start::previous:
            return "previous";
          case Start::stick:
            return "stick";
          case Start::fast_slip:
            return "fast slip";
          case Start::coupled:
            return "coupled";
        }
      return "";
    }


    /**
     * The initial velocity of the stick or fast-slip start at the owned,
     * unconstrained nodes: w_{n-1} with its tangential part replaced so that
     * the effective slip velocity w_e,tau = theta w_tau + (1 - theta)
     * w_{n-1},tau is zero (stick; the node's friction force is zeroed too)
     * or @p fast along the node's old slip direction (its first tangent
     * where it had none).
     */
    template <int dim>
    void
    set_start_velocity(const Start                          start,
                       const std::vector<ContactNode<dim>> &nodes,
                       const Vector_t                      &w_old,
                       const double                         theta,
                       const double                         fast,
                       Vector_t                            &w,
                       std::vector<Tensor<1, dim>>         &lambda)
    {
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          if (!nodes[i].unconstrained)
            continue;
          const Tensor<1, dim> wi = nodes[i].value(w_old);
          // w_e,tau = theta w_tau + (1 - theta) w_old,tau.
          Tensor<1, dim> target;
          if (start == Start::fast_slip)
            {
              Tensor<1, dim> d = nodes[i].tangential(wi);
              if (!(d.norm() > 0))
                d = nodes[i].tangents[0];
              target = fast * d / d.norm();
            }
          const Tensor<1, dim> w_tau =
            (target - (1 - theta) * nodes[i].tangential(wi)) / theta;
          const Tensor<1, dim> value = wi - nodes[i].tangential(wi) + w_tau;
          for (unsigned int c = 0; c < dim; ++c)
            w(nodes[i].dofs[c]) = value[c];
          if (start == Start::stick)
            lambda[i] = Tensor<1, dim>();
        }
      w.compress(VectorOperation::insert);
    }


    /**
     * The largest distance between the nodal velocities @p a and @p b on
     * Gamma_3 (all processes) relative to @p scale.
     */
    template <int dim>
    double
    relative_distance(const std::vector<Tensor<1, dim>> &a,
                      const std::vector<Tensor<1, dim>> &b,
                      const double                       scale,
                      const MPI_Comm                     comm)
    {
      double d = 0;
      for (unsigned int i = 0; i < a.size(); ++i)
        d = std::max(d, (a[i] - b[i]).norm());
      return Utilities::MPI::max(d, comm) / std::max(scale, 1e-300);
    }

    /**
     * The number of solutions in @p found farther apart than 1e-6 of
     * @p scale, the largest velocity on Gamma_3 (the loop's tolerance on mu
     * leaves slip rates to tol/L), each compared with the distinct ones
     * before it; @p spread: the largest of those distances.
     */
    template <int dim>
    unsigned int
    count_distinct(const std::vector<std::vector<Tensor<1, dim>>> &found,
                   const double                                    scale,
                   const MPI_Comm                                  comm,
                   double                                         &spread)
    {
      std::vector<unsigned int> distinct;
      for (unsigned int a = 0; a < found.size(); ++a)
        {
          bool is_new = true;
          for (const unsigned int b : distinct)
            {
              const double d =
                relative_distance(found[a], found[b], scale, comm);
              spread = std::max(spread, d);
              is_new = is_new && d > 1e-6;
            }
          if (is_new)
            distinct.push_back(a);
        }
      return distinct.size();
    }


    /**
     * The slip rate of the fast start: 1000/L (L the law's one-sided
     * Lipschitz constant), far beyond where the law weakens (it changes by
     * at most L s), kept inside [1e-3, 1] times Friction/Maximum slip rate.
     */
    double
    fast_slip_rate(const double maximum_slip_rate,
                   const double lipschitz_constant)
    {
      return std::min(maximum_slip_rate,
                      std::max(1e3 / std::max(lipschitz_constant, 1e-300),
                               1e-3 * maximum_slip_rate));
    }
  } // namespace


  template <int dim>
  void
  SolutionUniqueness<dim>::count_solutions(const Loop              &loop,
                                           const TimeScheme        &scheme,
                                           const Vector_t          &w_old,
                                           const ContactState<dim> &start_state,
                                           StepStatistics          &statistics)
  {
    // doc/theory.md section 5.3. Each start: an initial velocity (which
    // gives the loop its first coefficients mu(|w_tau|)), the friction
    // forces to start from, and the linearization.
    TimerSection            t(timer, "Friction: solution count");
    const MPI_Comm          comm         = discretization.comm;
    const ContactState<dim> solved_state = contact_state;
    const double            fast =
      fast_slip_rate(friction_parameters.maximum_slip_rate, lipschitz_constant);
    std::vector<std::vector<Tensor<1, dim>>> found;
    std::vector<std::string>                 found_by;
    double                                   scale = 0;
    for (const Start start :
         {Start::previous, Start::stick, Start::fast_slip, Start::coupled})
      {
        Vector_t w    = w_old;
        contact_state = start_state;
        if (start == Start::stick || start == Start::fast_slip)
          set_start_velocity(start,
                             contact_boundary.nodes(),
                             w_old,
                             scheme.effective_derivative(),
                             fast,
                             w,
                             contact_state.lambda);
        StepStatistics unused;
        try
          {
            loop(w,
                 unused,
                 1e-2 * friction_parameters.coefficient_tolerance,
                 std::max(200u,
                          friction_parameters.max_convexification_iterations),
                 start == Start::coupled);
          }
        catch (const StepFailure &failure)
          {
            details << "  solution count: start " << start_name(start)
                    << " reached no solution (" << failure.what() << ")"
                    << std::endl;
            ++statistics.failed_starts;
            continue;
          }
        details << "  solution count: start " << start_name(start)
                << " reached a solution in "
                << unused.convexification_iterations
                << " passes, max |mu_i - mu(|w_tau,i|)| "
                << unused.coefficient_residual << std::endl;
        found.push_back(contact_boundary.values(w));
        found_by.push_back(start_name(start));
        for (const auto &v : found.back())
          scale = std::max(scale, v.norm());
      }
    contact_state = solved_state;
    scale         = Utilities::MPI::max(scale, comm);

    statistics.solution_spread = 0;
    const unsigned int n_distinct =
      count_distinct(found, scale, comm, statistics.solution_spread);
    statistics.solutions = n_distinct;
    for (unsigned int a = 1; a < found.size(); ++a)
      details << "  solution count: start " << found_by[a]
              << ": distance to start " << found_by[0] << "'s "
              << relative_distance(found[a], found[0], scale, comm)
              << std::endl;
    details << "  solution count: " << found.size() << " starts reached "
            << n_distinct << " distinct solution(s), largest distance "
            << statistics.solution_spread
            << " of the largest velocity on Gamma_3" << std::endl;
  }


#define DYNAMIC_CONTACT_INSTANTIATE(dim)                  \
  template void SolutionUniqueness<dim>::count_solutions( \
    const Loop &,                                         \
    const TimeScheme &,                                   \
    const Vector_t &,                                     \
    const ContactState<dim> &,                            \
    StepStatistics &);
  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
