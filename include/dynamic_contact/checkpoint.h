#ifndef dynamic_contact_checkpoint_h
#define dynamic_contact_checkpoint_h

#include <dynamic_contact/bulk_solver.h>
#include <dynamic_contact/discretization.h>

#include <functional>
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
    /** The time index of the VTU files (solution.pvd). */
    std::vector<std::pair<double, std::string>> vtu_records;
  };


  /**
   * Checkpoints in the output directory, checkpoint_NNNNN/ (NNNNN the
   * step): the distributed mesh (p4est), the fields (serialized with
   * parallel::distributed::SolutionTransfer: u, w and the friction forces,
   * stored exactly so that a continued run repeats the uninterrupted one)
   * and the RunState. Written into
   * checkpoint_NNNNN.tmp/ and renamed when complete: a run killed while
   * writing leaves no incomplete checkpoint under a final name.
   * @p before_commit is called with everything written but not yet renamed
   * (the restart test kills the run there).
   */
  template <int dim>
  void
  write_checkpoint(const std::string &            output_directory,
                   Discretization<dim> &          discretization,
                   const std::vector<Vector_t *> &fields,
                   const RunState &               state,
                   const unsigned int             keep,
                   const std::function<void()> &  before_commit = {});

  /**
   * The newest complete checkpoint in @p output_directory ("" if none),
   * the same on every process.
   */
  std::string
  find_latest_checkpoint(const std::string &output_directory,
                         const MPI_Comm     comm);

  /**
   * Load a checkpoint: the mesh of @p discretization must be the coarse mesh
   * of the scene (the refinement is loaded); @p after_load sets up the DoFs;
   * the fields are then filled in (master form) and the RunState returned.
   */
  template <int dim>
  RunState
  read_checkpoint(const std::string &            checkpoint,
                  Discretization<dim> &          discretization,
                  const std::vector<Vector_t *> &fields,
                  const std::function<void()> &  after_load);

  /**
   * Keep the header and the rows of steps up to @p step of a CSV file whose
   * first column is the step (rank 0).
   */
  void
  truncate_time_series(const std::string &file,
                       const unsigned int step,
                       const MPI_Comm     comm);
} // namespace DynamicContact

#endif
