#ifndef dynamic_contact_output_directory_h
#define dynamic_contact_output_directory_h

#include <deal.II/base/mpi.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace DynamicContact
{
  /**
   * Files written so that a failure is never silent (README, "What can go
   * wrong"): every write is checked, after writing and after closing; a
   * failed write throws std::runtime_error("cannot write FILE: REASON"),
   * REASON from the operating system (e.g. "No space left on device"), and
   * leaves no partial file behind. These functions are local (one process);
   * the callers make the outcome collective (check_collectively).
   *
   * Fault injection for the tests (DYNAMIC_CONTACT_DISK_FULL, read by
   * FaultInjection::DiskFull), so that a full disk can be tested without
   * root: a budget of bytes, or the N-th write to a named file on a given
   * rank fails half-written, and so does every later one. Rewriting
   * run_status in the space reserved for it (StatusFile) still works on a
   * full disk, as it does on a real one.
   */

  /** CRC-32 (IEEE 802.3; zlib's crc32, Python's zlib.crc32) of @p n bytes. */
  std::uint32_t
  crc32(const void *data, const std::size_t n, const std::uint32_t crc = 0);

  /** Size and CRC-32 of a file; throws if it cannot be read. */
  std::pair<std::uintmax_t, std::uint32_t>
  file_size_and_crc32(const std::string &file);

  /** The message of a failed write: "cannot write FILE: REASON". */
  std::string
  cannot_write(const std::string &file, const std::string &reason);

  /**
   * Create or replace @p file with @p content; with @p sync flushed to disk
   * (fsync) before it returns. On failure the file is removed and
   * "cannot write FILE: REASON" thrown.
   */
  void
  write_file(const std::string &file,
             const std::string &content,
             const bool         sync = false);

  /**
   * Replace @p file atomically: written as FILE.tmp, then renamed, so that
   * the old content stays whole if the write fails.
   */
  void
  replace_file(const std::string &file,
               const std::string &content,
               const bool         sync = false);

  /** fsync a file or a directory (its entries); throws on failure. */
  void
  sync_path(const std::string &path);

  /**
   * Make sure @p bytes can be written into @p directory: reserve them
   * (posix_fallocate on a scratch file there, removed again) and throw
   * "cannot write @p file_for_message: REASON" if the file system has no
   * room. For writers that cannot fail safely themselves (p4est aborts the
   * process on a failed write).
   */
  void
  reserve_space(const std::string   &directory,
                const std::uintmax_t bytes,
                const std::string   &file_for_message);

  /** Account @p bytes written by others (p4est) to the injected disk size. */
  void
  account_written_bytes(const std::string &file, const std::uintmax_t bytes);


  /**
   * A file held open by one owner (no copies) and closed with it: what
   * AppendFile and StatusFile share.
   */
  class OpenFile
  {
  public:
    OpenFile(const OpenFile &) = delete;
    OpenFile &
    operator=(const OpenFile &) = delete;

    bool
    is_open() const
    {
      return fd >= 0;
    }

  protected:
    OpenFile() = default;
    ~OpenFile();

    std::string name;
    int         fd = -1;
  };


  /**
   * A file written a piece at a time (time_series.csv, the output
   * manifest): each append is complete or undone (the file is cut back to
   * its size before the append), so the file never ends in half a line.
   */
  class AppendFile : public OpenFile
  {
  public:
    /** Create (or truncate), or with @p append continue, @p file. */
    void
    open(const std::string &file, const bool append);
    void
    append(const std::string &text);
    /** fsync, then close, both checked. */
    void
    close();

  private:
    std::uintmax_t size = 0;
  };


  /**
   * run_status: created with room reserved beside it, and then rewritten in
   * place (and cut to length), so that the final status can be written
   * even when the disk has filled up meanwhile.
   */
  class StatusFile : public OpenFile
  {
  public:
    void
    open(const std::string &file);
    /** Replace the content by @p status and a newline (fsync'ed). */
    void
    write(const std::string &status);
  };


  /**
   * The output directory of a run, owned by the program (README, "What can
   * go wrong"):
   * - it is marked by the manifest .dynamic-contact, which lists every file
   *   and directory the program wrote there, each entered before it is
   *   written;
   * - a new run removes exactly what the manifest lists (the results of an
   *   earlier run) and nothing else; a file that has the name of a result
   *   (time_series.csv, contact_00012.csv, checkpoint_00010, ...) but is not
   *   in the manifest was not written here by the program: the run refuses
   *   the directory, naming such files, and touches nothing;
   * - a lock (flock on .dynamic-contact.lock, released by the system when
   *   the process ends, however it ends) refuses a second run in the same
   *   directory while one is running.
   * Rank 0 does the work; open() is collective, the rest rank 0's business
   * (the other processes may call it and nothing happens).
   */
  class OutputDirectory
  {
  public:
    OutputDirectory(const std::string &path, const MPI_Comm comm);
    ~OutputDirectory();

    /**
     * Collective: create the directory if needed (not with @p resume: it
     * must exist), lock it, check that it holds no foreign results, and
     * for a new run remove the results of the earlier one. Throws a
     * CollectiveError that says why it refuses.
     */
    void
    open(const bool resume);

    const std::string &
    path() const
    {
      return directory;
    }

    /** The path of @p name in the directory. */
    std::string
    file(const std::string &name) const
    {
      return directory + "/" + name;
    }

    /** Rank 0: enter @p names in the manifest before writing them. */
    void
    claim(const std::vector<std::string> &names);
    void
    claim(const std::string &name)
    {
      claim(std::vector<std::string>{name});
    }

    /** Rank 0: remove files or directories this run's manifest lists. */
    void
    remove(const std::vector<std::string> &names);

    /** Rank 0: the names the manifest lists. */
    const std::set<std::string> &
    owned() const
    {
      return names;
    }

    /** Rank 0: write run_status (claimed and reserved on first use). */
    void
    write_status(const std::string &status);

    /** Whether @p name is one of the names the program writes. */
    static bool
    is_result_name(const std::string &name);

    /** The manifest and the lock file. */
    static const char *const manifest_name;
    static const char *const lock_name;

  private:
    std::string           directory;
    MPI_Comm              comm;
    bool                  root;
    std::set<std::string> names;
    AppendFile            manifest;
    StatusFile            status_file;
    int                   lock_fd = -1;

    void
    rewrite_manifest();
    /** Rank 0, open(): the names the manifest lists; whether there is one. */
    bool
    read_manifest();
    /**
     * Rank 0, open(): refuse a directory holding files with the names of
     * results that are not in the manifest (not written here by the
     * program).
     */
    void
    refuse_foreign_results(const bool marked) const;
    /** Rank 0, open(): one run at a time (flock), or refuse. */
    void
    take_lock();
    /** Rank 0, open() for a new run: remove what the manifest lists. */
    void
    remove_earlier_results();
  };
} // namespace DynamicContact

#endif
