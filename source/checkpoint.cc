#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/solution_transfer.h>

#include <dynamic_contact/checkpoint.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    std::string
    checkpoint_name(const unsigned int step)
    {
      char name[32];
      std::snprintf(name, sizeof(name), "checkpoint_%05u", step);
      return name;
    }

    /** The steps of the complete checkpoints in a directory, ascending. */
    std::vector<unsigned int>
    complete_checkpoints(const std::string &directory)
    {
      std::vector<unsigned int> steps;
      if (!std::filesystem::is_directory(directory))
        return steps;
      for (const auto &entry : std::filesystem::directory_iterator(directory))
        {
          const std::string name = entry.path().filename().string();
          if (entry.is_directory() && name.rfind("checkpoint_", 0) == 0 &&
              name.size() == 16 &&
              std::all_of(name.begin() + 11, name.end(), ::isdigit) &&
              std::filesystem::exists(entry.path() / "state.txt"))
            steps.push_back(std::stoul(name.substr(11)));
        }
      std::sort(steps.begin(), steps.end());
      return steps;
    }


    /**
     * What a checkpoint must match to be loaded: the dimension, the coarse
     * mesh and the finite element (the refinement and the fields are in the
     * checkpoint; the number of processes may differ).
     */
    template <int dim>
    std::string
    signature(const Discretization<dim> &d)
    {
      std::ostringstream s;
      s << "dim=" << dim << " coarse_cells=" << d.triangulation.n_cells(0)
        << " element=" << d.fe.get_name();
      return s.str();
    }
  } // namespace


  template <int dim>
  void
  write_checkpoint(const std::string &            output_directory,
                   Discretization<dim> &          d,
                   const std::vector<Vector_t *> &fields,
                   const RunState &               state,
                   const unsigned int             keep,
                   const std::function<void()> &  before_commit)
  {
    const bool        root = Utilities::MPI::this_mpi_process(d.comm) == 0;
    const std::string name = checkpoint_name(state.step);
    const std::string tmp  = output_directory + "/" + name + ".tmp";
    if (root)
      {
        std::filesystem::remove_all(tmp);
        std::filesystem::create_directories(tmp);
      }
    MPI_Barrier(d.comm);

    std::vector<Vector_t>         ghosted;
    std::vector<const Vector_t *> input;
    for (const Vector_t *field : fields)
      ghosted.push_back(d.expanded(*field));
    for (const auto &g : ghosted)
      input.push_back(&g);
    parallel::distributed::SolutionTransfer<dim, Vector_t> transfer(
      d.dof_handler);
    transfer.prepare_for_serialization(input);
    d.triangulation.save(tmp + "/mesh");

    if (root)
      {
        std::ofstream out(tmp + "/state.txt");
        out.precision(17);
        out << "signature " << signature(d) << '\n'
            << "step " << state.step << '\n'
            << "time " << state.time << '\n'
            << "time_step " << state.time_step << '\n'
            << "good_steps_since_cutback " << state.good_steps_since_cutback
            << '\n'
            << "max_relative_defect " << state.max_relative_defect << '\n'
            << "min_dissipation " << state.min_dissipation << '\n'
            << "total_newton " << state.total_newton << '\n'
            << "vtu_records " << state.vtu_records.size() << '\n';
        for (const auto &[t, file] : state.vtu_records)
          out << t << ' ' << file << '\n';
        out.close();
        AssertThrow(static_cast<bool>(out),
                    ExcMessage("Cannot write the checkpoint '" + tmp + "'."));
      }
    MPI_Barrier(d.comm);
    if (before_commit)
      before_commit();

    // Complete: give it its final name (atomic), then drop the oldest.
    if (root)
      {
        const std::string final_name = output_directory + "/" + name;
        std::filesystem::remove_all(final_name);
        std::filesystem::rename(tmp, final_name);
        const auto steps = complete_checkpoints(output_directory);
        for (unsigned int i = 0; i + keep < steps.size(); ++i)
          std::filesystem::remove_all(output_directory + "/" +
                                      checkpoint_name(steps[i]));
      }
    MPI_Barrier(d.comm);
  }


  std::string
  find_latest_checkpoint(const std::string &output_directory,
                         const MPI_Comm     comm)
  {
    std::string latest;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        const auto steps = complete_checkpoints(output_directory);
        if (!steps.empty())
          latest = output_directory + "/" + checkpoint_name(steps.back());
      }
    return Utilities::MPI::broadcast(comm, latest, 0);
  }


  template <int dim>
  RunState
  read_checkpoint(const std::string &            checkpoint,
                  Discretization<dim> &          d,
                  const std::vector<Vector_t *> &fields,
                  const std::function<void()> &  after_load)
  {
    std::ifstream in(checkpoint + "/state.txt");
    AssertThrow(static_cast<bool>(in),
                ExcMessage("Cannot read the checkpoint '" + checkpoint + "'."));
    std::string line;
    std::getline(in, line);
    const std::string expected = "signature " + signature(d);
    AssertThrow(line == expected,
                ExcMessage("The checkpoint '" + checkpoint +
                           "' does not belong to this scene: it holds '" +
                           line.substr(std::min<std::size_t>(line.size(), 10)) +
                           "', the parameter file gives '" +
                           expected.substr(10) +
                           "' (Dimension, Geometry and "
                           "Finite element/Polynomial degree must be those of the "
                           "interrupted run)."));

    d.triangulation.load(checkpoint + "/mesh");
    after_load();
    parallel::distributed::SolutionTransfer<dim, Vector_t> transfer(
      d.dof_handler);
    std::vector<Vector_t *> output(fields);
    for (auto *f : output)
      d.reinit_owned(*f);
    transfer.deserialize(output);
    for (auto *f : output)
      d.constraints.set_zero(*f);

    RunState     state;
    std::string  key;
    unsigned int n_records = 0;
    in >> key >> state.step >> key >> state.time >> key >> state.time_step >>
      key >> state.good_steps_since_cutback >> key >>
      state.max_relative_defect >> key >> state.min_dissipation >> key >>
      state.total_newton >> key >> n_records;
    for (unsigned int i = 0; i < n_records; ++i)
      {
        double      t;
        std::string file;
        in >> t >> file;
        state.vtu_records.emplace_back(t, file);
      }
    AssertThrow(static_cast<bool>(in),
                ExcMessage("The checkpoint '" + checkpoint +
                           "' is damaged (state.txt)."));
    return state;
  }


  void
  truncate_time_series(const std::string &file,
                       const unsigned int step,
                       const MPI_Comm     comm)
  {
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ifstream            in(file);
        std::vector<std::string> kept;
        std::string              line;
        bool                     header = true;
        while (std::getline(in, line))
          {
            if (header || std::stoul(line.substr(0, line.find(','))) <= step)
              kept.push_back(line);
            header = false;
          }
        in.close();
        std::ofstream out(file);
        for (const auto &l : kept)
          out << l << '\n';
      }
    MPI_Barrier(comm);
  }


  template void
  write_checkpoint<2>(const std::string &,
                      Discretization<2> &,
                      const std::vector<Vector_t *> &,
                      const RunState &,
                      const unsigned int,
                      const std::function<void()> &);
  template void
  write_checkpoint<3>(const std::string &,
                      Discretization<3> &,
                      const std::vector<Vector_t *> &,
                      const RunState &,
                      const unsigned int,
                      const std::function<void()> &);
  template RunState
  read_checkpoint<2>(const std::string &,
                     Discretization<2> &,
                     const std::vector<Vector_t *> &,
                     const std::function<void()> &);
  template RunState
  read_checkpoint<3>(const std::string &,
                     Discretization<3> &,
                     const std::vector<Vector_t *> &,
                     const std::function<void()> &);
} // namespace DynamicContact
