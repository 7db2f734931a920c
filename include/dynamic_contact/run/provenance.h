#ifndef dynamic_contact_provenance_h
#define dynamic_contact_provenance_h

#include <deal.II/base/parameter_handler.h>

#include <dynamic_contact/output/output_directory.h>
#include <dynamic_contact/parameters/parameters.h>

#include <ostream>
#include <streambuf>
#include <string>

namespace DynamicContact
{
  /**
   * What a run leaves beside its results so that it can be traced and
   * repeated (README, "The output directory"): the parameters it used
   * (parameters.prm, parameters.json), a copy of its screen output
   * (log.txt) with the version of the program, of deal.II, the number of
   * processes and the start time; and the parameter listings of
   * --print-parameters (PRM, JSON, XML, and Markdown for
   * doc/parameters.md).
   */

  /** The current time, UTC, ISO 8601: "2026-11-23T21:40:00Z". */
  std::string
  utc_timestamp();

  /**
   * "dynamic-contact X (git H), deal.II A.B.C, N MPI processes, started T"
   * (T: @p start, utc_timestamp()); "N MPI processes (of S started)" when
   * only N of the @p n_started processes take part.
   */
  std::string
  provenance_line(const unsigned int n_processes,
                  const unsigned int n_started,
                  const std::string &start);

  /** The formats of --print-parameters[=FORMAT]. */
  enum class PrintFormat
  {
    prm,
    json,
    xml,
    markdown,
    /** moved_entries(): "old path = new path" lines (scripts/update-prm). */
    moved
  };

  /** "prm", "json", "xml", "markdown" (and "md"), "moved"; false for
   *  anything else. */
  bool
  parse_print_format(const std::string &name, PrintFormat &format);

  /**
   * Every entry of @p prm with its value, default, pattern and
   * documentation in @p format (deal.II's PRM, JSON or XML listing; PRM and
   * JSON/XML can be read back as a parameter file). Markdown: see
   * parameters_markdown().
   */
  void
  print_parameters(std::ostream           &out,
                   const ParameterHandler &prm,
                   const PrintFormat       format);

  /**
   * doc/parameters.md: every section and entry as the program declares them
   * (default, the values allowed, documentation), the defaults for
   * Dimension = 2 and, where they differ, for 3.
   */
  std::string
  parameters_markdown();

  /**
   * parameters.prm and parameters.json of a run: every value of @p prm,
   * that is the parameter file with the --set overrides applied. Either
   * file, given back to the program, runs the same scene (into the same
   * Output/Directory unless --set changes it); a relative Geometry/Mesh
   * file is written as an absolute path, since the copy no longer sits
   * beside the mesh (@p prm is left as it was).
   */
  struct ParameterFiles
  {
    std::string prm;
    std::string json;

    ParameterFiles() = default;
    ParameterFiles(ParameterHandler &prm, const RunParameters &parameters);

    /**
     * Rank 0: write both into @p directory (entered in its manifest,
     * written with checked writes).
     */
    void
    write(OutputDirectory &directory) const;
  };


  /**
   * The screen output of rank 0 and its copy log.txt: a stream that writes
   * to the screen (std::cout) at once and keeps the text for log.txt, which
   * is written at the points the run chooses (flush(), collectively, so that
   * a failed write is an error of the run like that of any result file).
   * Text printed before the log is opened is kept and written first.
   */
  class ScreenLog : public std::ostream
  {
  public:
    explicit ScreenLog(std::ostream &screen);
    ~ScreenLog() override;

    /**
     * Rank 0: enter log.txt in @p directory's manifest and open it; with
     * @p append continue it (--resume), with a line that starts the new
     * section. Writes the text kept so far.
     */
    void
    open(OutputDirectory &directory, const bool append);

    /** Text for log.txt only (not shown on the screen). */
    void
    log_only(const std::string &text);

    /** Write the text kept since the last call to log.txt (if open). */
    void
    write_pending();

    /** write_pending(), then flush log.txt to disk and close it (checked). */
    void
    close();

    bool
    is_open() const
    {
      return file.is_open();
    }

  private:
    class Tee : public std::streambuf
    {
    public:
      explicit Tee(std::ostream &screen)
        : screen(screen)
      {}
      std::ostream &screen;
      std::string   pending;

    protected:
      int_type
      overflow(int_type c) override;
      std::streamsize
      xsputn(const char *s, std::streamsize n) override;
      int
      sync() override;
    };

    Tee        tee;
    AppendFile file;
  };
} // namespace DynamicContact

#endif
