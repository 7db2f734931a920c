#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/output/checkpoint.h>
#include <dynamic_contact/base/failure.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace DynamicContact
{
  namespace fs = std::filesystem;

  namespace
  {
    const std::string manifest_header = "dynamic-contact checkpoint 1";
    /** The files a checkpoint must have (besides manifest.txt). */
    const std::vector<std::string> required_files = {"mesh",
                                                     "mesh.info",
                                                     "mesh_fixed.data",
                                                     "state.txt",
                                                     "parameters.txt"};

    std::string
    checkpoint_name(const unsigned int step)
    {
      char name[32];
      std::snprintf(name, sizeof(name), "checkpoint_%05u", step);
      return name;
    }

    /** The step of a name checkpoint_NNNNN, or -1. */
    long
    checkpoint_step(const std::string &name)
    {
      static const std::regex pattern(R"(checkpoint_([0-9]{5,}))");
      std::smatch             m;
      if (!std::regex_match(name, m, pattern))
        return -1;
      return std::stol(m[1].str());
    }

    std::string
    hex(const std::uint32_t x)
    {
      char text[16];
      std::snprintf(text, sizeof(text), "%08x", x);
      return text;
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

    /** Rank 0 reads @p file; every process gets its text (collective). */
    std::string
    read_collectively(const std::string &file, const MPI_Comm comm)
    {
      std::string text, error;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::ifstream in(file, std::ios::binary);
          if (!in)
            error = "cannot read " + file + ": " + std::strerror(errno);
          else
            {
              std::ostringstream s;
              s << in.rdbuf();
              text = s.str();
            }
        }
      check_collectively(comm, error);
      return Utilities::MPI::broadcast(comm, text, 0);
    }

    std::string
    format_state(RunState state, const std::string &signature)
    {
      std::ostringstream out;
      out.precision(17);
      out << "signature " << signature << '\n';
      state.for_each_number([&](const char *name, const auto &value) {
        out << name << ' ' << value << '\n';
      });
      out << "vtu_records " << state.vtu_records.size() << '\n';
      for (const auto &[t, file] : state.vtu_records)
        out << t << ' ' << file << '\n';
      out << "end\n";
      return out.str();
    }

    /** Parse "Section/Entry = value" lines (parameters_text). */
    std::vector<std::pair<std::string, std::string>>
    entries_of(const std::string &text)
    {
      std::vector<std::pair<std::string, std::string>> entries;
      std::istringstream                               in(text);
      for (std::string line; std::getline(in, line);)
        {
          const auto equal = line.find(" = ");
          if (equal == std::string::npos)
            continue;
          entries.emplace_back(line.substr(0, equal), line.substr(equal + 3));
        }
      return entries;
    }

    /** Values compare by token, numbers by value. */
    bool
    same_value(const std::string &a, const std::string &b)
    {
      static const std::regex separators(R"([\s,;]+)");
      auto                    tokens = [](const std::string &s) {
        std::vector<std::string> t;
        for (std::sregex_token_iterator i(s.begin(), s.end(), separators, -1),
             end;
             i != end;
             ++i)
          if (!i->str().empty())
            t.push_back(i->str());
        return t;
      };
      const auto ta = tokens(a), tb = tokens(b);
      if (ta.size() != tb.size())
        return false;
      for (unsigned int i = 0; i < ta.size(); ++i)
        {
          if (ta[i] == tb[i])
            continue;
          char        *end_a = nullptr, *end_b = nullptr;
          const double x = std::strtod(ta[i].c_str(), &end_a);
          const double y = std::strtod(tb[i].c_str(), &end_b);
          if (*end_a != '\0' || *end_b != '\0' || end_a == ta[i].c_str() ||
              x != y)
            return false;
        }
      return true;
    }

    /** README, "What can go wrong": what --resume lets change. */
    bool
    may_change_on_resume(const std::string &entry)
    {
      for (const char *prefix : {"Solver/", "Output/", "Checkpoint/"})
        if (entry.rfind(prefix, 0) == 0)
          return true;
      for (const char *e : {"Time/End time",
                            "Time/Time step",
                            "Time/Minimum time step",
                            "Friction/Convexification tolerance",
                            "Friction/Coefficient tolerance",
                            "Friction/Relaxation",
                            "Friction/Maximum convexification iterations",
                            "Friction/Maximum slip rate",
                            "Friction/Complementarity constant",
                            "Friction/Velocity strengthening",
                            "Geometry/Mesh file"})
        if (entry == e)
          return true;
      return false;
    }
  } // namespace


  // ------------------------------------------------------------ parameters
  std::string
  parameters_text(const ParameterHandler &prm, const std::string &mesh_file)
  {
    std::ostringstream printed;
    prm.print_parameters(printed, ParameterHandler::ShortPRM);
    std::istringstream       in(printed.str());
    std::vector<std::string> path;
    std::string              text;
    std::string              type;
    for (std::string line; std::getline(in, line);)
      {
        line = Utilities::trim(line);
        if (line.empty() || line[0] == '#')
          continue;
        if (line.rfind("subsection ", 0) == 0)
          path.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end")
          {
            if (!path.empty())
              path.pop_back();
          }
        else if (line.rfind("set ", 0) == 0)
          {
            const auto        equal = line.find('=');
            std::string       name = Utilities::trim(line.substr(4, equal - 4));
            const std::string value = equal == std::string::npos ?
                                        "" :
                                        Utilities::trim(line.substr(equal + 1));
            std::string       full;
            for (const auto &p : path)
              full += p + "/";
            full += name;
            if (full == "Geometry/Type")
              type = value;
            text += full + " = " + value + "\n";
          }
      }
    if (type == "gmsh" && !mesh_file.empty())
      {
        std::string content = "unreadable";
        try
          {
            const auto [size, crc] = file_size_and_crc32(mesh_file);
            content = std::to_string(size) + " bytes, crc32 " + hex(crc);
          }
        catch (const std::exception &)
          {}
        text += "Geometry/Mesh file content = " + content + "\n";
      }
    return text;
  }


  std::vector<std::string>
  scene_differences(const std::string &checkpoint_text,
                    const std::string &current_text)
  {
    const auto                         then = entries_of(checkpoint_text);
    const auto                         now  = entries_of(current_text);
    std::map<std::string, std::string> then_map(then.begin(), then.end());
    std::map<std::string, std::string> now_map(now.begin(), now.end());
    std::vector<std::string>           differences;
    for (const auto &[entry, value] : now)
      {
        if (may_change_on_resume(entry))
          continue;
        const auto it = then_map.find(entry);
        if (it == then_map.end())
          differences.push_back(entry + " = '" + value +
                                "' (checkpoint: not set)");
        else if (!same_value(it->second, value))
          differences.push_back(entry + " = '" + value + "' (checkpoint: '" +
                                it->second + "')");
      }
    for (const auto &[entry, value] : then)
      if (!may_change_on_resume(entry) && now_map.count(entry) == 0)
        differences.push_back(entry + " not set (checkpoint: '" + value + "')");
    return differences;
  }


  std::string
  parameter_value(const std::string &text, const std::string &entry)
  {
    for (const auto &[e, value] : entries_of(text))
      if (e == entry)
        return value;
    return "";
  }


  namespace
  {
    /**
     * Everything of a checkpoint into the directory @p tmp_name: room
     * reserved, mesh and fields, state, parameters, manifest (collective).
     */
    template <int dim>
    void
    write_checkpoint_files(OutputDirectory               &directory,
                           Discretization<dim>           &d,
                           const std::vector<Vector_t *> &fields,
                           const std::string             &state_text,
                           const std::string             &parameters,
                           const std::string             &tmp_name)
    {
      const MPI_Comm    comm = d.comm;
      const bool        root = Utilities::MPI::this_mpi_process(comm) == 0;
      const std::string tmp  = directory.file(tmp_name);
      collectively(comm, [&]() {
        if (!root)
          return;
        directory.claim(tmp_name);
        std::error_code ec;
        fs::remove_all(tmp, ec);
        fs::create_directories(tmp, ec);
        if (ec)
          throw std::runtime_error(cannot_write(tmp, ec.message()));
        // p4est aborts the process if a write fails: make sure the disk has
        // room for the mesh and the fields first (generous estimates of
        // their sizes: p4est's connectivity and quadrants, and the values of
        // every cell).
        const double n_active =
          static_cast<double>(d.triangulation.n_global_active_cells());
        const double n_coarse = static_cast<double>(d.triangulation.n_cells(0));
        const double n_processes = Utilities::MPI::n_mpi_processes(comm);
        const double bytes =
          1.25 *
          (8192 + n_coarse * (dim == 2 ? 128 : 384) +
           n_active * (dim == 2 ? 16 : 24) + n_processes * 256 +
           n_active * (16 + 8. * fields.size() * d.fe.n_dofs_per_cell()) +
           state_text.size() + parameters.size());
        reserve_space(tmp, static_cast<std::uintmax_t>(bytes), tmp + "/mesh");
      });

      collectively(comm, [&]() {
        FieldTransfer<dim, Vector_t> transfer(d, fields);
        transfer.prepare(true);
        d.triangulation.save(tmp + "/mesh");
      });

      collectively(comm, [&]() {
        if (!root)
          return;
        write_file(tmp + "/state.txt", state_text, true);
        write_file(tmp + "/parameters.txt", parameters, true);
        // Every file flushed to disk, then its size and checksum in the
        // manifest (read back from the file), which is written last.
        std::vector<std::string> files;
        for (const auto &entry : fs::directory_iterator(tmp))
          if (entry.is_regular_file())
            files.push_back(entry.path().filename().string());
        std::sort(files.begin(), files.end());
        std::string manifest = manifest_header + "\n";
        for (const auto &f : files)
          {
            sync_path(tmp + "/" + f);
            const auto [size, crc] = file_size_and_crc32(tmp + "/" + f);
            if (f.rfind("mesh", 0) == 0)
              account_written_bytes(f, size);
            manifest += f + " " + std::to_string(size) + " " + hex(crc) + "\n";
          }
        manifest += "end\n";
        write_file(tmp + "/manifest.txt", manifest, true);
        sync_path(tmp);
      });
    }
  } // namespace


  // ----------------------------------------------------------- writing
  template <int dim>
  void
  write_checkpoint(OutputDirectory               &directory,
                   Discretization<dim>           &d,
                   const std::vector<Vector_t *> &fields,
                   const RunState                &state,
                   const std::string             &parameters,
                   const unsigned int             keep,
                   const std::function<void()>   &before_commit)
  {
    const MPI_Comm    comm       = d.comm;
    const bool        root       = Utilities::MPI::this_mpi_process(comm) == 0;
    const std::string name       = checkpoint_name(state.step);
    const std::string tmp_name   = name + ".tmp";
    const std::string tmp        = directory.file(tmp_name);
    const std::string state_text = format_state(state, signature(d));
    try
      {
        write_checkpoint_files(
          directory, d, fields, state_text, parameters, tmp_name);
      }
    catch (const CollectiveError &)
      {
        // A checkpoint cut short is never used: free its room.
        if (root)
          {
            std::error_code ec;
            fs::remove_all(tmp, ec);
          }
        throw;
      }
    if (before_commit)
      before_commit();
    // Complete: give it its final name (atomic), then drop the oldest.
    collectively(comm, [&]() {
      if (!root)
        return;
      const std::string final_name = directory.file(name);
      directory.claim(name);
      std::error_code ec;
      fs::remove_all(final_name, ec);
      if (std::rename(tmp.c_str(), final_name.c_str()) != 0)
        throw std::runtime_error(
          cannot_write(final_name, std::strerror(errno)));
      sync_path(directory.path());
      std::vector<unsigned int> steps;
      for (const auto &entry : fs::directory_iterator(directory.path()))
        {
          const long s = checkpoint_step(entry.path().filename().string());
          if (s >= 0 && entry.is_directory() &&
              fs::exists(entry.path() / "manifest.txt"))
            steps.push_back(s);
        }
      std::sort(steps.begin(), steps.end());
      std::vector<std::string> old = {tmp_name};
      for (unsigned int i = 0; i + keep < steps.size(); ++i)
        old.push_back(checkpoint_name(steps[i]));
      directory.remove(old);
    });
  }


  // ------------------------------------------------------------ reading
  std::vector<std::string>
  list_checkpoints(const std::string &output_directory, const MPI_Comm comm)
  {
    std::vector<std::string> names;
    if (Utilities::MPI::this_mpi_process(comm) == 0 &&
        fs::is_directory(output_directory))
      {
        std::vector<std::pair<long, std::string>> found;
        for (const auto &entry : fs::directory_iterator(output_directory))
          {
            const std::string n = entry.path().filename().string();
            const long        s = checkpoint_step(n);
            if (s >= 0 && entry.is_directory())
              found.emplace_back(s, n);
          }
        std::sort(found.rbegin(), found.rend());
        for (const auto &f : found)
          names.push_back(f.second);
      }
    return Utilities::MPI::broadcast(comm, names, 0);
  }


  std::string
  verify_checkpoint(const std::string &checkpoint, const MPI_Comm comm)
  {
    std::string problem;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      try
        {
          const std::string manifest_file = checkpoint + "/manifest.txt";
          std::ifstream     in(manifest_file);
          if (!in)
            throw std::runtime_error(
              "it has no manifest.txt (a checkpoint cut short, or one of a "
              "version without manifests)");
          std::string line;
          if (!std::getline(in, line) || line != manifest_header)
            throw std::runtime_error("manifest.txt is damaged (line 1)");
          std::map<std::string, std::pair<std::uintmax_t, std::string>> files;
          bool ended = false;
          while (std::getline(in, line))
            {
              if (line == "end")
                {
                  ended = true;
                  break;
                }
              std::istringstream fields(line);
              std::string        name, crc;
              std::uintmax_t     size = 0;
              if (!(fields >> name >> size >> crc))
                throw std::runtime_error("manifest.txt is damaged (line '" +
                                         line + "')");
              files[name] = {size, crc};
            }
          if (!ended)
            throw std::runtime_error("manifest.txt is cut short");
          for (const auto &required : required_files)
            if (files.count(required) == 0)
              throw std::runtime_error("manifest.txt does not list " +
                                       required);
          for (const auto &[name, expected] : files)
            {
              const std::string file = checkpoint + "/" + name;
              if (!fs::is_regular_file(file))
                throw std::runtime_error(name + " is missing");
              const auto size = fs::file_size(file);
              if (size != expected.first)
                throw std::runtime_error(name + " has " + std::to_string(size) +
                                         " bytes, its manifest says " +
                                         std::to_string(expected.first));
              const auto [read_size, crc] = file_size_and_crc32(file);
              if (read_size != expected.first || hex(crc) != expected.second)
                throw std::runtime_error(name + " is damaged (checksum " +
                                         hex(crc) + ", its manifest says " +
                                         expected.second + ")");
            }
        }
      catch (const std::exception &e)
        {
          problem = e.what();
          if (problem.empty())
            problem = "it cannot be read";
        }
    return Utilities::MPI::broadcast(comm, problem, 0);
  }


  RunState
  read_run_state(const std::string &checkpoint, const MPI_Comm comm)
  {
    const std::string text = read_collectively(checkpoint + "/state.txt", comm);
    std::istringstream in(text);
    RunState           state;
    const auto         damaged = [&](const std::string &what) {
      return CollectiveError("The checkpoint '" + checkpoint +
                             "' is damaged (state.txt: " + what + ").");
    };
    // "name value" lines up to vtu_records, by name.
    std::map<std::string, std::string> numbers;
    std::string                        line;
    std::getline(in, line); // the signature, checked by load_checkpoint
    unsigned int n_records = 0;
    for (std::string key; in >> key;)
      {
        if (key == "vtu_records")
          {
            in >> n_records;
            break;
          }
        std::string value;
        in >> value;
        if (!numbers.emplace(key, value).second)
          throw damaged("'" + key + "' twice");
      }
    std::size_t used = 0;
    state.for_each_number([&](const char *name, auto &value) {
      const auto         found = numbers.find(name);
      std::istringstream parse(found == numbers.end() ? "" : found->second);
      if (found == numbers.end() || !(parse >> value) || !parse.eof())
        throw damaged("'" + std::string(name) + "' missing or not a number");
      ++used;
    });
    if (used != numbers.size())
      throw damaged("an unknown entry");
    for (unsigned int i = 0; in && i < n_records; ++i)
      {
        double      t;
        std::string file;
        in >> t >> file;
        state.vtu_records.emplace_back(t, file);
      }
    std::string end;
    in >> end;
    if (!in || end != "end")
      throw damaged("'end' expected");
    if (!(state.time >= 0) || !(state.time_step > 0))
      throw CollectiveError("The checkpoint '" + checkpoint +
                            "' is damaged (state.txt: time or time step).");
    return state;
  }


  std::string
  read_checkpoint_parameters(const std::string &checkpoint, const MPI_Comm comm)
  {
    return read_collectively(checkpoint + "/parameters.txt", comm);
  }


  template <int dim>
  void
  load_checkpoint(const std::string             &checkpoint,
                  Discretization<dim>           &d,
                  const std::vector<Vector_t *> &fields,
                  const std::function<void()>   &after_load)
  {
    const std::string text =
      read_collectively(checkpoint + "/state.txt", d.comm);
    const std::string line     = text.substr(0, text.find('\n'));
    const std::string expected = "signature " + signature(d);
    if (line != expected)
      throw CollectiveError(
        "The checkpoint '" + checkpoint +
        "' does not belong to this scene: it holds '" +
        line.substr(std::min<std::size_t>(line.size(), 10)) +
        "', the parameter file gives '" + expected.substr(10) +
        "' (Dimension, Geometry and Finite element/Polynomial degree must "
        "be those of the interrupted run).");

    collectively(d.comm, [&]() { d.triangulation.load(checkpoint + "/mesh"); });
    after_load();
    collectively(d.comm, [&]() {
      FieldTransfer<dim, Vector_t> transfer(d, fields);
      transfer.finish(true);
    });
  }


  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                                      \
  template void write_checkpoint<dim>(OutputDirectory &,                      \
                                      Discretization<dim> &,                  \
                                      const std::vector<Vector_t *> &,        \
                                      const RunState &,                       \
                                      const std::string &,                    \
                                      const unsigned int,                     \
                                      const std::function<void()> &);         \
  template void load_checkpoint<dim>(const std::string &,                     \
                                     Discretization<dim> &,                   \
                                     const std::vector<Vector_t *> &,         \
                                     const std::function<void()> &);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
