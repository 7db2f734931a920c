#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/error_messages.h>
#include <dynamic_contact/foundation.h>
#include <dynamic_contact/friction_law.h>
#include <dynamic_contact/gmsh_file.h>
#include <dynamic_contact/plugins.h>
#include <dynamic_contact/parameters.h>

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
  namespace
  {
    std::string
    zeros(const unsigned int n)
    {
      std::string s = "0";
      for (unsigned int i = 1; i < n; ++i)
        s += "; 0";
      return s;
    }

    void
    require(const bool condition, const std::string &message);

    /**
     * A list of boundary ids (Boundary conditions/@p list): numbers 0 to
     * 255, or names of physical groups of the Gmsh mesh (@p names, read from
     * @p mesh_file when the first name is met).
     */
    std::vector<types::boundary_id>
    parse_ids(const std::string &                         text,
              const std::string &                         list,
              const Parameters::Geometry &                geometry,
              const unsigned int                          dim,
              std::optional<std::map<std::string, types::boundary_id>> &names)
    {
      std::vector<types::boundary_id> ids;
      for (const auto &item : Utilities::split_string_list(text))
        {
          const std::string entry = "Boundary conditions/" + list;
          if (!item.empty() &&
              item.find_first_not_of("0123456789") == std::string::npos)
            {
              const long id = item.size() > 3 ? 256 : std::stol(item);
              require(id <= 255,
                      entry + ": boundary id " + item +
                        " is out of range (0 to 255).");
              ids.push_back(static_cast<types::boundary_id>(id));
              continue;
            }
          require(!item.empty(), entry + " = '" + text +
                                   "': an empty item in the list.");
          require(geometry.type == Parameters::Geometry::Type::gmsh,
                  entry + ": '" + item +
                    "' is not a boundary id (a number from 0 to 255); names "
                    "of physical groups need Geometry/Type = gmsh (the "
                    "rectangle's ids are 0/1 at x = min/max, 2/3 at y = "
                    "min/max, 4/5 at z = min/max).");
          if (!names)
            {
              // A mesh the program cannot use is the first thing to say.
              const GmshFileInfo info = scan_gmsh_file(geometry.mesh_file);
              check_gmsh_cells(info, geometry.mesh_file, dim);
              names = gmsh_boundary_names(info, dim);
            }
          const auto found = names->find(item);
          if (found == names->end())
            {
              std::string known;
              for (const auto &[name, id] : *names)
                known += (known.empty() ? "" : ", ") + ("'" + name + "'") +
                         " (" + std::to_string(id) + ")";
              require(false,
                      entry + ": '" + item +
                        "' is neither a boundary id nor the name of a "
                        "physical group of dimension " +
                        std::to_string(dim - 1) + " in Geometry/Mesh file '" +
                        geometry.mesh_file + "' (" +
                        (known.empty() ? std::string("it names none") :
                                         "its names: " + known) +
                        ").");
            }
          ids.push_back(found->second);
        }
      return ids;
    }

    void
    require(const bool condition, const std::string &message)
    {
      AssertThrow(condition, ExcMessage(message));
    }

    /**
     * Declare a subsection @p name holding a function of space and time in
     * the format of Functions::ParsedFunction (entries "Function constants",
     * "Function expression", "Variable names").
     */
    void
    declare_function(ParameterHandler & prm,
                     const std::string &name,
                     const unsigned int dim,
                     const std::string &default_expression,
                     const std::string &documentation)
    {
      prm.enter_subsection(name);
      prm.declare_entry("Function constants",
                        "",
                        Patterns::Anything(),
                        "Constants used in the expression, as name=value "
                        "pairs separated by commas, e.g. 'F=1e10, c=2'.");
      prm.declare_entry("Function expression",
                        default_expression,
                        Patterns::Anything(),
                        documentation);
      prm.declare_entry("Variable names",
                        dim == 2 ? "x,y,t" : "x,y,z,t",
                        Patterns::Anything(),
                        "Names of the space coordinates and of time in the "
                        "expression.");
      prm.leave_subsection();
    }

    std::string
    str(const double x)
    {
      std::ostringstream s;
      s << x;
      return s.str();
    }
  } // namespace

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
    Geometry::parse_parameters(ParameterHandler & prm,
                               const unsigned int dim,
                               const std::string &prm_directory)
    {
      prm.enter_subsection("Geometry");
      {
        type = (prm.get("Type") == "gmsh" ? Type::gmsh : Type::rectangle);
        lower_left  = Utilities::string_to_double(
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
    BoundaryConditions::declare_parameters(ParameterHandler & prm,
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
    BoundaryConditions::parse_parameters(ParameterHandler &prm,
                                         const Geometry &  geometry,
                                         const unsigned int dim)
    {
      std::optional<std::map<std::string, types::boundary_id>> names;
      prm.enter_subsection("Boundary conditions");
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
      for (const auto &[list, name] :
           {std::make_pair(&clamped, "Clamped"),
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
      density          = prm.get_double("Density");
      young_modulus    = prm.get_double("Young modulus");
      poisson_ratio    = prm.get_double("Poisson ratio");
      plane_model      = (prm.get("Plane model") == "plane stress" ?
                            PlaneModel::plane_stress :
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
    Foundation::declare_parameters(ParameterHandler &prm,
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
    void
    Friction::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Friction");
      {
        FrictionLaw::declare_parameters(prm);
        prm.declare_entry(
          "Maximum slip rate",
          "100",
          Patterns::Double(),
          "Slip rates on which mu(s) >= 0 and its one-sided Lipschitz "
          "constant are checked at start-up (m/s); the run also checks every "
          "value it uses.");
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
        prm.declare_entry(
          "Acceleration depth",
          "0",
          Patterns::Integer(0, 20),
          "Anderson acceleration of the convexification loop's fixed point "
          "mu = mu(|w_tau(mu)|): the next frozen coefficients combine the "
          "last this many passes (with the relaxation above as mixing "
          "factor); 0: the relaxed fixed-point iteration alone.");
        prm.declare_entry("Maximum convexification iterations",
                          "50",
                          Patterns::Integer(1),
                          "Cap on the convexification loop; a step that "
                          "reaches it has failed: it is retried with half "
                          "the time step (see Time/Minimum time step). At "
                          "the minimum time step it is kept, with a warning "
                          "and convexification_converged = 0.");
        prm.declare_entry(
          "Complementarity constant",
          "0",
          Patterns::Double(),
          "c_t of the complementarity function of friction (Pa s/m^2 ... "
          "scaled like E/h). 0 chooses E/h with h the smallest cell size.");
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
    Friction::parse_parameters(ParameterHandler &prm)
    {
      {
        const ScopedSubsection section(prm, "Friction");
        law      = FrictionLaw::create(prm);
        law_name = prm.get("Law");
        maximum_slip_rate    = prm.get_double("Maximum slip rate");
        convexification_tolerance =
          prm.get_double("Convexification tolerance");
        coefficient_tolerance = prm.get_double("Coefficient tolerance");
        relaxation            = prm.get_double("Relaxation");
        acceleration_depth    = prm.get_integer("Acceleration depth");
        max_convexification_iterations =
          prm.get_integer("Maximum convexification iterations");
        complementarity_constant = prm.get_double("Complementarity constant");
        allow_velocity_strengthening =
          prm.get("Velocity strengthening") == "allow";
      }

      require(std::isfinite(maximum_slip_rate) && maximum_slip_rate > 0,
              "Friction/Maximum slip rate must be positive.");
      require(std::isfinite(convexification_tolerance) &&
                convexification_tolerance > 0,
              "Friction/Convexification tolerance must be positive.");
      require(std::isfinite(coefficient_tolerance) &&
                coefficient_tolerance > 0,
              "Friction/Coefficient tolerance must be positive.");
      require(std::isfinite(relaxation) && relaxation > 0 && relaxation <= 1,
              "Friction/Relaxation must lie in (0, 1], got " +
                str(relaxation) + ".");
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
    MeshRefinement::parse_parameters(ParameterHandler & prm,
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
        refine_every     = prm.get_integer("Refine every");
        minimum_level    = std::max<unsigned int>(prm.get_integer("Minimum level"),
                                               global_refinements);
        maximum_level    = prm.get_integer("Maximum level");
        cell_budget      = prm.get_integer("Cell budget");
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

    // ---------------------------------------------------------------- Time
    void
    Time::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      prm.declare_entry("End time",
                        "1",
                        Patterns::Double(),
                        "Final time T (s), > 0.");
      prm.declare_entry("Time step",
                        "0.0078125",
                        Patterns::Double(),
                        "Time step k (s), > 0. If it does not divide the "
                        "end time, the last step is shortened to end at T.");
      prm.declare_entry(
        "Minimum time step",
        "0",
        Patterns::Double(0),
        "A step the solver cannot solve is retried with half the time step "
        "(again and again, down to this; 0: Time step/1024), and the time "
        "step grows back (doubling after three good steps) to Time step. A "
        "step that fails even at the minimum stops the run, the last good "
        "state written. Set it equal to Time step for no cut-back.");
      prm.declare_entry(
        "Scheme",
        "backward Euler",
        Patterns::Selection("backward Euler|trapezoidal|bathe"),
        "'backward Euler': the paper's scheme (eqs. (52)-(54)), first order. "
        "'trapezoidal': second order, u_n = u_{n-1} + k (w_n + w_{n-1})/2, "
        "the equation of motion at the midpoint, the compliance force the "
        "discrete gradient (Pi(u_n) - Pi(u_{n-1}))/(u_n - u_{n-1}), damping "
        "and friction on (w_n + w_{n-1})/2: energy-consistent (no numerical "
        "dissipation; the balance of doc/theory.md section 6 still holds "
        "exactly, with only the physical dissipation). "
        "'bathe': the Bathe composite scheme, second order with strong "
        "high-frequency dissipation (spectral radius 0 at infinity, like "
        "backward Euler, but little dissipation of the resolved modes): a "
        "trapezoidal sub-step over k/2, then the three-point backward "
        "difference, which is a backward-Euler step of k/3 from the "
        "extrapolated state (4 x_{n-1/2} - x_{n-1})/3; two solves per step "
        "(doc/theory.md section 2).");
      prm.declare_entry(
        "Adaptive",
        "false",
        Patterns::Bool(),
        "true: choose each step's k from a local error estimate "
        "(doc/theory.md section 2.5): a step whose estimate exceeds "
        "Adaptive tolerance is rejected and repeated with a smaller k, and "
        "the next k follows the estimate (safety factor 0.9, at most 2 times "
        "larger, at least 0.2 times smaller, rounded down to Time step times "
        "a power of 2 so that factorizations are reused), between Minimum "
        "time step and Maximum time step; Time step is the first k. Steps end exactly at "
        "the Output times. Needs Time/Scheme = bathe or backward Euler. "
        "time_series.csv gets the columns time_error_estimate and "
        "rejected_steps.");
      prm.declare_entry(
        "Adaptive tolerance",
        "1e-3",
        Patterns::Double(0),
        "The bound on the local error estimate of one step, relative to the "
        "size of the state in the energy norm (doc/theory.md section 2.5), "
        "> 0.");
      prm.declare_entry(
        "Maximum time step",
        "0",
        Patterns::Double(0),
        "With Adaptive = true: the largest k (0: no bound but the End "
        "time).");
      prm.leave_subsection();
    }

    void
    Time::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      end_time  = prm.get_double("End time");
      time_step = prm.get_double("Time step");
      minimum_time_step = prm.get_double("Minimum time step");
      if (minimum_time_step == 0)
        minimum_time_step = time_step / 1024;
      const std::string scheme_name = prm.get("Scheme");
      scheme = (scheme_name == "trapezoidal" ? Scheme::trapezoidal :
                scheme_name == "bathe"       ? Scheme::bathe :
                                               Scheme::backward_euler);
      adaptive           = prm.get_bool("Adaptive");
      adaptive_tolerance = prm.get_double("Adaptive tolerance");
      maximum_time_step  = prm.get_double("Maximum time step");
      if (maximum_time_step == 0)
        maximum_time_step = end_time;
      prm.leave_subsection();
      require(std::isfinite(end_time) && end_time > 0,
              "Time/End time must be positive, got " + str(end_time) + ".");
      require(std::isfinite(time_step) && time_step > 0,
              "Time/Time step must be positive, got " + str(time_step) + ".");
      require(minimum_time_step <= time_step,
              "Time/Minimum time step must not exceed Time/Time step.");
      require(!adaptive || scheme != Scheme::trapezoidal,
              "Time/Adaptive = true needs Time/Scheme = bathe or backward "
              "Euler (the trapezoidal rule has no error estimate here).");
      require(!adaptive || adaptive_tolerance > 0,
              "Time/Adaptive tolerance must be positive, got " +
                str(adaptive_tolerance) + ".");
      require(!adaptive || maximum_time_step >= time_step,
              "Time/Maximum time step must not be below Time/Time step.");
      require(end_time / time_step < 1e8,
              "Time/Time step: " + str(end_time / time_step) +
                " steps to reach Time/End time; at most 1e8 are allowed.");
    }

    // -------------------------------------------------------------- Solver
    void
    Solver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Solver");
      {
        prm.declare_entry(
          "Contact solver",
          "auto",
          Patterns::Selection("auto|condensed|assembled"),
          "How each semismooth Newton system is solved (all give the same "
          "iterates, to the Newton tolerance). 'condensed': static "
          "condensation onto Gamma_3 - the bulk matrix K0 is factorized once "
          "per mesh and time step, the compliance of the contact nodes "
          "computed from it (dim solves per node), and each iteration is a "
          "dense solve on the active contact nodes; Gamma_3 is replicated on "
          "every process. 'assembled': the sparse Newton system of the whole "
          "body, per process only its own part (with Linear solver = "
          "iterative: GMRES preconditioned by algebraic multigrid of K0, "
          "built once per mesh and time step; with direct: the Newton matrix "
          "factorized when it changes, as in deal.II's step-42). 'auto': "
          "condensed while dim times the number of contact nodes is at most "
          "Condensed limit, else assembled with the iterative linear solver "
          "(decided per mesh).");
        prm.declare_entry(
          "Condensed limit",
          "3000",
          Patterns::Integer(0),
          "Contact solver = auto: the largest dim times the number of "
          "contact nodes for which the condensed solver is chosen (the "
          "measured crossover, README 'Choosing the contact solver').");
        prm.declare_entry(
          "Provisional passes",
          "true",
          Patterns::Bool(),
          "Condensed solver with a convexification loop: a pass that does "
          "not end the loop takes its velocity from the stored compliance "
          "responses, without a solve with K0 (doc/algorithms.md, "
          "'Convexification loop'); false: every pass is solved in full.");
        prm.declare_entry(
          "Line search",
          "true",
          Patterns::Bool(),
          "Globalize the semismooth Newton iteration (condensed solver): "
          "when the active sets cycle (return to sets seen before) or, from "
          "the fifth iteration on, the merit function (half the squared "
          "residual) rises above that of the last five iterates, backtrack "
          "along the Newton step until it decreases (Armijo).");
        prm.declare_entry("Newton tolerance",
                          "1e-10",
                          Patterns::Double(),
                          "The semismooth Newton iteration stops when the "
                          "active sets no longer change and the residual is "
                          "below this, relative to the right-hand side.");
        prm.declare_entry("Maximum Newton iterations",
                          "50",
                          Patterns::Integer(1),
                          "Cap on the semismooth Newton iterations of one "
                          "solve; reaching it is an error.");
        prm.declare_entry(
          "Linear solver",
          "direct",
          Patterns::Selection("direct|iterative"),
          "'direct': sparse LU of the Newton matrix (package chosen below). "
          "'iterative': GMRES preconditioned with algebraic multigrid, for "
          "problems too large for a direct solver.");
        prm.declare_entry("Direct solver package",
                          "Amesos_Mumps",
                          Patterns::Selection("Amesos_Mumps|Amesos_Klu"),
                          "Trilinos Amesos package of the direct solver.");
        prm.declare_entry("Linear tolerance",
                          "1e-12",
                          Patterns::Double(),
                          "Relative residual reduction of the iterative "
                          "solver.");
        prm.declare_entry("Maximum linear iterations",
                          "1000",
                          Patterns::Integer(1),
                          "Cap on the iterations of the iterative solver.");
      }
      prm.leave_subsection();
    }

    void
    Solver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Solver");
      contact_solver =
        (prm.get("Contact solver") == "assembled" ?
           ContactSolver::assembled :
           prm.get("Contact solver") == "condensed" ? ContactSolver::condensed :
                                                      ContactSolver::automatic);
      condensed_limit       = prm.get_integer("Condensed limit");
      provisional_passes    = prm.get_bool("Provisional passes");
      line_search           = prm.get_bool("Line search");
      newton_tolerance      = prm.get_double("Newton tolerance");
      max_newton_iterations = prm.get_integer("Maximum Newton iterations");
      linear_solver         = (prm.get("Linear solver") == "iterative" ?
                                 LinearSolver::iterative :
                                 LinearSolver::direct);
      direct_solver_package = prm.get("Direct solver package");
      linear_tolerance      = prm.get_double("Linear tolerance");
      max_linear_iterations = prm.get_integer("Maximum linear iterations");
      prm.leave_subsection();
      require(std::isfinite(newton_tolerance) && newton_tolerance > 0 &&
                newton_tolerance < 1,
              "Solver/Newton tolerance must lie in (0, 1), got " +
                str(newton_tolerance) + ".");
      require(std::isfinite(linear_tolerance) && linear_tolerance > 0 &&
                linear_tolerance < 1,
              "Solver/Linear tolerance must lie in (0, 1), got " +
                str(linear_tolerance) + ".");
    }

    // ---------------------------------------------------------- Checkpoint
    void
    Checkpoint::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checkpoint");
      prm.declare_entry(
        "Every",
        "0",
        Patterns::Integer(0),
        "Write a checkpoint (mesh, fields, state) into Output/Directory every "
        "N steps (0: never); 'dynamic-contact --resume scene.prm' continues "
        "from the newest complete one. A checkpoint is written into a "
        "temporary directory and renamed when complete, so a run killed while "
        "writing leaves the previous checkpoint intact.");
      prm.declare_entry("Keep",
                        "2",
                        Patterns::Integer(1),
                        "How many complete checkpoints to keep (the newest).");
      prm.leave_subsection();
    }

    void
    Checkpoint::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checkpoint");
      every = prm.get_integer("Every");
      keep  = prm.get_integer("Keep");
      prm.leave_subsection();
    }

    // -------------------------------------------------------------- Output
    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        prm.declare_entry("Directory",
                          "output",
                          Patterns::Anything(),
                          "Directory for all results (created if missing); "
                          "relative to the working directory.");
        prm.declare_entry("Output every",
                          "1",
                          Patterns::Integer(0),
                          "Write contact_NNNNN.csv every N steps (0: only "
                          "the initial and the final state). "
                          "time_series.csv has every step.");
        prm.declare_entry("Write VTU",
                          "true",
                          Patterns::Bool(),
                          "Write the VTU files for ParaView: the fields "
                          "(solution_NNNNN.pvtu, indexed by solution.pvd) "
                          "and the contact surface (contact_surface_NNNNN"
                          ".pvtu, indexed by contact_surface.pvd), at the "
                          "initial state, every 'VTU every' steps, at the "
                          "Output times and at the final state. false: no "
                          "VTU files at all.");
        prm.declare_entry("VTU every",
                          "1",
                          Patterns::Integer(0),
                          "Write the VTU files every N steps (0: not "
                          "periodically; the initial state, the Output "
                          "times and the final state are written all the "
                          "same unless Write VTU = false).");
        prm.declare_entry("VTU subdivisions",
                          "0",
                          Patterns::Integer(0, 16),
                          "Subdivisions of each cell in the VTU files (0: the "
                          "polynomial degree, which shows Q_p fields at their "
                          "nodes).");
        prm.declare_entry(
          "Output times",
          "",
          Patterns::List(Patterns::Double()),
          "Times (s) at which contact_NNNNN.csv and (unless Write VTU = "
          "false) the VTU files are written in addition: at the first step "
          "that reaches each time. "
          "E.g. '0.2, 0.4, 0.6, 0.8' for the paper's Figure 2.");
        prm.declare_entry("Progress every",
                          "1",
                          Patterns::Integer(0),
                          "Print a progress line every N steps (0: never).");
        prm.declare_entry(
          "Print timings",
          "true",
          Patterns::Bool(),
          "Print the times: the elapsed time and the estimated time left in "
          "the progress lines, the program's provenance line (version, start "
          "time) and its parameter file in the header, and at the end the "
          "wall time, the peak memory and the table of the timer sections "
          "(disjoint sections that add up to the wall time). The summary of "
          "the run (cut-backs, unconverged steps, the largest energy defect "
          "and friction-law residual) is printed in any case.");
        prm.declare_entry(
          "Print iteration counts",
          "true",
          Patterns::Bool(),
          "Print the Newton and convexification counts in the progress lines "
          "and their totals at the end. Regression tests switch this and "
          "Print timings off so that their output is deterministic: on "
          "several processes the counts follow the round-off of the parallel "
          "direct solver near the stopping thresholds (time_series.csv has "
          "them in any case).");
        prm.declare_entry("Solver details",
                          "false",
                          Patterns::Bool(),
                          "Print every Newton iteration (residuals, active "
                          "nodes) and every convexification pass.");
      }
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory      = prm.get("Directory");
      output_every   = prm.get_integer("Output every");
      write_vtu      = prm.get_bool("Write VTU");
      vtu_every      = prm.get_integer("VTU every");
      vtu_subdivisions = prm.get_integer("VTU subdivisions");
      output_times   = Utilities::string_to_double(
        Utilities::split_string_list(prm.get("Output times")));
      progress_every = prm.get_integer("Progress every");
      print_timings  = prm.get_bool("Print timings");
      print_iteration_counts = prm.get_bool("Print iteration counts");
      solver_details = prm.get_bool("Solver details");
      prm.leave_subsection();
      require(!directory.empty(), "Output/Directory must not be empty.");
    }
  } // namespace Parameters


  // --------------------------------------------------------- RunParameters
  void
  RunParameters::declare_parameters(ParameterHandler &prm,
                                    const unsigned int dim)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Space dimension of the problem: 2 or 3. Selects the "
                      "instantiation of the program.");
    Parameters::Geometry::declare_parameters(prm, dim);
    Parameters::FiniteElement::declare_parameters(prm);
    Parameters::BoundaryConditions::declare_parameters(prm, dim);
    Parameters::Material::declare_parameters(prm);
    Parameters::Foundation::declare_parameters(prm, dim);
    Parameters::Friction::declare_parameters(prm);
    Parameters::MeshRefinement::declare_parameters(prm);
    Parameters::Time::declare_parameters(prm);
    Parameters::Solver::declare_parameters(prm);
    Parameters::Checkpoint::declare_parameters(prm);
    Parameters::Output::declare_parameters(prm);

    declare_function(prm,
                     "Body force",
                     dim,
                     zeros(dim),
                     "Body force density f_0(x, t) (N/m^3).");

    prm.enter_subsection("Exact solution");
    declare_function(prm,
                     "Displacement",
                     dim,
                     "",
                     "The exact displacement u(x, t), if known (a "
                     "manufactured solution): empty for none. When given, "
                     "every step records the errors of doc/theory.md "
                     "section 7.");
    declare_function(prm,
                     "Velocity",
                     dim,
                     "",
                     "The exact velocity du/dt(x, t) (with Displacement).");
    prm.leave_subsection();

    prm.enter_subsection("Initial conditions");
    declare_function(prm,
                     "Displacement",
                     dim,
                     zeros(dim),
                     "Initial displacement u_0(x) (m), interpolated; the "
                     "clamped and roller conditions are imposed on it.");
    declare_function(prm,
                     "Velocity",
                     dim,
                     zeros(dim),
                     "Initial velocity u_1(x) (m/s), interpolated; the "
                     "clamped and roller conditions are imposed on it.");
    prm.leave_subsection();
  }

  void
  RunParameters::parse_parameters(ParameterHandler &prm)
  {
    dimension = prm.get_integer("Dimension");
    const std::string directory =
      parameter_file.find('/') == std::string::npos ?
        std::string(".") :
        parameter_file.substr(0, parameter_file.rfind('/'));
    geometry.parse_parameters(prm, dimension, directory);
    finite_element.parse_parameters(prm);
    boundary_conditions.parse_parameters(prm, geometry, dimension);
    material.parse_parameters(prm);
    foundation.parse_parameters(prm);
    friction.parse_parameters(prm);
    mesh_refinement.parse_parameters(prm, geometry.global_refinements);
    time.parse_parameters(prm);
    solver.parse_parameters(prm);
    checkpoint.parse_parameters(prm);
    output.parse_parameters(prm);
  }


  // ----------------------------------------------------- reading the file
  namespace
  {
    /** A UTF-8 byte order mark at the start of a text (tolerated). */
    std::string
    without_bom(const std::string &text)
    {
      return text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text;
    }

    std::string
    read_file(const std::string &file)
    {
      std::ifstream      in(file, std::ios::binary);
      std::ostringstream s;
      s << in.rdbuf();
      return s.str();
    }

    /**
     * A parameter file (or a file it includes) must be a regular file: a
     * directory reads as nothing, and a named pipe blocks the reader and
     * cannot be read twice (the file is read more than once).
     */
    void
    check_file_kind(const std::string &file, const std::string &included_by)
    {
      namespace fs = std::filesystem;
      const std::string what =
        included_by.empty() ?
          "The parameter file '" + file + "'" :
          "The file '" + file + "' (included by '" + included_by + "')";
      const std::string cannot_open =
        included_by.empty() ?
          "Cannot open the parameter file '" + file + "'." :
          "Cannot open the file '" + file + "' (included by '" +
            included_by + "').";
      std::error_code ec;
      const auto      status = fs::status(file, ec);
      AssertThrow(!ec && fs::exists(status), ExcMessage(cannot_open));
      AssertThrow(!fs::is_directory(status),
                  ExcMessage(what + " is a directory, not a parameter file."));
      const std::string kind =
        fs::is_fifo(status)            ? "a named pipe" :
        fs::is_socket(status)          ? "a socket" :
        fs::is_character_file(status)  ? "a character device" :
        fs::is_block_file(status)      ? "a block device" :
                                         "not a regular file";
      AssertThrow(fs::is_regular_file(status),
                  ExcMessage(what + " is " + kind +
                             ", not a regular file: the program reads its "
                             "parameter file more than once; save it to a "
                             "file first."));
      std::ifstream in(file);
      AssertThrow(static_cast<bool>(in), ExcMessage(cannot_open));
    }

    /**
     * Follow the include statements (resolved as deal.II does, against the
     * working directory): every included file must be a regular file, and
     * none may include itself, directly or through others (the parser
     * would recurse without end).
     */
    void
    check_includes(const std::string &       file,
                   std::vector<std::string> &chain,
                   std::vector<std::string> &shown)
    {
      namespace fs = std::filesystem;
      std::istringstream lines(without_bom(read_file(file)));
      unsigned int       number = 0;
      for (std::string line; std::getline(lines, line);)
        {
          ++number;
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (line.rfind("include", 0) != 0 || line.size() < 8 ||
              (line[7] != ' ' && line[7] != '\t'))
            continue;
          const std::string included = Utilities::trim(line.substr(7));
          check_file_kind(included, file);
          std::error_code   ec;
          const std::string canonical =
            fs::weakly_canonical(included, ec).string();
          shown.push_back(included);
          if (std::find(chain.begin(), chain.end(), canonical) != chain.end())
            {
              std::string path;
              for (const auto &s : shown)
                path += (path.empty() ? "" : " -> ") + s;
              AssertThrow(false,
                          ExcMessage("The parameter file '" + shown[0] +
                                     "' includes itself (" + path +
                                     ", line " + std::to_string(number) +
                                     " of '" + file + "')."));
            }
          AssertThrow(chain.size() < 32,
                      ExcMessage("The parameter file '" + shown[0] +
                                 "' includes files more than 32 levels "
                                 "deep."));
          chain.push_back(canonical);
          check_includes(included, chain, shown);
          chain.pop_back();
          shown.pop_back();
        }
    }

    /**
     * The number of values a JSON or XML parameter file sets (the leaves of
     * its tree); throws an error naming the file if it is not valid JSON or
     * XML.
     */
    unsigned int
    count_structured_values(const std::string &parameter_file,
                            const std::string &text,
                            const ParameterFormat format)
    {
      namespace pt = boost::property_tree;
      pt::ptree tree;
      try
        {
          std::istringstream in(text);
          if (format == ParameterFormat::json)
            pt::read_json(in, tree);
          else
            pt::read_xml(in, tree);
        }
      catch (const pt::file_parser_error &e)
        {
          AssertThrow(false,
                      ExcMessage("The parameter file '" + parameter_file +
                                 "' is not valid " +
                                 (format == ParameterFormat::json ? "JSON" :
                                                                    "XML") +
                                 " (line " + std::to_string(e.line()) +
                                 ": " + e.message() + ")."));
        }
      const std::function<unsigned int(const pt::ptree &)> leaves =
        [&](const pt::ptree &t) -> unsigned int {
        unsigned int n = 0;
        for (const auto &child : t)
          if (child.first == "<xmlattr>" || child.first == "<xmlcomment>")
            continue;
          else if (child.second.empty())
            ++n;
          else
            n += leaves(child.second);
        return n;
      };
      return leaves(tree);
    }

    void
    check_readable(const std::string &parameter_file)
    {
      check_file_kind(parameter_file, "");
      const ParameterFormat format = parameter_format(parameter_file);
      if (format == ParameterFormat::prm)
        {
          std::error_code          ec;
          std::vector<std::string> chain = {
            std::filesystem::weakly_canonical(parameter_file, ec).string()};
          std::vector<std::string> shown = {parameter_file};
          check_includes(parameter_file, chain, shown);
        }
      const std::string text = without_bom(read_file(parameter_file));
      // A parameter file is text: refuse binary content with a clear message
      // rather than a confusing parse error about an unprintable line.
      // And a scene that sets nothing is a mistake, not the default scene.
      bool sets_something = false;
      if (format == ParameterFormat::prm)
        {
          std::istringstream lines(text);
          std::string        line;
          while (std::getline(lines, line))
            {
              line = Utilities::trim(line.substr(0, line.find('#')));
              if (line.rfind("set ", 0) == 0 ||
                  line.rfind("include ", 0) == 0)
                sets_something = true;
            }
        }
      unsigned int line = 1;
      for (const char c : text)
        {
          if (c == '\n')
            ++line;
          const unsigned char u = static_cast<unsigned char>(c);
          AssertThrow(!(u < 32 && c != '\n' && c != '\r' && c != '\t'),
                      ExcMessage("The parameter file '" + parameter_file +
                                 "' is not a text file (control character "
                                 "in line " +
                                 std::to_string(line) + ")."));
        }
      if (format != ParameterFormat::prm)
        sets_something =
          Utilities::trim(text).empty() ?
            false :
            count_structured_values(parameter_file, text, format) > 0;
      AssertThrow(sets_something,
                  ExcMessage("The parameter file '" + parameter_file +
                             "' is empty: it sets no parameter (write the "
                             "scene in it; --print-parameters lists every "
                             "parameter)."));
    }

    /** The subsection path ("A/B") open before line @p line of a file. */
    std::string
    subsection_path(const std::string &file, const unsigned int line)
    {
      std::istringstream       in(without_bom(read_file(file)));
      std::vector<std::string> path;
      std::string              text;
      for (unsigned int n = 1; n < line && std::getline(in, text); ++n)
        {
          text = Utilities::trim(text.substr(0, text.find('#')));
          if (text.rfind("subsection ", 0) == 0)
            path.push_back(Utilities::trim(text.substr(11)));
          else if (text == "end" && !path.empty())
            path.pop_back();
        }
      std::string result;
      for (const auto &p : path)
        result += p + "/";
      return result;
    }

    /** A pattern description as a user reads it. */
    std::string
    readable_pattern(const std::string &pattern)
    {
      if (pattern.rfind("[Double", 0) == 0)
        return "a number";
      if (pattern.rfind("[Integer", 0) == 0)
        {
          std::smatch m;
          if (std::regex_search(pattern,
                                m,
                                std::regex(R"(range (-?\d+)\.\.\.(-?\d+))")))
            return "an integer from " + m[1].str() + " to " + m[2].str();
          return "an integer";
        }
      if (pattern.rfind("[Bool", 0) == 0)
        return "true or false";
      if (pattern.rfind("[Selection", 0) == 0)
        return "one of " +
               Utilities::trim(pattern.substr(10, pattern.size() - 11));
      if (pattern.rfind("[List", 0) == 0)
        return "a comma-separated list (" + pattern + ")";
      return pattern;
    }

    /**
     * Where an entry of the flat layout of earlier versions lives now that
     * each law and refinement strategy has a subsection of its own (the
     * table of scripts/update-prm); empty if @p path did not move.
     */
    std::string
    moved_entry(const std::string &path)
    {
      static const std::map<std::string, std::string> moves = {
        {"Foundation/Normal compliance stiffness",
         "Foundation/Normal compliance/Capped ramp/Stiffness"},
        {"Foundation/Compliance cap",
         "Foundation/Normal compliance/Capped ramp/Cap"},
        {"Foundation/Normal damping",
         "Foundation/Normal damping/Capped ramp/Coefficient"},
        {"Foundation/Damping cap", "Foundation/Normal damping/Capped ramp/Cap"},
        {"Foundation/Damping only in contact",
         "Foundation/Normal damping/Only in contact"},
        {"Friction/Coefficient", "Friction/Constant/Coefficient"},
        {"Friction/Static coefficient",
         "Friction/Exponential/Static coefficient"},
        {"Friction/Dynamic coefficient",
         "Friction/Exponential/Dynamic coefficient"},
        {"Friction/Decay rate", "Friction/Exponential/Decay rate"},
        {"Friction/Expression", "Friction/Expression/Function expression"},
        {"Friction/Expression constants",
         "Friction/Expression/Function constants"},
        {"Mesh refinement/Load window",
         "Mesh refinement/Load following/Window"},
        {"Mesh refinement/Load threshold",
         "Mesh refinement/Load following/Threshold"},
        {"Mesh refinement/Look-ahead steps",
         "Mesh refinement/Load following/Look-ahead steps"},
        {"Mesh refinement/Contact window",
         "Mesh refinement/Contact following/Window"},
        {"Mesh refinement/Refine fraction",
         "Mesh refinement/Error indicator/Refine fraction"},
        {"Mesh refinement/Coarsen fraction",
         "Mesh refinement/Error indicator/Coarsen fraction"}};
      const auto found = moves.find(path);
      return found == moves.end() ? std::string() : found->second;
    }

    /** Why @p path is unknown: misspelt, or moved (and where to). */
    std::string
    unknown_entry(const std::string &path, const std::string &file)
    {
      const std::string moved = moved_entry(path);
      if (moved.empty())
        return "there is no parameter '" + path +
               "' (misspelt? --print-parameters lists every parameter).";
      return "there is no parameter '" + path + "': it is now '" + moved +
             "' (each law and refinement strategy has a subsection of its "
             "own; scripts/update-prm " +
             (file.empty() ? std::string("FILE") : "'" + file + "'") +
             " rewrites a parameter file of the old layout).";
    }

    /**
     * Rewrite a ParameterHandler error so that it names the parameter as
     * Section/Entry and the line: "line 2: Material/Density = 'abc' is not a
     * number."
     */
    std::string
    describe_parse_error(const std::string &file, const std::string &message)
    {
      std::smatch line_match;
      if (!std::regex_search(message,
                             line_match,
                             std::regex(R"(Line <(\d+)> of file <[^:>]*>?:\s*)")))
        return "'" + file + "': " + message;
      const unsigned int line  = std::stoi(line_match[1].str());
      const std::string  rest  = line_match.suffix().str();
      const std::string  where = "'" + file + "', line " +
                                std::to_string(line) + ": ";
      const std::string  path  = subsection_path(file, line);
      std::smatch        m;
      if (std::regex_search(
            rest,
            m,
            std::regex(R"(No entry with name <([^>]*)> was declared)")))
        return where + unknown_entry(path + m[1].str(), file);
      if (std::regex_search(
            rest,
            m,
            std::regex(
              R"(The entry value (.*) for the entry named (.*) does not match the given pattern: (.*))")))
        return where + path + Utilities::trim(m[2].str()) + " = '" +
               Utilities::trim(m[1].str()) + "' is not " +
               readable_pattern(Utilities::trim(m[3].str())) + ".";
      if (std::regex_search(
            rest, m, std::regex(R"(no such subsection to be entered: (.*))")))
        {
          // deal.II names the whole path, its sections joined by '.'.
          std::string name = Utilities::trim(m[1].str());
          std::string dotted_path = path;
          std::replace(dotted_path.begin(), dotted_path.end(), '/', '.');
          if (!dotted_path.empty() && name.rfind(dotted_path, 0) == 0)
            name = name.substr(dotted_path.size());
          return where + "there is no subsection '" + path + name +
                 "' (misspelt? --print-parameters lists every subsection).";
        }
      return where + rest;
    }

    /** How setting one entry went: set_entry(). */
    enum class SetResult
    {
      ok,
      undeclared,
      bad_value
    };

    /**
     * Set the entry "sections/entry" of @p prm to @p value; on failure
     * @p reason says why, naming the entry as Section/Entry.
     */
    SetResult
    set_entry(ParameterHandler &              prm,
              const std::vector<std::string> &sections,
              const std::string &             entry,
              const std::string &             value,
              std::string &                   reason)
    {
      unsigned int entered = 0;
      try
        {
          for (const auto &s : sections)
            {
              prm.enter_subsection(s);
              ++entered;
            }
          prm.set(entry, value);
        }
      catch (const std::exception &e)
        {
          for (; entered > 0; --entered)
            prm.leave_subsection();
          const std::string message = error_message(e);
          std::string       full_path;
          for (const auto &s : sections)
            full_path += s + "/";
          full_path += entry;
          std::smatch m;
          reason = message;
          if (message.find("not yet declared") != std::string::npos)
            {
              reason = unknown_entry(full_path, "");
              return SetResult::undeclared;
            }
          if (std::regex_search(
                message,
                m,
                std::regex(R"(does not match the given pattern <(.*)>)")))
            reason = full_path + " = '" + value + "' is not " +
                     readable_pattern(Utilities::trim(m[1].str())) + ".";
          return SetResult::bad_value;
        }
      for (; entered > 0; --entered)
        prm.leave_subsection();
      return SetResult::ok;
    }

    /** An XML name as ParameterHandler writes it ("Time_20step"), decoded. */
    std::string
    demangle(const std::string &name)
    {
      std::string result;
      for (std::size_t i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size() &&
            std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(name[i + 2])))
          {
            result += static_cast<char>(std::stoi(name.substr(i + 1, 2),
                                                  nullptr,
                                                  16));
            i += 2;
          }
        else
          result += name[i];
      return result;
    }

    /**
     * Set the entries of a JSON or XML tree in the form
     * ParameterHandler::print_parameters writes (every entry an object
     * with its "value"; also the value alone, as a scene written by hand
     * may give it: "End time": "2" or 2), subsections as objects. The
     * tree is read by deal.II's ParameterHandler conventions, the entries
     * set one by one so that an error names the entry as Section/Entry.
     */
    void
    set_entries(ParameterHandler &                  prm,
                const boost::property_tree::ptree &node,
                std::vector<std::string> &          path,
                const std::string &                 file,
                const bool                          xml,
                const bool                          skip_undefined)
    {
      for (const auto &[key, child] : node)
        {
          if (key == "<xmlattr>" || key == "<xmlcomment>")
            continue;
          const std::string name = xml ? demangle(key) : key;
          const auto        value_node = child.find("value");
          if (value_node == child.not_found() && !child.empty())
            {
              path.push_back(name);
              set_entries(prm, child, path, file, xml, skip_undefined);
              path.pop_back();
              continue;
            }
          const std::string value = Utilities::trim(
            value_node == child.not_found() ? child.data() :
                                              value_node->second.data());
          std::string     reason;
          const SetResult result = set_entry(prm, path, name, value, reason);
          if (result == SetResult::ok ||
              (result == SetResult::undeclared && skip_undefined))
            continue;
          AssertThrow(false,
                      ExcMessage("Error in the parameter file '" + file +
                                 "': " + reason));
        }
    }

    void
    parse_structured_file(ParameterHandler & prm,
                          const std::string &parameter_file,
                          const bool         xml,
                          const bool         skip_undefined)
    {
      namespace pt = boost::property_tree;
      pt::ptree          tree;
      std::istringstream in(without_bom(read_file(parameter_file)));
      // The syntax has been checked (check_readable).
      if (xml)
        pt::read_xml(in, tree);
      else
        pt::read_json(in, tree);
      std::vector<std::string> path;
      if (xml)
        {
          const auto root = tree.find("ParameterHandler");
          AssertThrow(root != tree.not_found() && tree.size() == 1,
                      ExcMessage("The parameter file '" + parameter_file +
                                 "' is not a parameter file in XML: its "
                                 "root element must be <ParameterHandler> "
                                 "(as --print-parameters=xml writes it)."));
          set_entries(
            prm, root->second, path, parameter_file, true, skip_undefined);
        }
      else
        set_entries(prm, tree, path, parameter_file, false, skip_undefined);
    }

    void
    parse_file(ParameterHandler & prm,
               const std::string &parameter_file,
               const bool         skip_undefined)
    {
      const ParameterFormat format = parameter_format(parameter_file);
      if (format != ParameterFormat::prm)
        {
          parse_structured_file(prm,
                                parameter_file,
                                format == ParameterFormat::xml,
                                skip_undefined);
          return;
        }
      try
        {
          // Parsed from its text, so that a UTF-8 byte order mark (which
          // some editors write) is tolerated.
          std::istringstream in(without_bom(read_file(parameter_file)));
          prm.parse_input(in, parameter_file, "", skip_undefined);
        }
      catch (const std::exception &e)
        {
          AssertThrow(false,
                      ExcMessage("Error in the parameter file " +
                                 describe_parse_error(parameter_file,
                                                      error_message(e))));
        }
    }
  } // namespace


  ParameterFormat
  parameter_format(const std::string &parameter_file)
  {
    std::string extension =
      std::filesystem::path(parameter_file).extension().string();
    std::transform(extension.begin(),
                   extension.end(),
                   extension.begin(),
                   [](const unsigned char c) { return std::tolower(c); });
    if (extension == ".json")
      return ParameterFormat::json;
    if (extension == ".xml")
      return ParameterFormat::xml;
    return ParameterFormat::prm;
  }


  void
  apply_override(ParameterHandler &prm, const std::string &assignment)
  {
    const auto equal = assignment.find('=');
    AssertThrow(equal != std::string::npos,
                ExcMessage("--set '" + assignment +
                           "': expected 'Section/Entry=value'."));
    std::string path  = Utilities::trim(assignment.substr(0, equal));
    std::string value = Utilities::trim(assignment.substr(equal + 1));

    std::vector<std::string> sections;
    std::string::size_type   slash;
    while ((slash = path.find('/')) != std::string::npos)
      {
        sections.push_back(Utilities::trim(path.substr(0, slash)));
        path = path.substr(slash + 1);
      }
    const std::string entry = Utilities::trim(path);

    std::string reason;
    if (set_entry(prm, sections, entry, value, reason) != SetResult::ok)
      AssertThrow(false, ExcMessage("--set '" + assignment + "': " + reason));
  }


  unsigned int
  read_dimension(const std::string &             parameter_file,
                 const std::vector<std::string> &overrides)
  {
    check_readable(parameter_file);
    ParameterHandler prm;
    prm.declare_entry("Dimension", "2", Patterns::Integer(2, 3), "");
    parse_file(prm, parameter_file, /*skip_undefined=*/true);
    for (const auto &o : overrides)
      if (Utilities::trim(o.substr(0, o.find('='))) == "Dimension")
        apply_override(prm, o);
    return prm.get_integer("Dimension");
  }


  RunParameters
  read_parameters(const std::string &             parameter_file,
                  const std::vector<std::string> &overrides,
                  ParameterHandler &              prm)
  {
    const unsigned int dim = read_dimension(parameter_file, overrides);
    RunParameters::declare_parameters(prm, dim);
    parse_file(prm, parameter_file, /*skip_undefined=*/false);
    for (const auto &o : overrides)
      apply_override(prm, o);

    RunParameters parameters;
    parameters.parameter_file = parameter_file;
    parameters.parse_parameters(prm);
    AssertThrow(parameters.dimension == dim,
                ExcMessage("Dimension changed between the two passes over '" +
                           parameter_file + "'."));
    return parameters;
  }
} // namespace DynamicContact
