#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/leading_process.h>
#include <dynamic_contact/base/mpi_wait.h>

#include <climits>
#include <exception>
#include <stdexcept>

namespace DynamicContact
{
  namespace
  {
    /** What the leading process tells the others, and when. */
    enum Message : unsigned long long
    {
      serve_request = 0, // then the list
      work_done     = 1,
      step_failure  = 2, // then the message
      other_error   = 3  // then the message
    };

    /** A message's header: its kind, a size, one more number. */
    struct Header
    {
      unsigned long long kind  = work_done;
      unsigned long long size  = 0;
      unsigned long long extra = 0;
    };

    /**
     * The header from rank 0 on every process (collective). The others
     * may wait through the whole work: they sleep between polls (at most
     * a millisecond, what each message may then take longer), so that they
     * leave the leading process the machine's memory bandwidth and, where
     * cores are hyperthreads of one another, its core.
     */
    void
    broadcast_header(Header &header, const MPI_Comm comm, const bool leads)
    {
      MPI_Request request;
      int         ierr =
        MPI_Ibcast(&header, sizeof(Header), MPI_BYTE, 0, comm, &request);
      AssertThrowMPI(ierr);
      if (leads)
        {
          ierr = MPI_Wait(&request, MPI_STATUS_IGNORE);
          AssertThrowMPI(ierr);
        }
      else
        wait_sleeping(request, 1e-3);
    }
  } // namespace


  LeadingProcess::LeadingProcess(const MPI_Comm comm, Serve serve)
    : comm(comm)
    , rank(dealii::Utilities::MPI::this_mpi_process(comm))
    , n_processes(dealii::Utilities::MPI::n_mpi_processes(comm))
    , serve(std::move(serve))
  {}


  void
  LeadingProcess::broadcast_bytes(void *data, const std::size_t bytes) const
  {
    if (n_processes == 1 || bytes == 0)
      return;
    // In pieces of at most INT_MAX bytes (MPI counts are ints).
    char       *p    = static_cast<char *>(data);
    std::size_t left = bytes;
    while (left > 0)
      {
        const int piece = static_cast<int>(std::min<std::size_t>(left, INT_MAX));
        const int ierr  = MPI_Bcast(p, piece, MPI_BYTE, 0, comm);
        AssertThrowMPI(ierr);
        p += piece;
        left -= piece;
      }
  }


  void
  LeadingProcess::request(const std::vector<unsigned int> &list)
  {
    if (n_processes > 1)
      {
        Assert(rank == 0, dealii::ExcInternalError());
        Header header{serve_request, list.size(), 0};
        broadcast_header(header, comm, true);
        std::vector<unsigned int> copy = list;
        broadcast_bytes(copy.data(), copy.size() * sizeof(unsigned int));
      }
    // Every process serves; if this fails here, it fails on the others too
    // (the serving function is collective), and they leave by their own
    // exception: run() must not tell them.
    serving_failed = true;
    serve(list);
    serving_failed = false;
  }


  void
  LeadingProcess::run(const std::function<void()> &work)
  {
    if (n_processes == 1)
      {
        work();
        return;
      }
    if (rank == 0)
      {
        serving_failed = false;
        Header             end;
        std::string        message;
        std::exception_ptr failure;
        try
          {
            work();
          }
        catch (const StepFailure &e)
          {
            if (serving_failed)
              throw;
            end     = {step_failure, 0, e.newton_iterations};
            message = e.what();
            failure = std::current_exception();
          }
        catch (const std::exception &e)
          {
            if (serving_failed)
              throw;
            end     = {other_error, 0, 0};
            message = error_message(e);
            failure = std::current_exception();
          }
        end.size = message.size();
        broadcast_header(end, comm, true);
        broadcast_bytes(message.data(), message.size());
        if (failure)
          std::rethrow_exception(failure);
        return;
      }
    // The others: serve until the work ends.
    for (;;)
      {
        Header header;
        broadcast_header(header, comm, false);
        if (header.kind == serve_request)
          {
            std::vector<unsigned int> list(header.size);
            broadcast_bytes(list.data(), list.size() * sizeof(unsigned int));
            serve(list);
            continue;
          }
        std::string message(header.size, ' ');
        broadcast_bytes(message.data(), message.size());
        if (header.kind == step_failure)
          throw StepFailure(message, header.extra);
        if (header.kind == other_error)
          throw std::runtime_error(message);
        return;
      }
  }
} // namespace DynamicContact
