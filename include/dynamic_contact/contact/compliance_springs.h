#ifndef dynamic_contact_compliance_springs_h
#define dynamic_contact_compliance_springs_h

#include <deal.II/lac/full_matrix.h>

#include <dynamic_contact/contact/compliance_table.h>
#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/contact/contact_solver.h>

#include <utility>
#include <vector>

namespace DynamicContact
{
  /**
   * The stiff springs S of BoundaryCompliance's K0' = K0 + S: at which two
   * (2D) or three (3D) extreme nodes of Gamma_3 they act (on the free
   * components), how stiff they are (the largest diagonal entry of K0
   * there), and how they are removed again: the Woodbury identity
   * K0^{-1} = C' + C' P^T (S^{-1} - P C' P^T)^{-1} P C' (C' = K0'^{-1} the
   * compliance table, P the springs' DoFs), whose small inverse it keeps for
   * the K0' it was made with.
   */
  template <int dim>
  class ComplianceSprings
  {
  public:
    ComplianceSprings(const ContactProblem<dim>   &problem,
                      const GatheredBoundary<dim> &gathered)
      : problem(problem)
      , gathered(gathered)
    {}

    /**
     * After GatheredBoundary::reinit(): choose the spring nodes and forget
     * the Woodbury correction.
     */
    void
    reinit();

    /**
     * @p regularized = K0 + S from the current K0 (collective);
     * @p owned_index: for each node, its index among the owned nodes, or -1.
     */
    void
    add_springs(Matrix_t &regularized, const std::vector<int> &owned_index);

    /** The spring's stiffness at every node (0 where there is none). */
    double
    stiffness(const unsigned int i) const
    {
      return springs[i];
    }

    /**
     * The nodes whose columns of C' apply_k0() needs: @p nodes and the
     * spring nodes (whose DoFs it first finds again if K0' changed,
     * @p prepared_scheme being that of the current K0').
     */
    std::vector<unsigned int>
    needed_nodes(const std::vector<unsigned int> &nodes,
                 const TimeScheme                &prepared_scheme);

    /**
     * @p v[a] = sum_b [K0^{-1}]_{nodes[a] nodes[b]} @p f[b] from the
     * columns of @p table (those of needed_nodes(), rank 0), with the
     * Woodbury correction made again if K0' changed.
     */
    void
    apply_k0(const ComplianceTable<dim>        &table,
             const std::vector<unsigned int>   &nodes,
             const std::vector<Tensor<1, dim>> &f,
             std::vector<Tensor<1, dim>>       &v,
             const TimeScheme                  &prepared_scheme);

    /**
     * sum_b |R_a [K0^{-1}]_ab R_b^T| x_b for every vector x of @p x (rank
     * 0, after apply_k0() over @p nodes): the entries of K0^{-1} one block
     * at a time, C' plus the springs' Woodbury term.
     */
    void
    apply_absolute(const ComplianceTable<dim>             &table,
                   const std::vector<unsigned int>        &nodes,
                   const std::vector<Tensor<2, dim>>      &R,
                   const std::vector<std::vector<double>> &x,
                   std::vector<std::vector<double>>       &y) const;

  private:
    const ContactProblem<dim>   &problem;
    const GatheredBoundary<dim> &gathered;

    /** The spring nodes (indices into all_nodes()) and their stiffness. */
    std::vector<unsigned int> spring_nodes;
    std::vector<double>       springs; // one per node of all_nodes()

    /**
     * (S^{-1} - P C' P^T)^{-1} of apply_k0() and the springs' (node,
     * component) pairs, for the K0' they were made with.
     */
    FullMatrix<double>                                 spring_correction;
    std::vector<std::pair<unsigned int, unsigned int>> spring_dofs;
    TimeScheme                                         correction_scheme;

    /** Choose the spring nodes (once per mesh). */
    void
    choose_spring_nodes();
  };
} // namespace DynamicContact

#endif
