// read_time_series(): time_series.csv as a resumed run finds it (its rows
// up to the checkpoint's step, checked), for --resume.

#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/output/checkpoint.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace DynamicContact
{
  namespace
  {
    /** The error of a damaged @p file at line @p i + 1: it @p what. */
    std::runtime_error
    damaged_series(const std::string &file,
                   const unsigned int i,
                   const std::string &what)
    {
      return std::runtime_error(
        "--resume: " + file + " is damaged: line " + std::to_string(i + 1) +
        " " + what +
        " (the resumed run would continue a damaged series; a "
        "new run starts afresh)");
    }


    /**
     * Whether @p l is a whole row of @p n_columns fields: every field, the
     * step an integer (into @p s), the time a number (into @p t).
     */
    bool
    read_whole_row(const std::string &l,
                   const std::size_t  n_columns,
                   unsigned int      &s,
                   double            &t)
    {
      if (l.empty() ||
          static_cast<std::size_t>(std::count(l.begin(), l.end(), ',') + 1) !=
            n_columns ||
          l.find(",,") != std::string::npos || l.back() == ',')
        return false;
      const auto        c1 = l.find(','), c2 = l.find(',', c1 + 1);
      const std::string step_text = l.substr(0, c1);
      const std::string time_text = l.substr(c1 + 1, c2 - c1 - 1);
      if (step_text.empty() ||
          !std::all_of(step_text.begin(), step_text.end(), ::isdigit))
        return false;
      char *end = nullptr;
      t         = std::strtod(time_text.c_str(), &end);
      if (end == time_text.c_str() || *end != '\0')
        return false;
      s = std::stoul(step_text);
      return true;
    }


    /**
     * On rank 0: read the time series @p file for a resume from the
     * checkpoint of @p step into @p result; throws a std::runtime_error
     * naming the file and the line if it cannot be continued.
     */
    void
    read_series_for_resume(const std::string &file,
                           const unsigned int step,
                           TimeSeriesOnDisk  &result)
    {
      std::ifstream in(file, std::ios::binary);
      if (!in)
        throw std::runtime_error(
          "--resume: cannot read " + file +
          " (the results of the interrupted run are incomplete)");
      std::vector<std::string> lines;
      for (std::string l; std::getline(in, l);)
        lines.push_back(l);
      if (lines.empty() || lines[0].rfind("step,time,", 0) != 0)
        throw damaged_series(file, 0, "is not the header 'step,time,...'");
      const std::size_t n_columns =
        std::count(lines[0].begin(), lines[0].end(), ',') + 1;
      result.kept          = lines[0] + "\n";
      bool         reached = false;
      unsigned int next    = 0;
      for (unsigned int i = 1; i < lines.size(); ++i)
        {
          unsigned int s     = 0;
          double       t     = 0;
          const bool   whole = read_whole_row(lines[i], n_columns, s, t);
          if (!reached)
            {
              if (!whole)
                throw damaged_series(file, i, "is not a whole row");
              if (s != next)
                throw damaged_series(file,
                                     i,
                                     "holds step " + std::to_string(s) +
                                       " where step " + std::to_string(next) +
                                       " belongs");
              result.kept += lines[i] + "\n";
              reached = (s == step);
              ++next;
            }
          else if (!whole)
            {
              if (i + 1 < lines.size())
                throw damaged_series(file, i, "is not a whole row");
              continue; // a row cut short by the interruption
            }
          result.last_step = s;
          result.last_time = t;
        }
      if (!reached)
        throw std::runtime_error(
          "--resume: " + file +
          " ends before the step of the "
          "checkpoint (step " +
          std::to_string(step) +
          "): the results of the interrupted run are incomplete");
    }
  } // namespace


  TimeSeriesOnDisk
  read_time_series(const std::string &file,
                   const unsigned int step,
                   const MPI_Comm     comm)
  {
    TimeSeriesOnDisk result;
    std::string      error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      try
        {
          read_series_for_resume(file, step, result);
        }
      catch (const std::exception &e)
        {
          error = e.what();
        }
    check_collectively(comm, error);
    result.last_step = Utilities::MPI::broadcast(comm, result.last_step, 0);
    result.last_time = Utilities::MPI::broadcast(comm, result.last_time, 0);
    return result;
  }
} // namespace DynamicContact
