#ifndef dynamic_contact_parameters_h
#define dynamic_contact_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>

#include <dynamic_contact/base/contact_solver_plugin.h>
#include <dynamic_contact/base/preconditioner_plugin.h>
#include <dynamic_contact/base/step_scheme.h>
#include <dynamic_contact/base/time_scheme.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/laws/slip_length.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  class Foundation;
  class FrictionLaw;

  /**
   * The parameters of a scene, one struct per subsection of the parameter
   * file. Every struct declares its entries (default, pattern, documentation)
   * and parses them, checking what can be checked without a mesh. Function
   * expressions are not stored here: they are parsed by the Scene, which
   * owns the functions (they need the dimension).
   *
   * Errors for users are thrown as ExcMessage naming the entry as
   * "Section/Entry", so that the message leads straight to the line to fix.
   */
  namespace Parameters
  {
    struct Geometry
    {
      enum class Type
      {
        rectangle,
        gmsh
      };
      Type                      type;
      std::vector<double>       lower_left;
      std::vector<double>       upper_right;
      std::vector<unsigned int> repetitions;
      unsigned int              global_refinements;
      std::string mesh_file; // resolved against the prm's directory

      static void
      declare_parameters(ParameterHandler &prm, const unsigned int dim);
      void
      parse_parameters(ParameterHandler  &prm,
                       const unsigned int dim,
                       const std::string &prm_directory);
    };

    struct FiniteElement
    {
      unsigned int degree;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * Boundary conditions by boundary id. Every boundary id of the mesh must
     * appear in exactly one list (checked against the mesh by the Scene).
     */
    struct BoundaryConditions
    {
      std::vector<types::boundary_id> clamped;  // Gamma_1: u = 0
      std::vector<types::boundary_id> roller;   // u . n = 0, tangential free
      std::vector<types::boundary_id> traction; // Gamma_2: sigma n = f_2
      std::vector<types::boundary_id> contact;  // Gamma_3: foundation
      std::vector<types::boundary_id> free;     // sigma n = 0
      /** Of the surface loads' quadrature (FaceLoadQuadrature). */
      double load_quadrature_tolerance = 1e-6;

      static void
      declare_parameters(ParameterHandler &prm, const unsigned int dim);
      /**
       * Each list holds boundary ids (0 to 255) or names of physical groups
       * of the Gmsh mesh of @p geometry (its $PhysicalNames of dimension
       * dim - 1), resolved to their tags here; an unknown name is an error
       * listing the names the mesh has.
       */
      void
      parse_parameters(ParameterHandler  &prm,
                       const Geometry    &geometry,
                       const unsigned int dim);

      /** All ids named in any list, with the name of the list. */
      std::vector<std::pair<types::boundary_id, std::string>>
      all_ids() const;
    };

    /**
     * The constants of the Kelvin-Voigt law (MaterialConstants, with the
     * law in material.h), read from the subsection Material.
     */
    struct Material : MaterialConstants
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Foundation
    {
      /**
       * The normal compliance and damped response the entries choose
       * (foundation.h; each law parses its own subsection).
       */
      std::shared_ptr<const DynamicContact::Foundation> law;

      static void
      declare_parameters(ParameterHandler &prm, const unsigned int dim);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Friction
    {
      /**
       * The law Friction/Law names, with the parameters of its own
       * subsection (friction_law.h); nullptr for 'none'.
       */
      std::shared_ptr<const FrictionLaw> law;
      std::string                        law_name;
      /**
       * The slip rates [0, maximum_slip_rate] on which mu is checked (the
       * entry, or for 'auto' the P-wave speed of the material).
       */
      double maximum_slip_rate;
      /**
       * Friction/Slip length and Reference slip rate: the coefficient a
       * state that relaxes towards mu(s) over a slip length (inactive for
       * L = 0, the default: the law of eq. (18) itself).
       */
      SlipLength slip_length;

      // Convexification loop (doc/theory.md section 4).
      double       convexification_tolerance; // epsilon_conv, eq. (85)
      double       coefficient_tolerance;     // max_i |mu_i - mu(|w_tau,i|)|
      double       relaxation;
      unsigned int max_convexification_iterations;
      /**
       * Friction/Linearization = coupled: the first pass of the loop
       * linearizes mu(|w_tau|) inside Newton's method (doc/theory.md
       * section 5.1); frozen: every pass freezes it (the paper's loop).
       */
      bool coupled_linearization;
      /**
       * Friction/Uniqueness monitor: when the uniqueness measures of a step
       * are evaluated (doc/theory.md section 5.2): auto with the condensed
       * solver (from its compliance table, cheap), always (with the
       * assembled one they cost solves with K0), never.
       */
      enum class Monitor
      {
        automatic,
        always,
        never
      };
      Monitor uniqueness_monitor;
      /**
       * Friction/Count solutions: solve every step again from several
       * starts and count the distinct solutions (doc/theory.md section
       * 5.3; a diagnostic: several times the cost).
       */
      bool count_solutions;

      // Complementarity constant c_t; 0 means "E/h".
      double complementarity_constant;

      // Run a law whose mu increases with s (README, "What can go wrong").
      bool allow_velocity_strengthening;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm, const Material &material);

      bool
      enabled() const
      {
        return law != nullptr;
      }
    };

    /**
     * Adaptive refinement (issue: the mesh follows the moving load and the
     * contact zone). Levels are those of deal.II: 0 for the cells of the
     * coarse mesh (Geometry/Repetitions), + Geometry/Global refinements.
     */
    struct MeshRefinement
    {
      /** The strategies of the list Strategy (refinement_strategy.h). */
      std::vector<std::string> strategies;
      unsigned int             refine_every;
      unsigned int             minimum_level;
      unsigned int             maximum_level;
      unsigned int             cell_budget;

      bool
      enabled() const
      {
        return !strategies.empty();
      }

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler  &prm,
                       const unsigned int global_refinements);
    };

    struct Time
    {
      double end_time;
      double time_step;
      double minimum_time_step;
      /**
       * The scheme Time/Scheme names, with the parameters of its own
       * subsection (step_scheme.h; the implementations in
       * source/time/step_schemes.cc), and that name.
       */
      std::shared_ptr<const StepScheme> scheme;
      std::string                       scheme_name;
      /**
       * Adaptive time stepping from a local error estimate (doc/theory.md
       * section 2.5): the tolerance, and the largest step (the smallest is
       * minimum_time_step).
       */
      bool   adaptive;
      double adaptive_tolerance;
      double maximum_time_step;
      /**
       * Time/Cut back where not unique: a step whose contraction factor is
       * 1 or more is retried with half the time step (doc/theory.md
       * section 5.2).
       */
      bool cut_back_where_not_unique;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Solver
    {
      enum class LinearSolver
      {
        automatic,
        direct,
        iterative
      };
      /** Solver/Contact solver: 'auto' or a registered solver's name. */
      std::string contact_solver = "auto";
      /**
       * Every registered contact solver with the entries of its
       * subsection (Solver/Condensed, ...), by name: Contact solver = auto
       * may choose either.
       */
      std::map<std::string, std::shared_ptr<const ContactSolverPlugin>>
        contact_solvers;

      /** The contact solver @p name (one of contact_solvers). */
      const ContactSolverPlugin &
      contact_solver_plugin(const std::string &name) const;
      /**
       * The fewest DoFs of the initial mesh per process: a run started on
       * more processes than DoFs / this takes part on that many only (the
       * first ones; at least one). 0: every process takes part.
       */
      unsigned int min_dofs_per_process;
      bool         line_search;
      double       newton_tolerance;
      unsigned int max_newton_iterations;
      LinearSolver linear_solver;
      std::string  direct_solver_package;
      double       linear_tolerance;
      unsigned int max_linear_iterations;
      /**
       * The iterative solver's preconditioner (Solver/Preconditioner): auto
       * or one of preconditioners; in the parameters a solver works with
       * (SolverPlan::solver_parameters()) never auto.
       */
      std::string preconditioner = "auto";
      /**
       * The registered preconditioners with the entries of their
       * subsections (Solver/AMG, ...), by name.
       */
      std::map<std::string, std::shared_ptr<const PreconditionerPlugin>>
        preconditioners;

      /** The preconditioner @p name (one of preconditioners). */
      const PreconditionerPlugin &
      preconditioner_plugin(const std::string &name) const;
      /**
       * Bytes one process may use (Solver/Memory per process);
       * std::nullopt for 'auto' (measured when the run starts).
       */
      std::optional<double> memory_per_process;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Checkpoint
    {
      unsigned int every;
      unsigned int keep;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Output
    {
      std::string         directory;
      unsigned int        output_every;
      bool                write_vtu;
      unsigned int        vtu_every;
      unsigned int        vtu_subdivisions;
      std::vector<double> output_times;
      unsigned int        progress_every;
      bool                print_timings;
      bool                print_iteration_counts;
      bool                solver_details;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace Parameters


  /**
   * All parameters of a run. The function-valued entries (loads, initial
   * conditions, gap) are declared here so that --print-parameters lists them,
   * and parsed by the Scene.
   */
  struct RunParameters
  {
    unsigned int                   dimension;
    std::string                    parameter_file;
    Parameters::Geometry           geometry;
    Parameters::FiniteElement      finite_element;
    Parameters::BoundaryConditions boundary_conditions;
    Parameters::Material           material;
    Parameters::Foundation         foundation;
    Parameters::Friction           friction;
    Parameters::MeshRefinement     mesh_refinement;
    Parameters::Time               time;
    Parameters::Solver             solver;
    Parameters::Checkpoint         checkpoint;
    Parameters::Output             output;

    /** Declare every entry for a problem in @p dim dimensions. */
    static void
    declare_parameters(ParameterHandler &prm, const unsigned int dim);

    void
    parse_parameters(ParameterHandler &prm);
  };


  /**
   * Declare Mesh refinement/Strategy and the subsection of every registered
   * refinement strategy (inside subsection Mesh refinement; defined with the
   * strategies, in refinement_strategy.cc).
   */
  void
  declare_refinement_strategies(ParameterHandler &prm);

  /**
   * The entries of the flat layout of earlier versions that moved when each
   * law and refinement strategy got a subsection of its own: old path ->
   * new path ("Friction/Decay rate" -> "Friction/Exponential/Decay rate").
   * The one table: the errors for old entries name the new place from it,
   * and scripts/update-prm reads it (--print-parameters=moved).
   */
  const std::map<std::string, std::string> &
  moved_entries();

  /**
   * The parameters of earlier versions that were removed: path -> why and
   * what to do instead. A parameter file that sets one gets an error that
   * says so.
   */
  const std::map<std::string, std::string> &
  removed_entries();

  /** The formats of a parameter file (deal.II's ParameterHandler). */
  enum class ParameterFormat
  {
    prm,
    json,
    xml
  };

  /**
   * The format of @p parameter_file by its extension: ".json" JSON, ".xml"
   * XML (as ParameterHandler::print_parameters writes them), anything else
   * the PRM text format.
   */
  ParameterFormat
  parameter_format(const std::string &parameter_file);

  /**
   * Read a parameter file (PRM, JSON or XML: parameter_format()) in two
   * passes: first the Dimension (everything else ignored), then every
   * entry, declared for that dimension, strictly: an unknown or malformed
   * entry is an error naming the file and (PRM) the line.
   * Each override "Section/Subsection/Entry=value" is applied after the file.
   * The ParameterHandler @p prm is left holding the values read.
   */
  RunParameters
  read_parameters(const std::string              &parameter_file,
                  const std::vector<std::string> &overrides,
                  ParameterHandler               &prm);

  /** Return the dimension named by a parameter file (its "set Dimension"). */
  unsigned int
  read_dimension(const std::string              &parameter_file,
                 const std::vector<std::string> &overrides);

  /**
   * Apply one override "Section/Subsection/Entry=value" to @p prm; throws an
   * ExcMessage naming the entry if it does not exist or the value does not
   * match its pattern.
   */
  void
  apply_override(ParameterHandler &prm, const std::string &assignment);
} // namespace DynamicContact

#endif
