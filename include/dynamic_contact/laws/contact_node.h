#ifndef dynamic_contact_contact_node_h
#define dynamic_contact_contact_node_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <array>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * One node of the contact boundary Gamma_3 (doc/theory.md section 3): a
   * support point of the finite element on Gamma_3 that is not a hanging node,
   * with its lumped weight m_i = int_Gamma3 phi_i (Gauss-Lobatto quadrature,
   * condensed through the hanging-node constraints), its averaged outward
   * normal nu_i and a tangent basis. Every contact law is evaluated node by
   * node on these data.
   */
  template <int dim>
  struct ContactNode
  {
    /** The DoF of each displacement/velocity component at the node. */
    std::array<types::global_dof_index, dim> dofs;
    /**
     * The clamped/roller constraints restricted to the node: the nodal
     * vector is P times the entries stored in master form (P = identity at
     * an unconstrained node). Node forces enter the residual as P^T f.
     */
    Tensor<2, dim> constraint_map;
    /** No component is constrained: the tangential motion is free. */
    bool       unconstrained;
    Point<dim> position;
    /** Unit outward normal nu_i (u_nu > 0 is penetration). */
    Tensor<1, dim> normal;
    /**
     * Orthonormal tangents: in 2D the normal rotated by +90 degrees
     * (t = (1, 0) on a bottom face), in 3D t_1 along the projection of the
     * first coordinate axis (or the second, if the normal is near the first),
     * t_2 = t_1 x nu.
     */
    std::array<Tensor<1, dim>, dim - 1> tangents;
    /** Lumped weight m_i. */
    double weight;
    /** Initial gap g0(x_i). */
    double gap;
    /** The node's DoF in the scalar output space. */
    types::global_dof_index scalar_dof;

    /** The nodal vector of a (master form) global vector. */
    template <typename VectorType>
    Tensor<1, dim>
    value(const VectorType &v) const
    {
      Tensor<1, dim> raw;
      for (unsigned int c = 0; c < dim; ++c)
        raw[c] = v[dofs[c]];
      return constraint_map * raw;
    }

    /** Tangential part of a vector. */
    Tensor<1, dim>
    tangential(const Tensor<1, dim> &v) const
    {
      return v - (v * normal) * normal;
    }
  };
} // namespace DynamicContact

#endif
