#ifndef dynamic_contact_output_h
#define dynamic_contact_output_h

#include <dynamic_contact/contact/contact_boundary.h>
#include <dynamic_contact/laws/contact_law.h>
#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/output/output_directory.h>

#include <string>
#include <utility>
#include <vector>

namespace DynamicContact
{
  /** One row of time_series.csv: named values, in column order. */
  class TimeSeriesRow
  {
  public:
    void
    add(const std::string &name, const double value);
    void
    add_integer(const std::string &name, const long long value);

    const std::vector<std::pair<std::string, std::string>> &
    columns() const
    {
      return entries;
    }

    /** The value of a column (for progress lines and tests). */
    double
    get(const std::string &name) const;

  private:
    std::vector<std::pair<std::string, std::string>> entries;
  };


  /**
   * time_series.csv: a header row, then one row per step, written by rank 0
   * as it comes, so that a long run can be watched. Every row is checked:
   * a row that cannot be written whole is taken back (the file ends with
   * the last whole row) and the run stops. All members are collective and
   * throw a CollectiveError "cannot write ...: REASON" on every process.
   */
  class TimeSeriesWriter
  {
  public:
    /** @p append: continue an existing file (no header; after --resume). */
    TimeSeriesWriter(OutputDirectory &directory,
                     const MPI_Comm   comm,
                     const bool       append = false);

    void
    write(const TimeSeriesRow &row);

    /** Flush to disk and close (checked). */
    void
    close();

  private:
    MPI_Comm   comm;
    bool       root;
    bool       header_written = false;
    AppendFile out;
  };


  /**
   * contact_NNNNN.csv: one row per node of Gamma_3, gathered from all
   * processes on rank 0 and sorted by coordinates. Columns: time (the same
   * @p time in every row), x, y (, z), u_nu, w_nu, normal_pressure (= p +
   * q), then the friction columns when the scene has friction, then the
   * displacement u_x, u_y (, u_z) (for drawing the deformed boundary).
   * Collective; the name is entered in @p directory's manifest first, the
   * write checked (CollectiveError).
   */
  template <int dim>
  void
  write_contact_csv(OutputDirectory                          &directory,
                    const std::string                        &name,
                    const double                              time,
                    const ContactBoundary<dim>               &boundary,
                    const std::vector<ContactNodeState<dim>> &states,
                    const Vector_t                           &u,
                    const Vector_t                           &w,
                    const bool                                friction,
                    const MPI_Comm                            comm);


  /**
   * The integer code of a node's state in the VTU files (doc/output.md):
   * 0 free (no normal force), 1 in contact without friction, 2 stick,
   * 3 slip.
   */
  template <int dim>
  int
  contact_state_code(const ContactNodeState<dim> &state);


  /**
   * The VTU output for ParaView, each file carrying its time and step:
   * - solution_NNNNN.pvtu (+ one .vtu per process), indexed by
   *   solution.pvd: displacement, velocity, the stress tensor (cell
   *   averages) and von Mises stress, the contact fields of Gamma_3 as
   *   nodal fields of the whole mesh, and the MPI subdomain;
   * - contact_surface_NNNNN.pvtu (+ one .vtu per process), indexed by
   *   contact_surface.pvd: the faces of Gamma_3 (the boundary ids
   *   @p contact_ids) with the nodal quantities of the contact laws.
   * Each process writes its pieces solution_NNNNN.R.vtu and
   * contact_surface_NNNNN.R.vtu, rank 0 the records .pvtu and the indexes
   * (replaced atomically); every file is entered in the manifest first,
   * every write is checked, and write() is collective (CollectiveError on
   * every process if a write fails).
   */
  template <int dim>
  class VtuWriter
  {
  public:
    VtuWriter(OutputDirectory                       &directory,
              const MPI_Comm                         comm,
              const std::vector<types::boundary_id> &contact_ids,
              const unsigned int                     subdivisions = 0);

    void
    write(const unsigned int                        step,
          const double                              time,
          const Discretization<dim>                &discretization,
          const KelvinVoigtMaterial<dim>           &material,
          const ContactBoundary<dim>               &boundary,
          const std::vector<ContactNodeState<dim>> &states,
          const Vector_t                           &u,
          const Vector_t                           &w,
          const bool                                friction);

    /**
     * The time index (solution.pvd): (time, pvtu file) pairs. The index of
     * the surface (contact_surface.pvd) has the same times.
     */
    const std::vector<std::pair<double, std::string>> &
    get_records() const
    {
      return records;
    }
    void
    set_records(const std::vector<std::pair<double, std::string>> &r)
    {
      records = r;
    }

    /**
     * Collective: write the indexes solution.pvd and contact_surface.pvd of
     * the records, or remove them if there are no records.
     */
    void
    write_index();

    /**
     * The files of the VTU output of @p step on @p n_processes: the record
     * BASE_NNNNN.pvtu, then the piece BASE_NNNNN.R.vtu of each process
     * (BASE: solution or contact_surface).
     */
    static std::vector<std::string>
    file_names(const std::string &base,
               const unsigned int step,
               const unsigned int n_processes);

  private:
    OutputDirectory                            &directory;
    MPI_Comm                                    comm;
    std::vector<types::boundary_id>             contact_ids;
    unsigned int                                subdivisions;
    std::vector<std::pair<double, std::string>> records;
  };
} // namespace DynamicContact

#endif
