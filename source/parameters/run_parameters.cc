// The sections Time, Checkpoint and Output of a parameter file, and the
// whole file (RunParameters): declared and parsed. The sections of the scene
// are in source/parameters/parameters.cc, the section Solver in
// source/parameters/solver_parameters.cc, the reading of the files in
// source/parameters/parameter_reader.cc.

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
    namespace
    {
      /** Time: the entries of adaptive time steps. */
      void
      declare_adaptive_entries(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Adaptive",
          "false",
          Patterns::Bool(),
          "true: choose each step's k from a local error estimate "
          "(doc/theory.md section 2.5): a step whose estimate exceeds "
          "Adaptive tolerance is rejected and repeated with a smaller k, and "
          "the next k follows the estimate (safety factor 0.9, at most 2 "
          "times larger, at least 0.2 times smaller, rounded down to Time "
          "step times a power of 2 so that factorizations are reused), "
          "between Minimum time step and Maximum time step; Time step is the "
          "first k. Steps end exactly at the Output times. Needs Time/Scheme "
          "= bathe, sdirk or backward Euler. time_series.csv gets the "
          "columns time_error_estimate and rejected_steps.");
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
          "With Adaptive = true: the largest k (s); 0: no bound but the "
          "End time.");
        prm.declare_entry(
          "Cut back where not unique",
          "false",
          Patterns::Bool(),
          "With a slip-rate dependent friction law: true treats a step whose "
          "solution has a contraction factor of 1 or more (a bound of the "
          "frozen-coefficient loop's: the loop may be repelled from it, and "
          "other solutions may lie beside it; not a proof of either, "
          "doc/theory.md section 5.2) as a "
          "failed step, retried "
          "with half the time step; at Minimum time step it is kept and "
          "counted in the summary. A smaller k restores the factor below 1 "
          "only where inertia dominates the step's compliance (k below the "
          "periods of the modes of the contact boundary): above them the "
          "compliance grows as k falls. Evaluates Friction/Uniqueness monitor "
          "at every step (its 'never' is refused).");
      }
    } // namespace

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
        "The smallest time step (s) of a cut-back: a step the solver "
        "cannot solve is retried with half the time step, again and again "
        "down to this (0: Time step/1024), and the time "
        "step grows back (doubling after three good steps) to Time step. A "
        "step that fails even at the minimum stops the run, the last good "
        "state written. Set it equal to Time step for no cut-back.");
      declare_step_schemes(prm);
      declare_adaptive_entries(prm);
      prm.leave_subsection();
    }

    void
    Time::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      end_time          = prm.get_double("End time");
      time_step         = prm.get_double("Time step");
      minimum_time_step = prm.get_double("Minimum time step");
      if (minimum_time_step == 0)
        minimum_time_step = time_step / 1024;
      scheme_name = prm.get("Scheme");
      scheme = PluginRegistry<StepScheme>::instance().create(scheme_name, prm);
      adaptive           = prm.get_bool("Adaptive");
      adaptive_tolerance = prm.get_double("Adaptive tolerance");
      maximum_time_step  = prm.get_double("Maximum time step");
      if (maximum_time_step == 0)
        maximum_time_step = end_time;
      cut_back_where_not_unique = prm.get_bool("Cut back where not unique");
      prm.leave_subsection();
      require(std::isfinite(end_time) && end_time > 0,
              "Time/End time must be positive, got " + str(end_time) + ".");
      require(std::isfinite(time_step) && time_step > 0,
              "Time/Time step must be positive, got " + str(time_step) + ".");
      require(minimum_time_step <= time_step,
              "Time/Minimum time step must not exceed Time/Time step.");
      require(!adaptive || scheme->local_error_order() > 0,
              "Time/Adaptive = true needs a Time/Scheme with a local error "
              "estimate; Time/Scheme = " +
                scheme_name + " has none.");
      require(!adaptive || adaptive_tolerance > 0,
              "Time/Adaptive tolerance must be positive, got " +
                str(adaptive_tolerance) + ".");
      require(!adaptive || maximum_time_step >= time_step,
              "Time/Maximum time step must not be below Time/Time step.");
      require(end_time / time_step < 1e8,
              "Time/Time step: " + str(end_time / time_step) +
                " steps to reach Time/End time; at most 1e8 are allowed.");
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
      directory        = prm.get("Directory");
      output_every     = prm.get_integer("Output every");
      write_vtu        = prm.get_bool("Write VTU");
      vtu_every        = prm.get_integer("VTU every");
      vtu_subdivisions = prm.get_integer("VTU subdivisions");
      output_times     = Utilities::string_to_double(
        Utilities::split_string_list(prm.get("Output times")));
      progress_every         = prm.get_integer("Progress every");
      print_timings          = prm.get_bool("Print timings");
      print_iteration_counts = prm.get_bool("Print iteration counts");
      solver_details         = prm.get_bool("Solver details");
      prm.leave_subsection();
      require(!directory.empty(), "Output/Directory must not be empty.");
    }
  } // namespace Parameters


  // --------------------------------------------------------- RunParameters
  void
  RunParameters::declare_parameters(ParameterHandler  &prm,
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
    friction.parse_parameters(prm, material);
    mesh_refinement.parse_parameters(prm, geometry.global_refinements);
    time.parse_parameters(prm);
    solver.parse_parameters(prm);
    checkpoint.parse_parameters(prm);
    output.parse_parameters(prm);
    if (solver.preconditioner != "auto")
      {
        const PreconditionerPlugin &chosen =
          solver.preconditioner_plugin(solver.preconditioner);
        require(chosen.stores_matrix() ||
                  (solver.linear_solver !=
                     Parameters::Solver::LinearSolver::direct &&
                   solver.contact_solver != "condensed"),
                "Solver/Preconditioner = " + solver.preconditioner +
                  " stores no K0: it needs Solver/Contact solver = "
                  "assembled (or auto) and Solver/Linear solver = iterative "
                  "(or auto).");
        require(!chosen.highest_degree() ||
                  finite_element.degree <= *chosen.highest_degree(),
                "Solver/Preconditioner = " + solver.preconditioner +
                  " is made for elements of degree up to " +
                  std::to_string(chosen.highest_degree().value_or(0)) +
                  " (Finite element/Polynomial degree = " +
                  std::to_string(finite_element.degree) + ").");
      }
    // The slip length's state advances with each solve over its own
    // (sub-)step: right for the theta-schemes, whose solve is the step; the
    // composite schemes combine their sub-steps' states differently
    // (doc/theory.md section 1.6).
    require(!friction.slip_length.active() ||
              time.scheme->solves_per_step() == 1,
            "Friction/Slip length > 0 needs a Time/Scheme of one solve per "
            "step; Time/Scheme = " +
              time.scheme_name + " has " +
              std::to_string(time.scheme->solves_per_step()) +
              " (the coefficient state would advance over its sub-steps, "
              "not over the step).");
    // The cut-back for uniqueness needs the measures at every step.
    if (time.cut_back_where_not_unique)
      {
        require(friction.uniqueness_monitor !=
                  Parameters::Friction::Monitor::never,
                "Time/Cut back where not unique = true needs the uniqueness "
                "measures: Friction/Uniqueness monitor must not be 'never'.");
        friction.uniqueness_monitor = Parameters::Friction::Monitor::always;
      }
  }


  // ----------------------------------------------------- reading the file
} // namespace DynamicContact
