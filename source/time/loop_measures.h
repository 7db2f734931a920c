#ifndef dynamic_contact_source_time_loop_measures_h
#define dynamic_contact_source_time_loop_measures_h

// What the convexification loop (convexification_loop.cc, its only user)
// measures of an iterate: a header of that file, not of the library.

#include <deal.II/base/mpi.h>

#include <dynamic_contact/time/step_solver.h>

#include <cmath>
#include <limits>

namespace DynamicContact
{
  namespace
  {
    /** mu(s), checked to be finite and >= 0 where it is used. */
    double
    checked_coefficient(const FrictionLaw &law, const double s)
    {
      const double mu = law.value(s);
      AssertThrow(std::isfinite(mu) && mu >= 0,
                  ExcMessage("Friction: the friction coefficient must be "
                             "finite and >= 0 on the slip rates that occur, "
                             "but mu(" +
                             std::to_string(s) + ") = " + std::to_string(mu) +
                             " (Friction/Law and its parameters)."));
      return mu;
    }
  } // namespace


  namespace
  {
    /**
     * What the convexification loop measures of an iterate w of a step
     * (doc/theory.md section 4), at the owned nodes of Gamma_3: the slip
     * rate of the effective velocity w_e = theta w + (1 - theta) w_old and
     * the normal pressure S = p + q, the friction density xi_i = lambda_i /
     * (m_i S_i) (the selection of the subdifferential in eq. (52)), and the
     * stopping rule (85) with the node-wise law.
     */
    template <int dim>
    class LoopMeasures
    {
    public:
      struct NodalIterate
      {
        std::vector<double> slip_rate, pressure;
      };
      /** The measures of a pass against the last one. */
      struct Measures
      {
        bool                        converged;
        double                      coefficient_residual;
        NodalIterate                iterate;
        std::vector<Tensor<1, dim>> xi;
        std::vector<double>         mu_new;
      };

      LoopMeasures(const Discretization<dim>         &discretization,
                   const ContactBoundary<dim>        &boundary,
                   const Foundation                  &foundation,
                   const FrictionLaw                 *friction_law,
                   const SlipLength                  &slip_length,
                   const std::vector<double>         &state,
                   const BulkOperator<dim>           &bulk,
                   const TimeScheme                  &scheme,
                   const std::vector<Tensor<1, dim>> &u_old_nodes,
                   const std::vector<Tensor<1, dim>> &w_old_nodes,
                   const double                       tolerance,
                   const double                       coefficient_tolerance,
                   const MPI_Comm                     comm)
        : all(boundary.nodes())
        , boundary(boundary)
        , foundation(foundation)
        , friction_law(friction_law)
        , slip_length(slip_length)
        , state(state)
        , bulk(bulk)
        , scheme(scheme)
        , u_old_nodes(u_old_nodes)
        , w_old_nodes(w_old_nodes)
        , eps(tolerance)
        , coefficient_tolerance(coefficient_tolerance)
        , comm(comm)
      {
        discretization.reinit_owned(u_previous);
        discretization.reinit_owned(u_current);
        discretization.reinit_owned(difference);
      }

      /**
       * At the start of the loop: mu_i = mu(|w_tau,i|) of the initial
       * guess @p w into @p mu; returns xi of @p lambda there.
       */
      std::vector<Tensor<1, dim>>
      start(const Vector_t                    &w,
            const std::vector<Tensor<1, dim>> &lambda,
            std::vector<double>               &mu) const
      {
        const auto n = iterate(boundary.values(w));
        coefficients_of(n, mu);
        return density(lambda, n);
      }

      /**
       * After a coupled pass: the coefficients it ended with, mu_i =
       * mu(|w_tau,i|) of its nodal velocities @p values, at every node (the
       * frozen coefficients of the passes after it).
       */
      void
      coefficients_at(const std::vector<Tensor<1, dim>> &values,
                      std::vector<double>               &mu) const
      {
        coefficients_of(iterate(values), mu);
      }

      /** mu_i = mu(|w_tau,i|) of @p n at every node. */
      void
      coefficients_of(const NodalIterate &n, std::vector<double> &mu) const
      {
        for (unsigned int i = 0; i < all.size(); ++i)
          mu[i] = coefficient(i, n.slip_rate[i]);
      }

      /**
       * The coefficient of node @p i at the slip rate @p s: mu(s), or with
       * a slip length the step's mu_e from the node's state (SlipLength).
       */
      double
      coefficient(const unsigned int i, const double s) const
      {
        const double mu = checked_coefficient(*friction_law, s);
        return slip_length.active() ?
                 slip_length
                   .step_coefficient(*friction_law, state[i], s, scheme)
                   .first :
                 mu;
      }

      /** Before a pass: u^(m) = u_old + k w of the last iterate. */
      void
      remember(const Vector_t &u_old, const double k, const Vector_t &w)
      {
        u_previous = u_old;
        u_previous.add(k, w);
      }

      /**
       * The coefficients mu(|w_tau,i|) of @p m also at the nodes out of
       * contact (measure() leaves them out): the next frozen ones.
       */
      void
      complete_coefficients(Measures &m) const
      {
        for (unsigned int i = 0; i < all.size(); ++i)
          if (!(m.iterate.pressure[i] > 0))
            m.mu_new[i] = coefficient(i, m.iterate.slip_rate[i]);
      }

      NodalIterate
      iterate(const std::vector<Tensor<1, dim>> &values) const
      {
        NodalIterate n{std::vector<double>(all.size()),
                       std::vector<double>(all.size())};
        for (unsigned int i = 0; i < all.size(); ++i)
          {
            n.slip_rate[i] =
              all[i]
                .tangential(scheme.weighted(values[i], w_old_nodes[i]))
                .norm();
            n.pressure[i] = normal_response(foundation,
                                            all[i],
                                            u_old_nodes[i],
                                            w_old_nodes[i],
                                            values[i],
                                            scheme)
                              .pressure;
          }
        return n;
      }

      std::vector<Tensor<1, dim>>
      density(const std::vector<Tensor<1, dim>> &forces,
              const NodalIterate                &n) const
      {
        std::vector<Tensor<1, dim>> xi(all.size());
        for (unsigned int i = 0; i < all.size(); ++i)
          if (n.pressure[i] > 0)
            xi[i] = forces[i] / (all[i].weight * n.pressure[i]);
        return xi;
      }

      double
      l2(const std::vector<Tensor<1, dim>> &xi) const
      {
        double sum = 0;
        for (unsigned int i = 0; i < all.size(); ++i)
          sum += all[i].weight * xi[i].norm_square();
        return std::sqrt(Utilities::MPI::sum(sum, comm));
      }

      /**
       * Rule (85): ||u^(m+1) - u^(m)||_V <= eps ||u^(m)||_V and
       * ||xi^(m+1) - xi^(m)|| <= eps ||xi^(m)||, plus the node-wise law
       * max_i |mu_i - mu(|w_tau,i|)| <= tol, of the pass @p pass that
       * gave (@p w, @p lambda) with the frozen @p mu (u^(m+1) = u_old +
       * k w), against the last pass (remember(), @p xi_previous). A
       * provisional pass (@p w null) has only its velocities at the nodes,
       * @p w_nodes: it is measured on Gamma_3 alone, and the V-norm part of
       * the rule is left to the pass once finished.
       */
      Measures
      measure(const Vector_t                    &u_old,
              const double                       k,
              const Vector_t                    *w,
              const std::vector<Tensor<1, dim>> &w_nodes,
              const std::vector<Tensor<1, dim>> &lambda,
              const std::vector<double>         &mu,
              const std::vector<Tensor<1, dim>> &xi_previous,
              const unsigned int                 pass,
              const ConditionalOStream          &details)
      {
        double du = 0, u_norm = 0;
        if (w != nullptr)
          {
            u_current = u_old;
            u_current.add(k, *w);
            difference = u_current;
            difference -= u_previous;
            du     = std::sqrt(bulk.strain_product(difference, difference));
            u_norm = std::sqrt(bulk.strain_product(u_previous, u_previous));
          }
        Measures m;
        m.iterate = iterate(w != nullptr ? boundary.values(*w) : w_nodes);
        m.xi      = density(lambda, m.iterate);
        std::vector<Tensor<1, dim>> dxi(all.size());
        for (unsigned int i = 0; i < all.size(); ++i)
          dxi[i] = m.xi[i] - xi_previous[i];
        const double dxi_norm = l2(dxi), xi_norm = l2(xi_previous);
        const bool   rule_85 = du <= eps * u_norm && dxi_norm <= eps * xi_norm;

        // mu(|w_tau,i|), at the nodes in contact first (the others only if
        // the loop goes on: a node out of contact does not decide it).
        m.mu_new.resize(all.size());
        m.coefficient_residual = 0;
        for (unsigned int i = 0; i < all.size(); ++i)
          if (m.iterate.pressure[i] > 0)
            {
              m.mu_new[i] = coefficient(i, m.iterate.slip_rate[i]);
              m.coefficient_residual =
                std::max(m.coefficient_residual, std::abs(mu[i] - m.mu_new[i]));
            }
        m.coefficient_residual =
          Utilities::MPI::max(m.coefficient_residual, comm);
        m.converged =
          rule_85 && m.coefficient_residual <= coefficient_tolerance;
        details << "  convexification pass " << pass + 1;
        if (w != nullptr)
          details << ": |du|_V/|u|_V " << du / std::max(u_norm, 1e-300);
        else
          details << " (provisional, on Gamma_3)";
        details << ", |dxi|/|xi| " << dxi_norm / std::max(xi_norm, 1e-300)
                << ", max |mu_i - mu(|w_tau,i|)| " << m.coefficient_residual
                << std::endl;
        return m;
      }

    private:
      const std::vector<ContactNode<dim>> &all;
      const ContactBoundary<dim>          &boundary;
      const Foundation                    &foundation;
      const FrictionLaw                   *friction_law;
      const SlipLength                    &slip_length;
      const std::vector<double>           &state;
      const BulkOperator<dim>             &bulk;
      const TimeScheme                    &scheme;
      const std::vector<Tensor<1, dim>>   &u_old_nodes;
      const std::vector<Tensor<1, dim>>   &w_old_nodes;
      const double                         eps;
      const double                         coefficient_tolerance;
      const MPI_Comm                       comm;
      Vector_t                             u_previous, u_current, difference;
    };
  } // namespace
} // namespace DynamicContact

#endif
