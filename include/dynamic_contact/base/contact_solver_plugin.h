#ifndef dynamic_contact_contact_solver_plugin_h
#define dynamic_contact_contact_solver_plugin_h

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <optional>

namespace DynamicContact
{
  template <int dim>
  class ContactSolver;
  template <int dim>
  struct ContactProblem;

  /**
   * The interface of Solver/Contact solver (a plugin in the way of the laws,
   * doc/extending.md): a way to solve the semismooth Newton systems of a
   * step, with the entries of its own subsection of Solver (named after
   * it: 'condensed' -> Solver/Condensed). An implementation registers with
   * DYNAMIC_CONTACT_REGISTER(ContactSolverPlugin, Class, "name",
   * "description") in source/contact/contact_solvers.cc (which
   * declare_contact_solvers() links into the program); Contact solver =
   * auto chooses between 'condensed' and 'assembled' by their predicted
   * costs (SolverPlan).
   *
   * The object is the parsed parameters, not state of a run: it makes a
   * solver for each mesh (create()).
   */
  class ContactSolverPlugin
  {
  public:
    virtual ~ContactSolverPlugin() = default;

    /** The solver of one mesh for @p problem. */
    virtual std::unique_ptr<ContactSolver<2>>
    create(const ContactProblem<2> &problem) const = 0;
    virtual std::unique_ptr<ContactSolver<3>>
    create(const ContactProblem<3> &problem) const = 0;

    /**
     * A pass of the convexification loop that is probably not its last
     * may take the solver's provisional answer
     * (ContactSolver::solve_provisional()).
     */
    virtual bool
    provisional_passes() const
    {
      return false;
    }

    /**
     * Contact solver = auto: the largest dim times the number of contact
     * nodes for which this solver may be chosen in dimension @p dim, where
     * K0 is factorized over several processes (@p distributed) or not;
     * std::nullopt: no limit.
     */
    virtual std::optional<unsigned int>
    boundary_limit(const unsigned int /*dim*/, const bool /*distributed*/) const
    {
      return std::nullopt;
    }
  };

  /**
   * Declare, in the current subsection of @p prm (Solver), the entry
   * 'Contact solver' (auto or one of the registered solvers) and the
   * subsection of every solver that has entries. Defined in
   * source/contact/contact_solvers.cc, beside the registrations, so that
   * they are part of the program.
   */
  void
  declare_contact_solvers(dealii::ParameterHandler &prm);
} // namespace DynamicContact

#endif
