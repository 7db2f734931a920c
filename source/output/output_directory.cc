#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/fault_injection.h>
#include <dynamic_contact/output/output_directory.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace DynamicContact
{
  using namespace dealii;

  namespace fs = std::filesystem;

  // ------------------------------------------------------------- CRC-32
  std::uint32_t
  crc32(const void *data, const std::size_t n, const std::uint32_t crc)
  {
    static const std::array<std::uint32_t, 256> table = []() {
      std::array<std::uint32_t, 256> t{};
      for (std::uint32_t i = 0; i < 256; ++i)
        {
          std::uint32_t c = i;
          for (unsigned int k = 0; k < 8; ++k)
            c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : (c >> 1);
          t[i] = c;
        }
      return t;
    }();
    std::uint32_t c     = crc ^ 0xFFFFFFFFu;
    const auto   *bytes = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < n; ++i)
      c = table[(c ^ bytes[i]) & 0xFFu] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
  }


  std::pair<std::uintmax_t, std::uint32_t>
  file_size_and_crc32(const std::string &file)
  {
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw std::runtime_error("cannot read " + file + ": " +
                               std::strerror(errno));
    std::vector<char> buffer(1 << 20);
    std::uintmax_t    size = 0;
    std::uint32_t     crc  = 0;
    while (in)
      {
        in.read(buffer.data(), buffer.size());
        const std::streamsize n = in.gcount();
        if (n <= 0)
          break;
        crc = crc32(buffer.data(), n, crc);
        size += n;
      }
    if (in.bad())
      throw std::runtime_error("cannot read " + file);
    return {size, crc};
  }


  std::string
  cannot_write(const std::string &file, const std::string &reason)
  {
    return "cannot write " + file + ": " + reason;
  }


  // ------------------------------------------------------ fault injection
  namespace
  {
    /** DYNAMIC_CONTACT_DISK_FULL (FaultInjection::DiskFull). */
    FaultInjection::DiskFull &
    injection()
    {
      return FaultInjection::instance().disk_full;
    }

    [[noreturn]] void
    fail(const std::string &file, const int error)
    {
      throw std::runtime_error(cannot_write(file, std::strerror(error)));
    }

    /** Write all of @p n bytes (or fail: partly written, as a full disk). */
    void
    write_all(const int          fd,
              const char        *data,
              const std::size_t  n,
              const std::string &file)
    {
      const std::size_t allowed = injection().allowance(file, n);
      std::size_t       done    = 0;
      while (done < allowed)
        {
          const ssize_t r = ::write(fd, data + done, allowed - done);
          if (r < 0)
            {
              if (errno == EINTR)
                continue;
              fail(file, errno);
            }
          done += static_cast<std::size_t>(r);
        }
      if (allowed < n)
        fail(file, ENOSPC);
    }
  } // namespace


  void
  account_written_bytes(const std::string &, const std::uintmax_t bytes)
  {
    auto &i = injection();
    if (i.active && i.budget_mode)
      i.budget -= std::min(i.budget, bytes);
  }


  // ------------------------------------------------------- whole files
  void
  write_file(const std::string &file,
             const std::string &content,
             const bool         sync)
  {
    const int fd =
      ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
      fail(file, errno);
    try
      {
        write_all(fd, content.data(), content.size(), file);
        if (sync && ::fsync(fd) != 0)
          fail(file, errno);
      }
    catch (...)
      {
        ::close(fd);
        ::unlink(file.c_str());
        throw;
      }
    if (::close(fd) != 0)
      {
        const int error = errno;
        ::unlink(file.c_str());
        fail(file, error);
      }
  }


  void
  sync_path(const std::string &path)
  {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
      fail(path, errno);
    if (::fsync(fd) != 0)
      {
        const int error = errno;
        ::close(fd);
        // Directories of some file systems cannot be synced: nothing lost.
        if (error == EINVAL && fs::is_directory(path))
          return;
        fail(path, error);
      }
    ::close(fd);
  }


  void
  replace_file(const std::string &file,
               const std::string &content,
               const bool         sync)
  {
    const std::string tmp = file + ".tmp";
    write_file(tmp, content, sync);
    if (std::rename(tmp.c_str(), file.c_str()) != 0)
      {
        const int error = errno;
        ::unlink(tmp.c_str());
        fail(file, error);
      }
    if (sync)
      sync_path(fs::path(file).parent_path().empty() ?
                  std::string(".") :
                  fs::path(file).parent_path().string());
  }


  void
  reserve_space(const std::string   &directory,
                const std::uintmax_t bytes,
                const std::string   &file_for_message)
  {
    if (!injection().fits(file_for_message, bytes))
      fail(file_for_message, ENOSPC);
    const std::string scratch = directory + "/.reserve";
    const int         fd =
      ::open(scratch.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
      fail(file_for_message, errno);
    const int error =
      ::posix_fallocate(fd,
                        0,
                        static_cast<off_t>(std::max<std::uintmax_t>(bytes, 1)));
    ::close(fd);
    ::unlink(scratch.c_str());
    // EINVAL/EOPNOTSUPP: the file system cannot reserve; go on unchecked.
    if (error == ENOSPC || error == EDQUOT || error == EFBIG || error == EIO)
      throw std::runtime_error(cannot_write(file_for_message,
                                            std::string(std::strerror(error)) +
                                              " (the checkpoint needs about " +
                                              std::to_string(bytes / 1024 + 1) +
                                              " kB)"));
  }


  // ---------------------------------------------------- OpenFile, AppendFile
  OpenFile::~OpenFile()
  {
    if (fd >= 0)
      ::close(fd);
  }


  void
  AppendFile::open(const std::string &file, const bool append)
  {
    if (fd >= 0)
      ::close(fd);
    name = file;
    fd =
      ::open(file.c_str(),
             O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | (append ? 0 : O_TRUNC),
             0644);
    if (fd < 0)
      fail(file, errno);
    struct stat s;
    if (::fstat(fd, &s) != 0)
      fail(file, errno);
    size = s.st_size;
  }


  void
  AppendFile::append(const std::string &text)
  {
    if (fd < 0)
      fail(name, EBADF);
    try
      {
        write_all(fd, text.data(), text.size(), name);
      }
    catch (...)
      {
        // Undo the part written: the file ends with the last whole append.
        if (::ftruncate(fd, static_cast<off_t>(size)) != 0)
          {}
        throw;
      }
    size += text.size();
  }


  void
  AppendFile::close()
  {
    if (fd < 0)
      return;
    const int f = fd;
    fd          = -1;
    if (::fsync(f) != 0)
      {
        const int error = errno;
        ::close(f);
        fail(name, error);
      }
    if (::close(f) != 0)
      fail(name, errno);
  }


  // ---------------------------------------------------------- StatusFile
  namespace
  {
    constexpr std::size_t status_room = 4096;
  }

  void
  StatusFile::open(const std::string &file)
  {
    name = file;
    fd   = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      fail(file, errno);
#ifdef FALLOC_FL_KEEP_SIZE
    // Room for the final status, whatever happens to the disk meanwhile.
    if (::fallocate(fd, FALLOC_FL_KEEP_SIZE, 0, status_room) != 0)
      {}
#endif
  }


  void
  StatusFile::write(const std::string &status)
  {
    if (fd < 0)
      fail(name, EBADF);
    std::string text = status.substr(0, status_room - 2) + "\n";
    // In the room reserved: a full disk does not stop it (unless run_status
    // itself is the injected failure).
    auto &i = injection();
    if (i.active && !i.budget_mode && i.name == "run_status" &&
        i.allowance(name, text.size()) < text.size())
      fail(name, ENOSPC);
    std::size_t done = 0;
    while (done < text.size())
      {
        const ssize_t r =
          ::pwrite(fd, text.data() + done, text.size() - done, done);
        if (r < 0)
          {
            if (errno == EINTR)
              continue;
            fail(name, errno);
          }
        done += static_cast<std::size_t>(r);
      }
    if (::ftruncate(fd, static_cast<off_t>(text.size())) != 0)
      fail(name, errno);
    if (::fsync(fd) != 0)
      fail(name, errno);
  }


  // ----------------------------------------------------- OutputDirectory
  const char *const OutputDirectory::manifest_name = ".dynamic-contact";
  const char *const OutputDirectory::lock_name     = ".dynamic-contact.lock";

  namespace
  {
    const std::string manifest_header =
      "# dynamic-contact output directory. The program wrote the files and "
      "directories listed below here; a new run removes exactly these, and "
      "never a file that is not listed.";

    std::string
    host_name()
    {
      char name[256] = {};
      if (::gethostname(name, sizeof(name) - 1) != 0)
        return "?";
      return name;
    }

    std::string
    list_of(const std::vector<std::string> &names, const unsigned int most)
    {
      std::string list;
      for (unsigned int i = 0; i < names.size() && i < most; ++i)
        list += (i ? ", " : "") + names[i];
      if (names.size() > most)
        list += " (and " + std::to_string(names.size() - most) + " more)";
      return list;
    }
  } // namespace


  OutputDirectory::OutputDirectory(const std::string &path, const MPI_Comm comm)
    : directory(path)
    , comm(comm)
    , root(Utilities::MPI::this_mpi_process(comm) == 0)
  {
    while (directory.size() > 1 && directory.back() == '/')
      directory.pop_back();
  }


  OutputDirectory::~OutputDirectory()
  {
    if (lock_fd >= 0)
      ::close(lock_fd); // releases the lock
  }


  bool
  OutputDirectory::is_result_name(const std::string &name)
  {
    static const std::regex pattern(
      R"((time_series\.csv|run_status|log\.txt|parameters\.prm|)"
      R"(parameters\.json|solution\.pvd|contact_[0-9]{5,}\.csv|)"
      R"(solution_[0-9]{5,}\.pvtu|solution_[0-9]{5,}\.[0-9]+\.vtu|)"
      R"(contact_surface\.pvd|contact_surface_[0-9]{5,}\.pvtu|)"
      R"(contact_surface_[0-9]{5,}\.[0-9]+\.vtu|)"
      R"(checkpoint_[0-9]{5,}(\.tmp)?)(\.tmp)?)");
    return std::regex_match(name, pattern);
  }


  bool
  OutputDirectory::read_manifest()
  {
    // What the program wrote here before.
    const std::string manifest_path = file(manifest_name);
    const bool        marked        = fs::exists(manifest_path);
    names.clear();
    if (marked)
      {
        std::ifstream in(manifest_path);
        std::string   line;
        if (!std::getline(in, line) || line != manifest_header)
          throw std::runtime_error(
            "Output/Directory '" + directory + "' holds a file " +
            manifest_name +
            " that is not the manifest of dynamic-contact: refusing "
            "the directory (choose another Output/Directory).");
        while (std::getline(in, line))
          if (!line.empty())
            names.insert(line);
      }
    return marked;
  }


  void
  OutputDirectory::refuse_foreign_results(const bool marked) const
  {
    // Results not written here by the program are never touched.
    std::vector<std::string> foreign;
    for (const auto &entry : fs::directory_iterator(directory))
      {
        const std::string name = entry.path().filename().string();
        // NAME.tmp: a replacement of NAME cut short (replace_file).
        const bool ours =
          names.count(name) == 1 ||
          (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0 &&
           names.count(name.substr(0, name.size() - 4)) == 1);
        if (is_result_name(name) && !ours)
          foreign.push_back(name);
      }
    std::sort(foreign.begin(), foreign.end());
    if (!foreign.empty())
      throw std::runtime_error(
        "Output/Directory '" + directory + "' holds " +
        (foreign.size() == 1 ? "a file" : "files") +
        " with the names of results that " +
        (marked ? "its runs of dynamic-contact did not write" :
                  "dynamic-contact did not write there (the directory "
                  "has no manifest " +
                    std::string(manifest_name) +
                    ": they were written by another program, or by a "
                    "version of dynamic-contact from before output "
                    "directories were marked)") +
        ": " + list_of(foreign, 5) +
        ". They are not overwritten: move them away, or choose "
        "another Output/Directory.");
  }


  void
  OutputDirectory::take_lock()
  {
    // One run at a time.
    lock_fd =
      ::open(file(lock_name).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd < 0)
      throw std::runtime_error(
        cannot_write(file(lock_name), std::strerror(errno)));
    if (::flock(lock_fd, LOCK_EX | LOCK_NB) != 0)
      {
        const int   lock_error = errno;
        std::string holder;
        {
          std::ifstream in(file(lock_name));
          std::getline(in, holder);
        }
        ::close(lock_fd);
        lock_fd = -1;
        if (lock_error == EWOULDBLOCK)
          throw std::runtime_error(
            "Output/Directory '" + directory +
            "' is in use by another run of dynamic-contact" +
            (holder.empty() ? "" : " (" + holder + ")") +
            ": two runs must not write into one directory; wait for "
            "it to end, or choose another Output/Directory.");
        throw std::runtime_error("cannot lock " + file(lock_name) + ": " +
                                 std::strerror(lock_error));
      }
    {
      const std::string holder = "process " + std::to_string(::getpid()) +
                                 " on host " + host_name() + "\n";
      if (::ftruncate(lock_fd, 0) != 0 ||
          ::pwrite(lock_fd, holder.data(), holder.size(), 0) !=
            static_cast<ssize_t>(holder.size()))
        throw std::runtime_error(
          cannot_write(file(lock_name), std::strerror(errno)));
    }
  }


  void
  OutputDirectory::remove_earlier_results()
  {
    std::error_code ec;
    // A new run: the results of the earlier one go (exactly those).
    for (const auto &name : names)
      {
        fs::remove_all(file(name + ".tmp"), ec);
        fs::remove_all(file(name), ec);
        if (ec)
          throw std::runtime_error("cannot remove " + file(name) +
                                   " (a result of an earlier "
                                   "run): " +
                                   ec.message());
      }
    names.clear();
  }


  void
  OutputDirectory::open(const bool resume)
  {
    std::string error;
    if (root)
      try
        {
          std::error_code ec;
          if (resume)
            {
              if (!fs::is_directory(directory))
                throw std::runtime_error(
                  "--resume: Output/Directory '" + directory +
                  "' does not exist (the interrupted run needs "
                  "Checkpoint/Every > 0).");
            }
          else
            {
              fs::create_directories(directory, ec);
              if (ec || !fs::is_directory(directory))
                throw std::runtime_error(
                  "Output/Directory: cannot create '" + directory + "'" +
                  (ec ? " (" + ec.message() + ")" : " (not a directory)") +
                  ".");
            }

          const bool marked = read_manifest();
          refuse_foreign_results(marked);
          take_lock();
          if (!resume)
            remove_earlier_results();
          if (resume && marked)
            manifest.open(file(manifest_name), true); // as it is
          else
            rewrite_manifest();
        }
      catch (const std::exception &e)
        {
          error = e.what();
          if (lock_fd >= 0)
            {
              ::close(lock_fd);
              lock_fd = -1;
            }
        }
    check_collectively(comm, error);
  }


  void
  OutputDirectory::rewrite_manifest()
  {
    std::string text = manifest_header + "\n";
    for (const auto &n : names)
      text += n + "\n";
    replace_file(file(manifest_name), text);
    manifest.open(file(manifest_name), true);
  }


  void
  OutputDirectory::claim(const std::vector<std::string> &new_names)
  {
    if (!root)
      return;
    std::string text;
    for (const auto &n : new_names)
      if (names.count(n) == 0)
        text += n + "\n";
    if (text.empty())
      return;
    manifest.append(text);
    names.insert(new_names.begin(), new_names.end());
  }


  void
  OutputDirectory::remove(const std::vector<std::string> &old_names)
  {
    if (!root)
      return;
    bool changed = false;
    for (const auto &n : old_names)
      if (names.count(n) == 1)
        {
          std::error_code ec;
          fs::remove_all(file(n), ec);
          if (ec)
            throw std::runtime_error("cannot remove " + file(n) + ": " +
                                     ec.message());
          names.erase(n);
          changed = true;
        }
    if (changed)
      rewrite_manifest();
  }


  void
  OutputDirectory::write_status(const std::string &status)
  {
    if (!root)
      return;
    if (!status_file.is_open())
      {
        claim("run_status");
        status_file.open(file("run_status"));
      }
    status_file.write(status);
  }
} // namespace DynamicContact
