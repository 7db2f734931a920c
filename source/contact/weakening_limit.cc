#include <dynamic_contact/contact/weakening_limit.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace DynamicContact
{
  namespace WeakeningLimit
  {
    namespace
    {
      /**
       * The smallest or largest eigenvalue of the symmetric block @p A
       * restricted to the tangent plane of @p node.
       */
      template <int dim>
      double
      tangential_eigenvalue(const ContactNode<dim> &node,
                            const Tensor<2, dim>   &A,
                            const bool              largest)
      {
        const auto  &t = node.tangents;
        const double a = t[0] * (A * t[0]);
        if (dim == 2)
          return a;
        const double d    = t[dim - 2] * (A * t[dim - 2]);
        const double b    = 0.5 * (t[0] * (A * t[dim - 2]) +
                                t[dim - 2] * (A * t[0]));
        const double mean = 0.5 * (a + d);
        const double root = std::sqrt(0.25 * (a - d) * (a - d) + b * b);
        return largest ? mean + root : mean - root;
      }
    } // namespace


    template <int dim>
    double
    tangential_stiffness(const ContactNode<dim> &node, const Tensor<2, dim> &K)
    {
      const Tensor<2, dim> &P = node.constraint_map;
      return tangential_eigenvalue(node, P * K * transpose(P), false);
    }


    template <int dim>
    double
    tangential_compliance(const ContactNode<dim> &node,
                          const Tensor<2, dim>   &C_ii)
    {
      return tangential_eigenvalue(node, C_ii, true);
    }


    template <int dim>
    std::vector<int>
    sample(const std::vector<ContactNode<dim>> &nodes, const MPI_Comm comm)
    {
      // The bounding box of Gamma_3.
      Point<dim> lower, upper;
      for (unsigned int c = 0; c < dim; ++c)
        {
          double lo = std::numeric_limits<double>::max(), hi = -lo;
          for (const auto &node : nodes)
            {
              lo = std::min(lo, node.position[c]);
              hi = std::max(hi, node.position[c]);
            }
          lower[c] = Utilities::MPI::min(lo, comm);
          upper[c] = Utilities::MPI::max(hi, comm);
        }
      unsigned int axis = 0;
      for (unsigned int c = 1; c < dim; ++c)
        if (upper[c] - lower[c] > upper[axis] - lower[axis])
          axis = c;

      std::vector<int> chosen(n_samples, -1);
      for (unsigned int s = 0; s < n_samples; ++s)
        {
          Point<dim> target = 0.5 * (lower + upper);
          target[axis] =
            lower[axis] + (s + 0.5) / n_samples * (upper[axis] - lower[axis]);
          int    best     = -1;
          double distance = std::numeric_limits<double>::max();
          for (unsigned int i = 0; i < nodes.size(); ++i)
            {
              const double d = nodes[i].position.distance(target);
              if (d < distance || (best >= 0 && d == distance &&
                                   nodes[i].dofs[0] < nodes[best].dofs[0]))
                {
                  distance = d;
                  best     = i;
                }
            }
          const double nearest = Utilities::MPI::min(distance, comm);
          const double first_dof =
            (best >= 0 && distance == nearest) ?
              static_cast<double>(nodes[best].dofs[0]) :
              std::numeric_limits<double>::max();
          const double winner = Utilities::MPI::min(first_dof, comm);
          if (best >= 0 && first_dof == winner &&
              winner < std::numeric_limits<double>::max())
            chosen[s] = best;
        }
      return chosen;
    }


    template <int dim>
    std::vector<double>
    limits(const std::vector<ContactNode<dim>>    &nodes,
           const std::vector<double>              &stiffness,
           const std::function<double(const int)> &compliance,
           const MPI_Comm                          comm)
    {
      const std::vector<int> chosen = sample(nodes, comm);
      double                 ratio  = 0;
      for (const int j : chosen)
        {
          const double c = compliance(j); // collective
          if (j >= 0 && c > 0 && stiffness[j] > 0)
            ratio = std::max(ratio, stiffness[j] * c);
        }
      ratio = Utilities::MPI::max(ratio, comm);
      std::vector<double> result(nodes.size(),
                                 std::numeric_limits<double>::infinity());
      if (ratio > 0)
        for (unsigned int i = 0; i < nodes.size(); ++i)
          if (stiffness[i] > 0)
            result[i] = fraction * stiffness[i] / ratio;
      return result;
    }


    template double
    tangential_stiffness(const ContactNode<2> &, const Tensor<2, 2> &);
    template double
    tangential_stiffness(const ContactNode<3> &, const Tensor<2, 3> &);
    template double
    tangential_compliance(const ContactNode<2> &, const Tensor<2, 2> &);
    template double
    tangential_compliance(const ContactNode<3> &, const Tensor<2, 3> &);
    template std::vector<int>
    sample(const std::vector<ContactNode<2>> &, const MPI_Comm);
    template std::vector<int>
    sample(const std::vector<ContactNode<3>> &, const MPI_Comm);
    template std::vector<double>
    limits(const std::vector<ContactNode<2>> &,
           const std::vector<double> &,
           const std::function<double(const int)> &,
           const MPI_Comm);
    template std::vector<double>
    limits(const std::vector<ContactNode<3>> &,
           const std::vector<double> &,
           const std::function<double(const int)> &,
           const MPI_Comm);
  } // namespace WeakeningLimit
} // namespace DynamicContact
