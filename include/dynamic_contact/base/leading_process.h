#ifndef dynamic_contact_leading_process_h
#define dynamic_contact_leading_process_h

#include <mpi.h>

#include <cstddef>
#include <functional>
#include <type_traits>
#include <vector>

namespace DynamicContact
{
  /**
   * Work that one process does for all: rank 0 of a communicator runs it
   * while the others wait, and the answer is then broadcast. The condensed
   * solver's dense iterations on Gamma_3 are such work: every process would
   * compute the same answer from the same tables, and on many processes
   * sharing a machine's memory bandwidth the copies slow each other down;
   * so rank 0 alone holds the tables and iterates.
   *
   * The work may need the others now and then (a collective step, such as
   * new compliance columns from the distributed factorization): it calls
   * request() with a list of numbers, and every process then runs the
   * serving function with that list together. A failure of the work ends
   * run() on every process: rank 0 rethrows its exception, the others
   * throw a StepFailure with its message and Newton iterations where it
   * was one (the time loop then retries the step on all of them), else a
   * std::runtime_error with its message. A failure inside the serving
   * function, which every process runs, leaves each process by its own
   * exception.
   *
   * On one process run() just calls the work and request() the serving
   * function.
   */
  class LeadingProcess
  {
  public:
    using Serve = std::function<void(const std::vector<unsigned int> &)>;

    /** On every process of @p comm (nothing is communicated). */
    LeadingProcess(const MPI_Comm comm, Serve serve);

    /** Whether this process does the work (rank 0). */
    bool
    leads() const
    {
      return rank == 0;
    }

    /** Whether there are other processes to wait and be told. */
    bool
    shared() const
    {
      return n_processes > 1;
    }

    /**
     * Collective: @p work on the leading process, the others serving its
     * requests until it ends (see the class documentation for failures).
     */
    void
    run(const std::function<void()> &work);

    /**
     * Inside the work only: every process runs the serving function with
     * @p list (the leading one too).
     */
    void
    request(const std::vector<unsigned int> &list);

    /**
     * Collective: the leading process's @p values on every process
     * (resized). For trivially copyable elements (Tensor<1, dim>, numbers).
     */
    template <typename T>
    void
    share(std::vector<T> &values) const
    {
      static_assert(std::is_trivially_copyable_v<T>,
                    "LeadingProcess::share() copies bytes.");
      unsigned long long size = values.size();
      broadcast_bytes(&size, sizeof(size));
      values.resize(size);
      broadcast_bytes(values.data(), size * sizeof(T));
    }

    /** Collective: the leading process's @p value on every process. */
    template <typename T>
    void
    share(T &value) const
    {
      static_assert(std::is_trivially_copyable_v<T>,
                    "LeadingProcess::share() copies bytes.");
      broadcast_bytes(&value, sizeof(T));
    }

  private:
    const MPI_Comm     comm;
    const unsigned int rank;
    const unsigned int n_processes;
    const Serve        serve;
    /** A request's serving function failed (inside run(), leading). */
    bool serving_failed = false;

    void
    broadcast_bytes(void *data, const std::size_t bytes) const;
  };
} // namespace DynamicContact

#endif
