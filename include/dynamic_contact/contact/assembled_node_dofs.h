#ifndef dynamic_contact_assembled_node_dofs_h
#define dynamic_contact_assembled_node_dofs_h

#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/contact_node.h>

#include <cmath>

namespace DynamicContact
{
  /**
   * A contact node's entries in a vector of the whole body as the assembled
   * solver's Newton system sees them: the raw DoF values (without the
   * node's constraint map), their normal part, and the row that carries a
   * stick node's normal equation.
   */
  namespace AssembledNodeDofs
  {
    /** The raw (DoF) values of a node, without its constraint map. */
    template <int dim>
    inline Tensor<1, dim>
    raw_values(const ContactNode<dim> &node, const Vector_t &v)
    {
      Tensor<1, dim> r;
      for (unsigned int c = 0; c < dim; ++c)
        r[c] = v[node.dofs[c]];
      return r;
    }

    template <int dim>
    inline void
    set_raw_values(const ContactNode<dim> &node,
                   const Tensor<1, dim>   &r,
                   Vector_t               &v)
    {
      for (unsigned int c = 0; c < dim; ++c)
        v(node.dofs[c]) = r[c];
    }

    /** The normal part nu (nu . v) of a nodal vector. */
    template <int dim>
    inline Tensor<1, dim>
    normal_part(const ContactNode<dim> &node, const Tensor<1, dim> &v)
    {
      return (v * node.normal) * node.normal;
    }

    /**
     * The host row of a stick node's normal equation in the assembled
     * Newton matrix: the component with the largest normal entry; the
     * others carry t_s . w = 0.
     */
    template <int dim>
    inline unsigned int
    host_component(const ContactNode<dim> &node)
    {
      unsigned int host = 0;
      for (unsigned int c = 1; c < dim; ++c)
        if (std::abs(node.normal[c]) > std::abs(node.normal[host]))
          host = c;
      return host;
    }
  } // namespace AssembledNodeDofs
} // namespace DynamicContact

#endif
