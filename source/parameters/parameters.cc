#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/gmsh_file.h>
#include <dynamic_contact/base/plugins.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/parameters/parameters.h>

#include "parameter_tools.h"

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

namespace DynamicContact
{
  using namespace ParameterTools;

  namespace Parameters
  {
    // ------------------------------------------------------------ Geometry
    void
    Geometry::declare_parameters(ParameterHandler &prm, const unsigned int dim)
    {
      prm.enter_subsection("Geometry");
      {
        prm.declare_entry(
          "Type",
          "rectangle",
          Patterns::Selection("rectangle|gmsh"),
          "How the body is meshed. 'rectangle': an axis-parallel box from "
          "'Lower left' to 'Upper right' with 'Repetitions' cells per "
          "direction, boundary ids 0/1 at x = min/max, 2/3 at y = min/max, "
          "4/5 at z = min/max. 'gmsh': the coarse mesh in 'Mesh file' (Gmsh "
          "format), with the boundary ids it carries as physical tags.");
        prm.declare_entry("Lower left",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Lower left corner of the rectangle (m), one "
                          "coordinate per dimension.");
        prm.declare_entry("Upper right",
                          dim == 2 ? "2, 0.1" : "2, 0.1, 0.1",
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Upper right corner of the rectangle (m).");
        prm.declare_entry(
          "Repetitions",
          dim == 2 ? "32, 4" : "32, 4, 4",
          Patterns::List(Patterns::Integer(1), dim, dim),
          "Number of cells of the coarse rectangle in each direction.");
        prm.declare_entry("Global refinements",
                          "0",
                          Patterns::Integer(0, 20),
                          "Number of uniform refinements of the coarse mesh.");
        prm.declare_entry(
          "Mesh file",
          "",
          Patterns::Anything(),
          "Gmsh mesh file for Type = gmsh (MSH 2.2 or 4.1, ASCII): "
          "quadrilaterals in 2D, hexahedra in 3D, first order; the number of "
          "a physical group of boundary elements is their boundary id, and "
          "named groups may be named in the Boundary conditions lists. A "
          "relative path is taken relative to the directory of the "
          "parameter file.");
      }
      prm.leave_subsection();
    }

    void
    Geometry::parse_parameters(ParameterHandler  &prm,
                               const unsigned int dim,
                               const std::string &prm_directory)
    {
      prm.enter_subsection("Geometry");
      {
        type       = (prm.get("Type") == "gmsh" ? Type::gmsh : Type::rectangle);
        lower_left = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Lower left")));
        upper_right = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Upper right")));
        repetitions.clear();
        for (const int r : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Repetitions"))))
          repetitions.push_back(static_cast<unsigned int>(r));
        global_refinements = prm.get_integer("Global refinements");
        mesh_file          = prm.get("Mesh file");
      }
      prm.leave_subsection();

      if (type == Type::rectangle)
        for (unsigned int d = 0; d < dim; ++d)
          require(upper_right[d] > lower_left[d],
                  "Geometry/Upper right must exceed Geometry/Lower left in "
                  "every coordinate (coordinate " +
                    std::to_string(d) + ": " + str(lower_left[d]) +
                    " >= " + str(upper_right[d]) + ").");
      else
        {
          require(!mesh_file.empty(),
                  "Geometry/Type = gmsh needs Geometry/Mesh file.");
          if (mesh_file[0] != '/' && !prm_directory.empty())
            mesh_file = prm_directory + "/" + mesh_file;
          std::ifstream in(mesh_file);
          require(static_cast<bool>(in),
                  "Geometry/Mesh file: cannot open the mesh file '" +
                    mesh_file + "'.");
        }
    }

    // ------------------------------------------------------- FiniteElement
    void
    FiniteElement::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Finite element");
      prm.declare_entry("Polynomial degree",
                        "1",
                        Patterns::Integer(1, 4),
                        "Degree of the continuous Lagrange (Q_p) elements. "
                        "The contact integrals on the contact boundary use "
                        "the Gauss-Lobatto rule with p+1 points, whose nodes "
                        "are the element's support points (nodal contact).");
      prm.leave_subsection();
    }

    void
    FiniteElement::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Finite element");
      degree = prm.get_integer("Polynomial degree");
      prm.leave_subsection();
    }

    // -------------------------------------------------- BoundaryConditions
    void
    BoundaryConditions::declare_parameters(ParameterHandler  &prm,
                                           const unsigned int dim)
    {
      // Numbers 0 to 255 or names of Gmsh physical groups: checked by
      // parse_parameters (against the mesh file for names).
      const auto ids = Patterns::List(Patterns::Anything());
      prm.enter_subsection("Boundary conditions");
      {
        prm.declare_entry("Clamped",
                          "0, 1",
                          ids,
                          "Boundary ids where the body is clamped (Gamma_1, "
                          "u = 0). In every list: numbers from 0 to 255 "
                          "or, with Geometry/Type = gmsh, names of physical "
                          "groups of the mesh file (of dimension dim - 1; "
                          "a group's number is its boundary id).");
        prm.declare_entry("Roller",
                          "",
                          ids,
                          "Boundary ids where the normal displacement "
                          "vanishes and the tangential traction is zero.");
        prm.declare_entry("Traction",
                          "3",
                          ids,
                          "Boundary ids where the traction of the subsection "
                          "'Traction function' acts (Gamma_2).");
        prm.declare_entry("Contact",
                          "2",
                          ids,
                          "Boundary ids in contact with the deformable "
                          "foundation (Gamma_3).");
        prm.declare_entry("Free",
                          "",
                          ids,
                          "Boundary ids without load (zero traction).");
        prm.declare_entry(
          "Load quadrature tolerance",
          "1e-6",
          Patterns::Double(0, 1),
          "How accurately the traction and the contact source are integrated "
          "on each face: Gauss rules of degree + 2 points per direction on "
          "1, 2, 4, ... subintervals, until two in a row agree to this "
          "tolerance times the largest load times the face's area (a load "
          "narrower than the cells needs several). 0: one Gauss rule of "
          "degree + 2 points per direction.");
        declare_function(prm,
                         "Traction function",
                         dim,
                         zeros(dim),
                         "Traction f_2(x, t) on the 'Traction' ids (Pa), one "
                         "expression per component separated by ';'.");
        declare_function(
          prm,
          "Contact source",
          dim,
          zeros(dim),
          "An additional traction s(x, t) on the 'Contact' ids (Pa), added to "
          "the foundation's response: sigma nu = s - (p + q) nu - friction. "
          "Zero in physical scenes; manufactured solutions use it.");
      }
      prm.leave_subsection();
    }

    void
    BoundaryConditions::parse_parameters(ParameterHandler  &prm,
                                         const Geometry    &geometry,
                                         const unsigned int dim)
    {
      std::optional<std::map<std::string, types::boundary_id>> names;
      prm.enter_subsection("Boundary conditions");
      load_quadrature_tolerance = prm.get_double("Load quadrature tolerance");
      const std::string text[] = {prm.get("Clamped"),
                                  prm.get("Roller"),
                                  prm.get("Traction"),
                                  prm.get("Contact"),
                                  prm.get("Free")};
      prm.leave_subsection();
      clamped  = parse_ids(text[0], "Clamped", geometry, dim, names);
      roller   = parse_ids(text[1], "Roller", geometry, dim, names);
      traction = parse_ids(text[2], "Traction", geometry, dim, names);
      contact  = parse_ids(text[3], "Contact", geometry, dim, names);
      free     = parse_ids(text[4], "Free", geometry, dim, names);

      std::map<types::boundary_id, std::string> seen;
      for (const auto &[id, list] : all_ids())
        {
          const auto it = seen.find(id);
          require(it == seen.end() || it->second == list,
                  "Boundary conditions: boundary id " + std::to_string(id) +
                    " is used twice, in 'Boundary conditions/" +
                    (it == seen.end() ? "" : it->second) +
                    "' and in 'Boundary conditions/" + list + "'.");
          require(it == seen.end(),
                  "Boundary conditions/" + list + ": boundary id " +
                    std::to_string(id) + " is listed twice.");
          seen[id] = list;
        }
    }

    std::vector<std::pair<types::boundary_id, std::string>>
    BoundaryConditions::all_ids() const
    {
      std::vector<std::pair<types::boundary_id, std::string>> result;
      for (const auto &[list, name] : {std::make_pair(&clamped, "Clamped"),
                                       std::make_pair(&roller, "Roller"),
                                       std::make_pair(&traction, "Traction"),
                                       std::make_pair(&contact, "Contact"),
                                       std::make_pair(&free, "Free")})
        for (const auto id : *list)
          result.emplace_back(id, name);
      return result;
    }

    // ------------------------------------------------------------ Material
    void
    Material::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      {
        prm.declare_entry("Density",
                          "1000",
                          Patterns::Double(),
                          "Mass density rho (kg/m^3), > 0.");
        prm.declare_entry("Young modulus",
                          "1e11",
                          Patterns::Double(),
                          "Young's modulus E of the elasticity tensor (Pa), "
                          "> 0.");
        prm.declare_entry("Poisson ratio",
                          "0.3",
                          Patterns::Double(),
                          "Poisson's ratio kappa, in (-1, 0.5).");
        prm.declare_entry(
          "Plane model",
          "plane strain",
          Patterns::Selection("plane strain|plane stress"),
          "2D only. 'plane strain' uses the Lame constants "
          "lambda = E kappa/((1+kappa)(1-2 kappa)), 2 mu = E/(1+kappa): this "
          "is eq. (87) of the paper as written (the paper calls it plane "
          "stress). 'plane stress' uses lambda* = 2 lambda mu/(lambda + 2 "
          "mu) instead of lambda, for the elasticity and the viscosity "
          "tensor alike. Ignored in 3D.");
        prm.declare_entry("Viscosity lambda",
                          "0",
                          Patterns::Double(),
                          "First constant of the isotropic viscosity tensor "
                          "C (Pa s): C eps = lambda_v tr(eps) I + 2 mu_v "
                          "eps. The paper's example has C = 0.");
        prm.declare_entry("Viscosity mu",
                          "0",
                          Patterns::Double(),
                          "Second constant mu_v of the viscosity tensor C "
                          "(Pa s), >= 0.");
      }
      prm.leave_subsection();
    }

    void
    Material::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      density       = prm.get_double("Density");
      young_modulus = prm.get_double("Young modulus");
      poisson_ratio = prm.get_double("Poisson ratio");
      plane_model =
        (prm.get("Plane model") == "plane stress" ? PlaneModel::plane_stress :
                                                    PlaneModel::plane_strain);
      viscosity_lambda = prm.get_double("Viscosity lambda");
      viscosity_mu     = prm.get_double("Viscosity mu");
      prm.leave_subsection();

      require(std::isfinite(density) && density > 0,
              "Material/Density must be positive, got " + str(density) + ".");
      require(std::isfinite(young_modulus) && young_modulus > 0,
              "Material/Young modulus must be positive, got " +
                str(young_modulus) + ".");
      require(std::isfinite(poisson_ratio) && poisson_ratio > -1 &&
                poisson_ratio < 0.5,
              "Material/Poisson ratio must lie in (-1, 0.5), got " +
                str(poisson_ratio) + ".");
      require(std::isfinite(viscosity_mu) && viscosity_mu >= 0,
              "Material/Viscosity mu must be >= 0, got " + str(viscosity_mu) +
                ".");
      require(std::isfinite(viscosity_lambda) &&
                3 * viscosity_lambda + 2 * viscosity_mu >= 0,
              "Material/Viscosity lambda: the viscosity tensor must be "
              "positive semi-definite (3 lambda_v + 2 mu_v >= 0), got "
              "lambda_v = " +
                str(viscosity_lambda) + ".");
    }

    // ---------------------------------------------------------- Foundation
    void
    Foundation::declare_parameters(ParameterHandler  &prm,
                                   const unsigned int dim)
    {
      prm.enter_subsection("Foundation");
      {
        DynamicContact::Foundation::declare_parameters(prm);
        declare_function(prm,
                         "Initial gap",
                         dim,
                         "0",
                         "Initial gap g0(x) >= 0 between Gamma_3 and the "
                         "foundation (m): the laws act on u_nu - g0.");
      }
      prm.leave_subsection();
    }

    void
    Foundation::parse_parameters(ParameterHandler &prm)
    {
      const ScopedSubsection section(prm, "Foundation");
      law = std::make_shared<const DynamicContact::Foundation>(
        DynamicContact::Foundation::create(prm));
    }

    // ------------------------------------------------------------ Friction
    namespace
    {
      /**
       * Friction: the stopping rule, relaxation and cap of the
       * convexification loop.
       */
      void
      declare_convexification_loop(ParameterHandler &prm)
      {
        prm.declare_entry("Convexification tolerance",
                          "1e-6",
                          Patterns::Double(),
                          "epsilon_conv of the stopping rule (85).");
        prm.declare_entry(
          "Coefficient tolerance",
          "1e-6",
          Patterns::Double(),
          "The loop also stops only when max_i |mu_i - mu(|w_tau,i|)| is "
          "below this, so that the law holds node-wise (doc/theory.md "
          "section 4).");
        prm.declare_entry("Relaxation",
                          "1",
                          Patterns::Double(),
                          "Relaxation factor theta in (0, 1] of the frozen "
                          "coefficients: mu_i <- (1-theta) mu_i + theta "
                          "mu(|w_tau,i|).");
        prm.declare_entry("Maximum convexification iterations",
                          "50",
                          Patterns::Integer(1),
                          "Cap on the convexification loop; a step that "
                          "reaches it has failed: it is retried with half "
                          "the time step (see Time/Minimum time step). At "
                          "the minimum time step it is kept, with a warning "
                          "and convexification_converged = 0.");
      }


      /**
       * Friction: how a slip-rate dependent coefficient enters the Newton
       * iteration, and the diagnostics of the uniqueness of its solutions.
       */
      void
      declare_slip_rate_dependence(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Linearization",
          "frozen",
          Patterns::Selection("frozen|coupled"),
          "How a slip-rate dependent coefficient mu(|w_tau|) enters the "
          "semismooth Newton iteration of the convexification loop "
          "(doc/theory.md sections 4 and 5.1). 'frozen': every pass freezes "
          "mu_i (the paper's algorithm). 'coupled': the first pass takes "
          "mu(|w_tau|) of the iterate itself and its derivative into the "
          "Newton linearization (the weakening limited to half the "
          "body's tangential stiffness at the node) and lands on a fixed "
          "point of the loop, which the next, frozen, pass confirms: most "
          "steps take two passes and, on the 3D rail, half the Newton "
          "iterations. But it may end at another point than the frozen "
          "loop, chosen by details as small as round-off, so that its "
          "answers depend on the contact solver and the number of processes "
          "(most steps of the paper's scenes have several solutions: Count "
          "solutions). A "
          "coupled pass that does not converge sends the step back to its "
          "start, for the frozen loop (counted in coupled_fallbacks).");
        prm.declare_entry(
          "Uniqueness monitor",
          "auto",
          Patterns::Selection("auto|always|never"),
          "When a slip-rate dependent law's uniqueness measures are "
          "evaluated after a step (doc/theory.md section 5.2; the columns "
          "uniqueness_bound, uniqueness_certificate and contraction_factor "
          "of time_series.csv, -1 where not evaluated; a bound certified "
          "below 1 proves one solution, above 1 nothing): 'auto' where the condensed contact solver "
          "solves the step (from its compliance table, a few ms), 'always' "
          "(with the assembled solver each costs a few dozen solves with K0 "
          "by CG), 'never' (no columns). Time/Cut back where not unique "
          "needs them at every step.");
        prm.declare_entry(
          "Count solutions",
          "false",
          Patterns::Bool(),
          "With a slip-rate dependent law, a diagnostic of several times "
          "the cost: true solves every step again from four starts (the "
          "last step's velocity, all of Gamma_3 sticking, all of it slipping "
          "fast, and the coupled linearization), each with the frozen loop "
          "to max |mu_i - mu(|w_tau,i|)| <= Coefficient tolerance/100, and "
          "counts the distinct "
          "solutions they reach (doc/theory.md section 5.3; the columns "
          "solutions, solution_spread and failed_starts of "
          "time_series.csv). A count of 1 says the starts agree, not that "
          "the solution is unique; 2 or more proves several. The run's "
          "answers are those of its own loop, unchanged.");
      }
    } // namespace


    void
    Friction::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Friction");
      {
        FrictionLaw::declare_parameters(prm);
        prm.declare_entry(
          "Maximum slip rate",
          "auto",
          Patterns::Anything(),
          "The largest slip rate (m/s) of the window [0, Maximum slip rate] "
          "on which mu(s) is checked at start-up (finite, >= 0, not "
          "increasing unless Velocity strengthening = allow) and its "
          "one-sided Lipschitz constant is sampled; the run also checks every "
          "value it uses. 'auto': the P-wave speed of the body, sqrt((lambda "
          "+ 2 mu)/rho), which the velocities of a linearly elastic body stay "
          "far below (its strains are about v/c), so that the window scales "
          "with the scene in any consistent units.");
        prm.declare_entry(
          "Slip length",
          "0",
          Patterns::Double(),
          "L (m): the friction coefficient becomes a state mu~ of each node "
          "of Gamma_3 that follows the law mu(s) over the slip L, d mu~/dt "
          "= -((s + v*)/L)(mu~ - mu(s)) (a regularization of the slip-rate "
          "law as in dynamic-rupture codes, doc/theory.md section 1.6): the "
          "coefficient no longer drops at once with the slip rate; on the "
          "paper's small scene the friction force then converges as k and h "
          "fall, where with the law itself it does not in k (measured: "
          "doc/accuracy.md section 6). The state is carried from step to "
          "step, through remeshing and in checkpoints; with Time/Scheme = "
          "backward Euler or trapezoidal. 0: no state, mu = mu(s) (the "
          "paper's law).");
        prm.declare_entry(
          "Reference slip rate",
          "0",
          Patterns::Double(),
          "v* (m/s) of Slip length: the state relaxes at the rate (s + "
          "v*)/L, so that with v* > 0 it also returns to mu(0) while a node "
          "sticks; 0: it stays as it is while the node sticks.");
        declare_convexification_loop(prm);
        declare_slip_rate_dependence(prm);
        prm.declare_entry(
          "Complementarity constant",
          "0",
          Patterns::Double(),
          "c_t of the complementarity function of friction (Pa/m), a "
          "stiffness per unit area like E/h: c_t k m_i w_tau is a nodal "
          "force. 0 chooses E/h with h the smallest cell size.");
        prm.declare_entry(
          "Velocity strengthening",
          "refuse",
          Patterns::Selection("refuse|allow"),
          "A law whose mu increases with the slip rate somewhere on [0, "
          "Maximum slip rate] (velocity strengthening, e.g. 1 - 0.5 "
          "exp(-2000 s)): 'refuse' stops with an error before the run, "
          "since the convexification loop does not converge for it (a node "
          "alternates between stick and slip; measured in the README, "
          "'What can go wrong'); 'allow' runs it, and steps whose loop "
          "reaches its cap at the minimum time step are kept and reported "
          "(run_status 'completed with warnings').");
      }
      prm.leave_subsection();
    }

    void
    Friction::parse_parameters(ParameterHandler &prm, const Material &material)
    {
      {
        const ScopedSubsection section(prm, "Friction");
        std::unique_ptr<FrictionLaw> new_law = FrictionLaw::create(prm);
        law_name                             = prm.get("Law");
        const std::string           window   = prm.get("Maximum slip rate");
        const std::optional<double> s_max =
          positive_or_auto(window,
                           "Friction/Maximum slip rate: '" + window +
                             "' is neither a positive number nor 'auto'.");
        maximum_slip_rate = s_max ? *s_max : material.p_wave_speed();
        if (new_law)
          new_law->set_slip_rate_window(maximum_slip_rate);
        law                       = std::move(new_law);
        const double L            = prm.get_double("Slip length");
        const double v_ref        = prm.get_double("Reference slip rate");
        require(std::isfinite(L) && L >= 0,
                "Friction/Slip length must be a finite number >= 0 (0: no "
                "slip length), got " +
                  str(L) + ".");
        require(std::isfinite(v_ref) && v_ref >= 0,
                "Friction/Reference slip rate must be a finite number >= 0, "
                "got " +
                  str(v_ref) + ".");
        slip_length               = SlipLength(L, v_ref);
        convexification_tolerance = prm.get_double("Convexification tolerance");
        coefficient_tolerance     = prm.get_double("Coefficient tolerance");
        relaxation                = prm.get_double("Relaxation");
        max_convexification_iterations =
          prm.get_integer("Maximum convexification iterations");
        coupled_linearization     = prm.get("Linearization") == "coupled";
        const std::string monitor = prm.get("Uniqueness monitor");
        uniqueness_monitor =
          monitor == "always" ? Monitor::always :
          monitor == "never"  ? Monitor::never :
                                Monitor::automatic;
        count_solutions          = prm.get_bool("Count solutions");
        complementarity_constant = prm.get_double("Complementarity constant");
        allow_velocity_strengthening =
          prm.get("Velocity strengthening") == "allow";
      }

      require(std::isfinite(convexification_tolerance) &&
                convexification_tolerance > 0,
              "Friction/Convexification tolerance must be positive.");
      require(std::isfinite(coefficient_tolerance) && coefficient_tolerance > 0,
              "Friction/Coefficient tolerance must be positive.");
      require(std::isfinite(relaxation) && relaxation > 0 && relaxation <= 1,
              "Friction/Relaxation must lie in (0, 1], got " + str(relaxation) +
                ".");
      require(std::isfinite(complementarity_constant) &&
                complementarity_constant >= 0,
              "Friction/Complementarity constant must be >= 0 (0: automatic).");
    }

    // ------------------------------------------------------ MeshRefinement
    void
    MeshRefinement::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh refinement");
      {
        declare_refinement_strategies(prm);
        prm.declare_entry("Refine every",
                          "4",
                          Patterns::Integer(1),
                          "Adapt the mesh before every N-th step.");
        prm.declare_entry("Minimum level",
                          "0",
                          Patterns::Integer(0, 30),
                          "Coarsest level (0: the coarse mesh); raised to "
                          "Geometry/Global refinements if below it.");
        prm.declare_entry("Maximum level",
                          "3",
                          Patterns::Integer(0, 30),
                          "Finest level (0: the coarse mesh).");
        prm.declare_entry("Cell budget",
                          "0",
                          Patterns::Integer(0),
                          "Most active cells allowed (0: no limit): above it "
                          "the finest level of this adaptation is lowered "
                          "until the mesh fits.");
      }
      prm.leave_subsection();
    }

    void
    MeshRefinement::parse_parameters(ParameterHandler  &prm,
                                     const unsigned int global_refinements)
    {
      prm.enter_subsection("Mesh refinement");
      {
        strategies = Utilities::split_string_list(prm.get("Strategy"));
        require(!(std::find(strategies.begin(), strategies.end(), "none") !=
                    strategies.end() &&
                  strategies.size() > 1),
                "Mesh refinement/Strategy: 'none' cannot be combined with "
                "other strategies.");
        if (strategies.size() == 1 && strategies[0] == "none")
          strategies.clear();
        refine_every  = prm.get_integer("Refine every");
        minimum_level = std::max<unsigned int>(prm.get_integer("Minimum level"),
                                               global_refinements);
        maximum_level = prm.get_integer("Maximum level");
        cell_budget   = prm.get_integer("Cell budget");
      }
      prm.leave_subsection();
      if (enabled())
        require(maximum_level >= minimum_level,
                "Mesh refinement/Maximum level (" +
                  std::to_string(maximum_level) +
                  ") must not be below the minimum level (" +
                  std::to_string(minimum_level) +
                  ", at least Geometry/Global refinements).");
    }

  } // namespace Parameters
} // namespace DynamicContact
