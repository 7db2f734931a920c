#ifndef dynamic_contact_output_h
#define dynamic_contact_output_h

#include <dynamic_contact/bulk_operator.h>
#include <dynamic_contact/contact_boundary.h>
#include <dynamic_contact/discretization.h>
#include <dynamic_contact/material.h>
#include <dynamic_contact/output_directory.h>
#include <dynamic_contact/step_solver.h>

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
   * processes on rank 0 and sorted by coordinates. Columns: x, y (, z),
   * u_nu, w_nu, normal_pressure (= p + q), then the friction columns when
   * the scene has friction, then the displacement u_x, u_y (, u_z) (for
   * drawing the deformed boundary). Collective; the name is entered in
   * @p directory's manifest first, the write checked (CollectiveError).
   */
  template <int dim>
  void
  write_contact_csv(OutputDirectory &                          directory,
                    const std::string &                        name,
                    const ContactBoundary<dim> &               boundary,
                    const std::vector<ContactNodeState<dim>> &states,
                    const Vector_t &                           u,
                    const Vector_t &                           w,
                    const bool                                 friction,
                    const MPI_Comm                             comm);


  /**
   * solution_NNNNN.pvtu (+ one .vtu per process) and the time index
   * solution.pvd: displacement, velocity, stress (tensor components and von
   * Mises, cell averages), the contact pressure and traction on Gamma_3,
   * friction fields when present, and the MPI subdomain. Each process
   * writes its piece solution_NNNNN.R.vtu, rank 0 the record .pvtu and the
   * index (replaced atomically); every write is checked, and write() is
   * collective (CollectiveError on every process if a write fails).
   */
  template <int dim>
  class VtuWriter
  {
  public:
    VtuWriter(OutputDirectory &  directory,
              const MPI_Comm     comm,
              const unsigned int subdivisions = 0);

    void
    write(const unsigned int                         step,
          const double                               time,
          const Discretization<dim> &                discretization,
          const KelvinVoigtMaterial<dim> &           material,
          const ContactBoundary<dim> &               boundary,
          const std::vector<ContactNodeState<dim>> &states,
          const Vector_t &                           u,
          const Vector_t &                           w,
          const bool                                 friction);

    /** The time index (solution.pvd): (time, pvtu file) pairs. */
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

    /** Collective: write the index solution.pvd of the records. */
    void
    write_index();

    /** The files of the VTU output of @p step on @p n_processes. */
    static std::vector<std::string>
    file_names(const unsigned int step, const unsigned int n_processes);

  private:
    OutputDirectory &                         directory;
    MPI_Comm                                  comm;
    unsigned int                              subdivisions;
    std::vector<std::pair<double, std::string>> records;
  };
} // namespace DynamicContact

#endif
