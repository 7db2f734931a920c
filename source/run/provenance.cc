#include <deal.II/base/utilities.h>

#include <dynamic_contact/run/command_line.h>
#include <dynamic_contact/run/provenance.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <ctime>
#include <filesystem>
#include <regex>
#include <sstream>

namespace DynamicContact
{
  std::string
  utc_timestamp()
  {
    const std::time_t now = std::time(nullptr);
    std::tm           utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
  }


  std::string
  provenance_line(const unsigned int n_processes,
                  const unsigned int n_started,
                  const std::string &start)
  {
    return CommandLine::version_text() + ", " + std::to_string(n_processes) +
           " MPI process" + (n_processes == 1 ? "" : "es") +
           (n_started > n_processes ?
              " (of " + std::to_string(n_started) + " started)" :
              std::string()) +
           ", started " + start;
  }


  bool
  parse_print_format(const std::string &name, PrintFormat &format)
  {
    if (name == "prm")
      format = PrintFormat::prm;
    else if (name == "json")
      format = PrintFormat::json;
    else if (name == "xml")
      format = PrintFormat::xml;
    else if (name == "markdown" || name == "md")
      format = PrintFormat::markdown;
    else if (name == "moved")
      format = PrintFormat::moved;
    else
      return false;
    return true;
  }


  void
  print_parameters(std::ostream           &out,
                   const ParameterHandler &prm,
                   const PrintFormat       format)
  {
    switch (format)
      {
        case PrintFormat::prm:
          prm.print_parameters(out, ParameterHandler::PRM);
          break;
        case PrintFormat::json:
          prm.print_parameters(out, ParameterHandler::JSON);
          break;
        case PrintFormat::xml:
          prm.print_parameters(out, ParameterHandler::XML);
          out << '\n';
          break;
        case PrintFormat::markdown:
          out << parameters_markdown();
          break;
        case PrintFormat::moved:
          for (const auto &[old_path, new_path] : moved_entries())
            out << old_path << " = " << new_path << '\n';
          break;
      }
  }


  // ------------------------------------------------------------- markdown
  namespace
  {
    namespace pt = boost::property_tree;

    pt::ptree
    declarations(const unsigned int dim)
    {
      ParameterHandler prm;
      RunParameters::declare_parameters(prm, dim);
      std::stringstream json;
      prm.print_parameters(json, ParameterHandler::JSON);
      pt::ptree tree;
      pt::read_json(json, tree);
      return tree;
    }

    bool
    is_entry(const pt::ptree &node)
    {
      return node.find("value") != node.not_found() &&
             node.find("documentation") != node.not_found();
    }

    /** Text in `code`, with a backtick inside made harmless. */
    std::string
    code(const std::string &text)
    {
      if (text.empty())
        return "(empty)";
      if (text.find('`') != std::string::npos)
        return "`` " + text + " ``";
      return "`" + text + "`";
    }

    std::string
    bound(const std::string &x)
    {
      if (x == "MAX_DOUBLE" || x == "2147483647" || x == "4294967295")
        return "inf";
      if (x == "-MAX_DOUBLE" || x == "-2147483648")
        return "-inf";
      return x;
    }

    /** A deal.II pattern description as a reader wants it. */
    std::string
    allowed(const std::string &pattern)
    {
      std::smatch m;
      if (pattern == "[Anything]")
        return "any text";
      if (pattern.rfind("[Bool", 0) == 0)
        return "true or false";
      if (
        std::regex_match(
          pattern,
          m,
          std::regex(
            R"(\[(Double|Integer) range (\S+)\.\.\.(\S+) \(inclusive\)\])")) ||
        std::regex_match(
          pattern,
          m,
          std::regex(R"(\[(Double|Integer) (\S+)\.\.\.(\S+) \(inclusive\)\])")))
        {
          const std::string what =
            m[1].str() == "Double" ? "a number" : "an integer";
          const std::string lo = bound(m[2].str()), hi = bound(m[3].str());
          if (lo == "-inf" && hi == "inf")
            return what;
          if (hi == "inf")
            return what + " >= " + lo;
          if (lo == "-inf")
            return what + " <= " + hi;
          return what + " from " + lo + " to " + hi;
        }
      if (std::regex_match(pattern, m, std::regex(R"(\[Selection (.*) \])")))
        {
          std::string list;
          for (const auto &option :
               Utilities::split_string_list(m[1].str(), '|'))
            list += (list.empty() ? "" : ", ") + code(option);
          return "one of " + list;
        }
      if (
        std::regex_match(
          pattern,
          m,
          std::regex(
            R"(\[List of <(.*)> of length (\S+)\.\.\.(\S+) \(inclusive\)(?: separated by <(.*)>)?\])")))
        {
          const std::string lo = bound(m[2].str()), hi = bound(m[3].str());
          const std::string separator =
            m[4].matched ? m[4].str() : std::string(",");
          std::string length;
          if (lo == hi)
            length = lo + " ";
          else if (hi != "inf")
            length = lo + " to " + hi + " ";
          else if (lo != "0")
            length = "at least " + lo + " ";
          return "a list of " + length + "values separated by '" + separator +
                 "', each " + allowed(m[1].str());
        }
      return code(pattern);
    }

    void
    write_section(std::ostream      &out,
                  const pt::ptree   &node2,
                  const pt::ptree   *node3,
                  const std::string &path,
                  const unsigned int level)
    {
      // The entries first, then the subsections.
      for (const auto &[name, child] : node2)
        if (is_entry(child))
          {
            const std::string default2 =
              child.get<std::string>("default_value");
            const std::string pattern2 =
              Utilities::trim(child.get<std::string>("pattern_description"));
            std::string default3 = default2, pattern3 = pattern2;
            if (node3 != nullptr)
              {
                const auto it = node3->find(name);
                if (it != node3->not_found())
                  {
                    default3 = it->second.get<std::string>("default_value");
                    pattern3 = Utilities::trim(
                      it->second.get<std::string>("pattern_description"));
                  }
              }
            out << "- **" << name << "** = " << code(default2);
            if (default3 != default2)
              out << " (2D), " << code(default3) << " (3D)";
            out << "; " << allowed(pattern2);
            if (pattern3 != pattern2)
              out << " (2D), " << allowed(pattern3) << " (3D)";
            out << "\n";
            const std::string documentation =
              Utilities::trim(child.get<std::string>("documentation"));
            if (!documentation.empty())
              out << "  " << documentation << "\n";
          }
      for (const auto &[name, child] : node2)
        if (!is_entry(child))
          {
            const std::string sub    = path.empty() ? name : path + "/" + name;
            const pt::ptree  *child3 = nullptr;
            if (node3 != nullptr)
              {
                const auto it = node3->find(name);
                if (it != node3->not_found())
                  child3 = &it->second;
              }
            out << "\n"
                << std::string(std::min(level, 6u), '#') << " " << sub
                << "\n\n";
            write_section(out, child, child3, sub, level + 1);
          }
    }
  } // namespace


  std::string
  parameters_markdown()
  {
    const pt::ptree    two   = declarations(2);
    const pt::ptree    three = declarations(3);
    std::ostringstream out;
    out << "# Parameters\n"
           "\n"
           "<!-- Generated from the program's declarations: do not edit by "
           "hand, regenerate with\n"
           "     build/dynamic-contact --print-parameters=markdown > "
           "doc/parameters.md\n"
           "     (the test provenance fails while this file is stale). "
           "-->\n"
           "\n"
           "Every entry of a parameter file, by section, as\n"
           "`dynamic-contact --print-parameters` lists them: **name** = "
           "default;\n"
           "the values allowed (deal.II's pattern); what the entry means. "
           "Where the\n"
           "default depends on the dimension, both are given. A parameter "
           "file sets\n"
           "an entry `Entry` of section `Section` with `subsection Section`, "
           "`set Entry = value`,\n"
           "`end` (or in JSON or XML: README, \"Running a scene\"); `--set "
           "'Section/Entry=value'`\n"
           "overrides one on the command line.\n"
           "\n"
           "Units: the program takes every number in one consistent "
           "system of units; the\n"
           "texts name the SI unit (m, kg, s, N, Pa), and the defaults "
           "with a unit are the\n"
           "paper's values in SI. In mm-tonne-s or inch-lbf-s set them "
           "(`scripts/convert-units`\n"
           "writes a scene in another system: running.md, \"Units\").\n"
           "\n"
           "## Top level\n"
           "\n";
    write_section(out, two, &three, "", 2);
    return out.str();
  }


  // ------------------------------------------------------ parameter files
  ParameterFiles::ParameterFiles(ParameterHandler    &prm,
                                 const RunParameters &parameters)
  {
    // A relative mesh file is relative to the parameter file; the copy
    // lives elsewhere, so it names the mesh by its absolute path.
    std::string original_mesh_file;
    prm.enter_subsection("Geometry");
    original_mesh_file = prm.get("Mesh file");
    const bool gmsh =
      parameters.geometry.type == Parameters::Geometry::Type::gmsh &&
      !parameters.geometry.mesh_file.empty();
    if (gmsh)
      prm.set("Mesh file",
              std::filesystem::absolute(parameters.geometry.mesh_file)
                .lexically_normal()
                .string());
    prm.leave_subsection();
    std::ostringstream prm_text, json_text;
    prm_text << "# The parameters of the run that wrote this directory ("
             << CommandLine::version_text()
             << "):\n# the parameter file with the --set overrides applied. "
                "dynamic-contact parameters.prm\n# runs it again.\n";
    print_parameters(prm_text, prm, PrintFormat::prm);
    print_parameters(json_text, prm, PrintFormat::json);
    if (gmsh)
      {
        prm.enter_subsection("Geometry");
        prm.set("Mesh file", original_mesh_file);
        prm.leave_subsection();
      }
    this->prm  = prm_text.str();
    this->json = json_text.str();
  }


  void
  ParameterFiles::write(OutputDirectory &directory) const
  {
    directory.claim(
      std::vector<std::string>{"parameters.prm", "parameters.json"});
    write_file(directory.file("parameters.prm"), prm);
    write_file(directory.file("parameters.json"), json);
  }


  // ------------------------------------------------------------ ScreenLog
  ScreenLog::Tee::int_type
  ScreenLog::Tee::overflow(int_type c)
  {
    if (traits_type::eq_int_type(c, traits_type::eof()))
      return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    screen.put(ch);
    pending += ch;
    return c;
  }


  std::streamsize
  ScreenLog::Tee::xsputn(const char *s, std::streamsize n)
  {
    screen.write(s, n);
    pending.append(s, static_cast<std::size_t>(n));
    return n;
  }


  int
  ScreenLog::Tee::sync()
  {
    screen.flush();
    return screen ? 0 : -1;
  }


  ScreenLog::ScreenLog(std::ostream &screen)
    : std::ostream(nullptr)
    , tee(screen)
  {
    rdbuf(&tee);
  }


  ScreenLog::~ScreenLog()
  {
    rdbuf(nullptr);
  }


  void
  ScreenLog::open(OutputDirectory &directory, const bool append)
  {
    directory.claim("log.txt");
    const std::string name      = directory.file("log.txt");
    const bool        continued = append && std::filesystem::exists(name) &&
                           std::filesystem::file_size(name) > 0;
    file.open(name, append);
    if (continued)
      file.append("\n==== --resume ====\n");
    write_pending();
  }


  void
  ScreenLog::log_only(const std::string &text)
  {
    tee.pending += text;
  }


  void
  ScreenLog::write_pending()
  {
    if (!file.is_open() || tee.pending.empty())
      return;
    file.append(tee.pending);
    tee.pending.clear();
  }


  void
  ScreenLog::close()
  {
    write_pending();
    file.close();
  }
} // namespace DynamicContact
