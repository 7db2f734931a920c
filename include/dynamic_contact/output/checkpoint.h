#ifndef dynamic_contact_checkpoint_h
#define dynamic_contact_checkpoint_h

#include <deal.II/base/parameter_handler.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/output/output_directory.h>

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace DynamicContact
{
  /** What the time loop needs to go on, besides the fields. */
  struct RunState
  {
    unsigned int step                     = 0;
    double       time                     = 0;
    double       time_step                = 0; // k_current
    unsigned int good_steps_since_cutback = 0;
    double       max_relative_defect      = 0;
    double       min_dissipation          = 0;
    unsigned int total_newton             = 0;
    /** Steps kept with an unconverged convexification loop, and the worst
     *  coefficient residual among them (the run's honest ending). */
    unsigned int unconverged_steps = 0;
    double       worst_unconverged = 0;
    /** The time index of the VTU files (solution.pvd). */
    std::vector<std::pair<double, std::string>> vtu_records;

    /**
     * Call @p visit(name, field) for every number above: state.txt writes
     * them as "name value" lines and reads them back by name (each must be
     * there, once), so that a new field is one line here.
     */
    template <class Visitor>
    void
    for_each_number(Visitor &&visit)
    {
      visit("step", step);
      visit("time", time);
      visit("time_step", time_step);
      visit("good_steps_since_cutback", good_steps_since_cutback);
      visit("max_relative_defect", max_relative_defect);
      visit("min_dissipation", min_dissipation);
      visit("total_newton", total_newton);
      visit("unconverged_steps", unconverged_steps);
      visit("worst_unconverged", worst_unconverged);
    }
  };


  /**
   * Checkpoints in the output directory, checkpoint_NNNNN/ (NNNNN the
   * step): the distributed mesh (p4est), the fields (serialized with
   * parallel::distributed::SolutionTransfer: u, w and the friction forces,
   * stored exactly so that a continued run repeats the uninterrupted one),
   * the RunState (state.txt), the parameters of the run (parameters.txt),
   * and manifest.txt: the size and CRC-32 of each of these files, written
   * last.
   *
   * Written into checkpoint_NNNNN.tmp/ (after making sure the disk has
   * room for it: p4est aborts the process on a failed write), every file
   * flushed to disk (fsync), then renamed: a run killed while writing
   * leaves no incomplete checkpoint under a final name, and only a
   * checkpoint whose files match its manifest is ever loaded.
   * @p before_commit is called with everything written but not yet renamed
   * (the restart test kills the run there). Collective; a failure throws a
   * CollectiveError "cannot write ...: REASON" on every process.
   */
  template <int dim>
  void
  write_checkpoint(OutputDirectory               &directory,
                   Discretization<dim>           &discretization,
                   const std::vector<Vector_t *> &fields,
                   const RunState                &state,
                   const std::string             &parameters,
                   const unsigned int             keep,
                   const std::function<void()>   &before_commit = {});

  /**
   * Collective: the checkpoints of @p output_directory that are complete
   * (they have a manifest), newest first, as names checkpoint_NNNNN.
   */
  std::vector<std::string>
  list_checkpoints(const std::string &output_directory, const MPI_Comm comm);

  /**
   * Collective: "" if every file of the checkpoint's manifest is there with
   * its size and checksum, else what is wrong (e.g. "mesh_fixed.data has
   * 1000 bytes, its manifest says 33800").
   */
  std::string
  verify_checkpoint(const std::string &checkpoint, const MPI_Comm comm);

  /**
   * Collective: the RunState (state.txt) and the parameters
   * (parameters.txt) of a verified checkpoint; nothing is loaded into the
   * mesh. A file that does not read as written is a CollectiveError.
   */
  RunState
  read_run_state(const std::string &checkpoint, const MPI_Comm comm);
  std::string
  read_checkpoint_parameters(const std::string &checkpoint,
                             const MPI_Comm     comm);

  /**
   * Load a verified checkpoint: the mesh of @p discretization must be the
   * coarse mesh of the scene (the refinement is loaded); @p after_load sets
   * up the DoFs; the fields are then filled in (master form).
   */
  template <int dim>
  void
  load_checkpoint(const std::string             &checkpoint,
                  Discretization<dim>           &discretization,
                  const std::vector<Vector_t *> &fields,
                  const std::function<void()>   &after_load);

  /**
   * The parameters of a run as text (every entry, as the ParameterHandler
   * prints them), with the checksum of a Gmsh mesh file appended as the
   * entry "Geometry/Mesh file content" (the file could change under its
   * name).
   */
  std::string
  parameters_text(const ParameterHandler &prm, const std::string &mesh_file);

  /**
   * The entries of @p text (parameters_text) that define the solution and
   * differ from those of @p current, as "Section/Entry = 'now' (checkpoint:
   * 'then')". Everything defines the solution except what may change on
   * --resume: Time/End time, Time/Time step, Time/Minimum time step, the
   * subsections Solver, Output and Checkpoint, and the convexification
   * loop's settings (Friction/Convexification tolerance, Coefficient
   * tolerance, Relaxation, Maximum convexification iterations, Maximum slip
   * rate, Complementarity constant, Velocity strengthening). Numbers compare
   * by value ("1e10" = "1e+10").
   */
  std::vector<std::string>
  scene_differences(const std::string &checkpoint_text,
                    const std::string &current_text);

  /** The value of one entry ("Time/Time step") of parameters_text. */
  std::string
  parameter_value(const std::string &text, const std::string &entry);

  /** What a resumed run finds of time_series.csv. */
  struct TimeSeriesOnDisk
  {
    /** The header and the rows up to the checkpoint's step. */
    std::string kept;
    /** The last whole row of the file (possibly after the checkpoint). */
    unsigned int last_step = 0;
    double       last_time = 0;
  };

  /**
   * Collective: read time_series.csv for a resume from the checkpoint of
   * @p step: it must hold the rows of steps 0 to @p step in order, each
   * whole; rows after them (the interrupted continuation) may end in a cut
   * row. Anything else is a CollectiveError naming the file and the line.
   */
  TimeSeriesOnDisk
  read_time_series(const std::string &file,
                   const unsigned int step,
                   const MPI_Comm     comm);
} // namespace DynamicContact

#endif
