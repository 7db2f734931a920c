// Reading a parameter file (.prm, .json, .xml) and --set overrides, with
// errors that name the entry as Section/Entry and the file.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/gmsh_file.h>
#include <dynamic_contact/base/plugins.h>
#include <dynamic_contact/laws/foundation.h>
#include <dynamic_contact/laws/friction_law.h>
#include <dynamic_contact/parameters/parameters.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    /** A UTF-8 byte order mark at the start of a text (tolerated). */
    std::string
    without_bom(const std::string &text)
    {
      return text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text;
    }

    std::string
    read_file(const std::string &file)
    {
      std::ifstream      in(file, std::ios::binary);
      std::ostringstream s;
      s << in.rdbuf();
      return s.str();
    }

    /**
     * A parameter file (or a file it includes) must be a regular file: a
     * directory reads as nothing, and a named pipe blocks the reader and
     * cannot be read twice (the file is read more than once).
     */
    void
    check_file_kind(const std::string &file, const std::string &included_by)
    {
      namespace fs = std::filesystem;
      const std::string what =
        included_by.empty() ?
          "The parameter file '" + file + "'" :
          "The file '" + file + "' (included by '" + included_by + "')";
      const std::string cannot_open =
        included_by.empty() ? "Cannot open the parameter file '" + file + "'." :
                              "Cannot open the file '" + file +
                                "' (included by '" + included_by + "').";
      std::error_code ec;
      const auto      status = fs::status(file, ec);
      AssertThrow(!ec && fs::exists(status), ExcMessage(cannot_open));
      AssertThrow(!fs::is_directory(status),
                  ExcMessage(what + " is a directory, not a parameter file."));
      const std::string kind = fs::is_fifo(status)   ? "a named pipe" :
                               fs::is_socket(status) ? "a socket" :
                               fs::is_character_file(status) ?
                                                       "a character device" :
                               fs::is_block_file(status) ? "a block device" :
                                                           "not a regular file";
      AssertThrow(fs::is_regular_file(status),
                  ExcMessage(what + " is " + kind +
                             ", not a regular file: the program reads its "
                             "parameter file more than once; save it to a "
                             "file first."));
      std::ifstream in(file);
      AssertThrow(static_cast<bool>(in), ExcMessage(cannot_open));
    }

    /**
     * Follow the include statements (resolved as deal.II does, against the
     * working directory): every included file must be a regular file, and
     * none may include itself, directly or through others (the parser
     * would recurse without end).
     */
    void
    check_includes(const std::string        &file,
                   std::vector<std::string> &chain,
                   std::vector<std::string> &shown)
    {
      namespace fs = std::filesystem;
      std::istringstream lines(without_bom(read_file(file)));
      unsigned int       number = 0;
      for (std::string line; std::getline(lines, line);)
        {
          ++number;
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (line.rfind("include", 0) != 0 || line.size() < 8 ||
              (line[7] != ' ' && line[7] != '\t'))
            continue;
          const std::string included = Utilities::trim(line.substr(7));
          check_file_kind(included, file);
          std::error_code   ec;
          const std::string canonical =
            fs::weakly_canonical(included, ec).string();
          shown.push_back(included);
          if (std::find(chain.begin(), chain.end(), canonical) != chain.end())
            {
              std::string path;
              for (const auto &s : shown)
                path += (path.empty() ? "" : " -> ") + s;
              AssertThrow(false,
                          ExcMessage("The parameter file '" + shown[0] +
                                     "' includes itself (" + path + ", line " +
                                     std::to_string(number) + " of '" + file +
                                     "')."));
            }
          AssertThrow(chain.size() < 32,
                      ExcMessage("The parameter file '" + shown[0] +
                                 "' includes files more than 32 levels "
                                 "deep."));
          chain.push_back(canonical);
          check_includes(included, chain, shown);
          chain.pop_back();
          shown.pop_back();
        }
    }

    /**
     * The number of values a JSON or XML parameter file sets (the leaves of
     * its tree); throws an error naming the file if it is not valid JSON or
     * XML.
     */
    unsigned int
    count_structured_values(const std::string    &parameter_file,
                            const std::string    &text,
                            const ParameterFormat format)
    {
      namespace pt = boost::property_tree;
      pt::ptree tree;
      try
        {
          std::istringstream in(text);
          if (format == ParameterFormat::json)
            pt::read_json(in, tree);
          else
            pt::read_xml(in, tree);
        }
      catch (const pt::file_parser_error &e)
        {
          AssertThrow(
            false,
            ExcMessage(
              "The parameter file '" + parameter_file + "' is not valid " +
              (format == ParameterFormat::json ? "JSON" : "XML") + " (line " +
              std::to_string(e.line()) + ": " + e.message() + ")."));
        }
      const std::function<unsigned int(const pt::ptree &)> leaves =
        [&](const pt::ptree &t) -> unsigned int {
        unsigned int n = 0;
        for (const auto &child : t)
          if (child.first == "<xmlattr>" || child.first == "<xmlcomment>")
            continue;
          else if (child.second.empty())
            ++n;
          else
            n += leaves(child.second);
        return n;
      };
      return leaves(tree);
    }

    void
    check_readable(const std::string &parameter_file)
    {
      check_file_kind(parameter_file, "");
      const ParameterFormat format = parameter_format(parameter_file);
      if (format == ParameterFormat::prm)
        {
          std::error_code          ec;
          std::vector<std::string> chain = {
            std::filesystem::weakly_canonical(parameter_file, ec).string()};
          std::vector<std::string> shown = {parameter_file};
          check_includes(parameter_file, chain, shown);
        }
      const std::string text = without_bom(read_file(parameter_file));
      // A parameter file is text: refuse binary content with a clear message
      // rather than a confusing parse error about an unprintable line.
      // And a scene that sets nothing is a mistake, not the default scene.
      bool sets_something = false;
      if (format == ParameterFormat::prm)
        {
          std::istringstream lines(text);
          std::string        line;
          while (std::getline(lines, line))
            {
              line = Utilities::trim(line.substr(0, line.find('#')));
              if (line.rfind("set ", 0) == 0 || line.rfind("include ", 0) == 0)
                sets_something = true;
            }
        }
      unsigned int line = 1;
      for (const char c : text)
        {
          if (c == '\n')
            ++line;
          const unsigned char u = static_cast<unsigned char>(c);
          AssertThrow(!(u < 32 && c != '\n' && c != '\r' && c != '\t'),
                      ExcMessage("The parameter file '" + parameter_file +
                                 "' is not a text file (control character "
                                 "in line " +
                                 std::to_string(line) + ")."));
        }
      if (format != ParameterFormat::prm)
        sets_something =
          Utilities::trim(text).empty() ?
            false :
            count_structured_values(parameter_file, text, format) > 0;
      AssertThrow(sets_something,
                  ExcMessage("The parameter file '" + parameter_file +
                             "' is empty: it sets no parameter (write the "
                             "scene in it; --print-parameters lists every "
                             "parameter)."));
    }

    /** The subsection path ("A/B") open before line @p line of a file. */
    std::string
    subsection_path(const std::string &file, const unsigned int line)
    {
      std::istringstream       in(without_bom(read_file(file)));
      std::vector<std::string> path;
      std::string              text;
      for (unsigned int n = 1; n < line && std::getline(in, text); ++n)
        {
          text = Utilities::trim(text.substr(0, text.find('#')));
          if (text.rfind("subsection ", 0) == 0)
            path.push_back(Utilities::trim(text.substr(11)));
          else if (text == "end" && !path.empty())
            path.pop_back();
        }
      std::string result;
      for (const auto &p : path)
        result += p + "/";
      return result;
    }

    /** A pattern description as a user reads it. */
    std::string
    readable_pattern(const std::string &pattern)
    {
      if (pattern.rfind("[Double", 0) == 0)
        return "a number";
      if (pattern.rfind("[Integer", 0) == 0)
        {
          std::smatch m;
          if (std::regex_search(pattern,
                                m,
                                std::regex(R"(range (-?\d+)\.\.\.(-?\d+))")))
            return "an integer from " + m[1].str() + " to " + m[2].str();
          return "an integer";
        }
      if (pattern.rfind("[Bool", 0) == 0)
        return "true or false";
      if (pattern.rfind("[Selection", 0) == 0)
        return "one of " +
               Utilities::trim(pattern.substr(10, pattern.size() - 11));
      if (pattern.rfind("[List", 0) == 0)
        return "a comma-separated list (" + pattern + ")";
      return pattern;
    }

    /** Where @p path lives now if it moved (moved_entries()), else "". */
    std::string
    moved_entry(const std::string &path)
    {
      const auto &moves = moved_entries();
      const auto  found = moves.find(path);
      return found == moves.end() ? std::string() : found->second;
    }

    /** Why @p path is unknown: misspelt, or moved (and where to). */
    std::string
    unknown_entry(const std::string &path, const std::string &file)
    {
      const auto removed = removed_entries().find(path);
      if (removed != removed_entries().end())
        return "there is no parameter '" + path + "': it was removed (" +
               removed->second + ").";
      const std::string moved = moved_entry(path);
      if (moved.empty())
        return "there is no parameter '" + path +
               "' (misspelt? --print-parameters lists every parameter).";
      return "there is no parameter '" + path + "': it is now '" + moved +
             "' (each law, refinement strategy, contact solver and "
             "preconditioner has a subsection of its own; scripts/update-prm " +
             (file.empty() ? std::string("FILE") : "'" + file + "'") +
             " rewrites a parameter file of the old layout).";
    }

    /**
     * Rewrite a ParameterHandler error so that it names the parameter as
     * Section/Entry and the line: "line 2: Material/Density = 'abc' is not a
     * number."
     */
    std::string
    describe_parse_error(const std::string &file, const std::string &message)
    {
      std::smatch line_match;
      if (!std::regex_search(message,
                             line_match,
                             std::regex(
                               R"(Line <(\d+)> of file <[^:>]*>?:\s*)")))
        return "'" + file + "': " + message;
      const unsigned int line = std::stoi(line_match[1].str());
      const std::string  rest = line_match.suffix().str();
      const std::string  where =
        "'" + file + "', line " + std::to_string(line) + ": ";
      const std::string path = subsection_path(file, line);
      std::smatch       m;
      if (std::regex_search(rest,
                            m,
                            std::regex(
                              R"(No entry with name <([^>]*)> was declared)")))
        return where + unknown_entry(path + m[1].str(), file);
      if (
        std::regex_search(
          rest,
          m,
          std::regex(
            R"(The entry value (.*) for the entry named (.*) does not match the given pattern: (.*))")))
        return where + path + Utilities::trim(m[2].str()) + " = '" +
               Utilities::trim(m[1].str()) + "' is not " +
               readable_pattern(Utilities::trim(m[3].str())) + ".";
      if (std::regex_search(
            rest, m, std::regex(R"(no such subsection to be entered: (.*))")))
        {
          // deal.II names the whole path, its sections joined by '.'.
          std::string name        = Utilities::trim(m[1].str());
          std::string dotted_path = path;
          std::replace(dotted_path.begin(), dotted_path.end(), '/', '.');
          if (!dotted_path.empty() && name.rfind(dotted_path, 0) == 0)
            name = name.substr(dotted_path.size());
          return where + "there is no subsection '" + path + name +
                 "' (misspelt? --print-parameters lists every subsection).";
        }
      return where + rest;
    }

    /** How setting one entry went: set_entry(). */
    enum class SetResult
    {
      ok,
      undeclared,
      bad_value
    };

    /**
     * Set the entry "sections/entry" of @p prm to @p value; on failure
     * @p reason says why, naming the entry as Section/Entry.
     */
    SetResult
    set_entry(ParameterHandler               &prm,
              const std::vector<std::string> &sections,
              const std::string              &entry,
              const std::string              &value,
              std::string                    &reason)
    {
      unsigned int entered = 0;
      try
        {
          for (const auto &s : sections)
            {
              prm.enter_subsection(s);
              ++entered;
            }
          prm.set(entry, value);
        }
      catch (const std::exception &e)
        {
          for (; entered > 0; --entered)
            prm.leave_subsection();
          const std::string message = error_message(e);
          std::string       full_path;
          for (const auto &s : sections)
            full_path += s + "/";
          full_path += entry;
          std::smatch m;
          reason = message;
          if (message.find("not yet declared") != std::string::npos)
            {
              reason = unknown_entry(full_path, "");
              return SetResult::undeclared;
            }
          if (std::regex_search(
                message,
                m,
                std::regex(R"(does not match the given pattern <(.*)>)")))
            reason = full_path + " = '" + value + "' is not " +
                     readable_pattern(Utilities::trim(m[1].str())) + ".";
          return SetResult::bad_value;
        }
      for (; entered > 0; --entered)
        prm.leave_subsection();
      return SetResult::ok;
    }

    /** An XML name as ParameterHandler writes it ("Time_20step"), decoded. */
    std::string
    demangle(const std::string &name)
    {
      std::string result;
      for (std::size_t i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size() &&
            std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(name[i + 2])))
          {
            result +=
              static_cast<char>(std::stoi(name.substr(i + 1, 2), nullptr, 16));
            i += 2;
          }
        else
          result += name[i];
      return result;
    }

    /**
     * Set the entries of a JSON or XML tree in the form
     * ParameterHandler::print_parameters writes (every entry an object
     * with its "value"; also the value alone, as a scene written by hand
     * may give it: "End time": "2" or 2), subsections as objects. The
     * tree is read by deal.II's ParameterHandler conventions, the entries
     * set one by one so that an error names the entry as Section/Entry.
     */
    void
    set_entries(ParameterHandler                  &prm,
                const boost::property_tree::ptree &node,
                std::vector<std::string>          &path,
                const std::string                 &file,
                const bool                         xml,
                const bool                         skip_undefined)
    {
      for (const auto &[key, child] : node)
        {
          if (key == "<xmlattr>" || key == "<xmlcomment>")
            continue;
          const std::string name       = xml ? demangle(key) : key;
          const auto        value_node = child.find("value");
          if (value_node == child.not_found() && !child.empty())
            {
              path.push_back(name);
              set_entries(prm, child, path, file, xml, skip_undefined);
              path.pop_back();
              continue;
            }
          const std::string value = Utilities::trim(
            value_node == child.not_found() ? child.data() :
                                              value_node->second.data());
          std::string     reason;
          const SetResult result = set_entry(prm, path, name, value, reason);
          if (result == SetResult::ok ||
              (result == SetResult::undeclared && skip_undefined))
            continue;
          AssertThrow(false,
                      ExcMessage("Error in the parameter file '" + file +
                                 "': " + reason));
        }
    }

    void
    parse_structured_file(ParameterHandler  &prm,
                          const std::string &parameter_file,
                          const bool         xml,
                          const bool         skip_undefined)
    {
      namespace pt = boost::property_tree;
      pt::ptree          tree;
      std::istringstream in(without_bom(read_file(parameter_file)));
      // The syntax has been checked (check_readable).
      if (xml)
        pt::read_xml(in, tree);
      else
        pt::read_json(in, tree);
      std::vector<std::string> path;
      if (xml)
        {
          const auto root = tree.find("ParameterHandler");
          AssertThrow(root != tree.not_found() && tree.size() == 1,
                      ExcMessage("The parameter file '" + parameter_file +
                                 "' is not a parameter file in XML: its "
                                 "root element must be <ParameterHandler> "
                                 "(as --print-parameters=xml writes it)."));
          set_entries(
            prm, root->second, path, parameter_file, true, skip_undefined);
        }
      else
        set_entries(prm, tree, path, parameter_file, false, skip_undefined);
    }

    void
    parse_file(ParameterHandler  &prm,
               const std::string &parameter_file,
               const bool         skip_undefined)
    {
      const ParameterFormat format = parameter_format(parameter_file);
      if (format != ParameterFormat::prm)
        {
          parse_structured_file(prm,
                                parameter_file,
                                format == ParameterFormat::xml,
                                skip_undefined);
          return;
        }
      try
        {
          // Parsed from its text, so that a UTF-8 byte order mark (which
          // some editors write) is tolerated.
          std::istringstream in(without_bom(read_file(parameter_file)));
          prm.parse_input(in, parameter_file, "", skip_undefined);
        }
      catch (const std::exception &e)
        {
          AssertThrow(false,
                      ExcMessage("Error in the parameter file " +
                                 describe_parse_error(parameter_file,
                                                      error_message(e))));
        }
    }
  } // namespace


  const std::map<std::string, std::string> &
  moved_entries()
  {
    static const std::map<std::string, std::string> moves = {
      {"Foundation/Normal compliance stiffness",
       "Foundation/Normal compliance/Capped ramp/Stiffness"},
      {"Foundation/Compliance cap",
       "Foundation/Normal compliance/Capped ramp/Cap"},
      {"Foundation/Normal damping",
       "Foundation/Normal damping/Capped ramp/Coefficient"},
      {"Foundation/Damping cap", "Foundation/Normal damping/Capped ramp/Cap"},
      {"Foundation/Damping only in contact",
       "Foundation/Normal damping/Only in contact"},
      {"Friction/Coefficient", "Friction/Constant/Coefficient"},
      {"Friction/Static coefficient",
       "Friction/Exponential/Static coefficient"},
      {"Friction/Dynamic coefficient",
       "Friction/Exponential/Dynamic coefficient"},
      {"Friction/Decay rate", "Friction/Exponential/Decay rate"},
      {"Friction/Expression", "Friction/Expression/Function expression"},
      {"Friction/Expression constants",
       "Friction/Expression/Function constants"},
      {"Mesh refinement/Load window", "Mesh refinement/Load following/Window"},
      {"Mesh refinement/Load threshold",
       "Mesh refinement/Load following/Threshold"},
      {"Mesh refinement/Contact window",
       "Mesh refinement/Contact following/Window"},
      {"Mesh refinement/Refine fraction",
       "Mesh refinement/Error indicator/Refine fraction"},
      {"Mesh refinement/Coarsen fraction",
       "Mesh refinement/Error indicator/Coarsen fraction"},
      {"Solver/Condensed limit", "Solver/Condensed/Limit"},
      {"Solver/Condensed limit on several processes",
       "Solver/Condensed/Limit on several processes"},
      {"Solver/Provisional passes", "Solver/Condensed/Provisional passes"},
      {"Solver/AMG aggregation", "Solver/AMG/Aggregation"}};
    return moves;
  }


  const std::map<std::string, std::string> &
  removed_entries()
  {
    static const std::map<std::string, std::string> removed = {
      {"Friction/Acceleration depth",
       "Anderson acceleration of the convexification loop, which was "
       "slower than the plain loop in every scene measured; delete the "
       "line: the loop relaxes by Friction/Relaxation alone"},
      {"Mesh refinement/Load following/Look-ahead steps",
       "the load is sampled until the next adaptation ('Refine every' "
       "steps), as its default did; delete the line, and widen the refined "
       "zone with Mesh refinement/Load following/Window"},
      {"Mesh refinement/Look-ahead steps",
       "the load is sampled until the next adaptation ('Refine every' "
       "steps), as its default did; delete the line, and widen the refined "
       "zone with Mesh refinement/Load following/Window"},
      {"Time/Spectral radius at infinity",
       "each time scheme has a subsection of its own: set "
       "Time/Bathe/Spectral radius at infinity or Time/Sdirk/Spectral "
       "radius at infinity, for the scheme Time/Scheme names"}};
    return removed;
  }


  ParameterFormat
  parameter_format(const std::string &parameter_file)
  {
    std::string extension =
      std::filesystem::path(parameter_file).extension().string();
    std::transform(extension.begin(),
                   extension.end(),
                   extension.begin(),
                   [](const unsigned char c) { return std::tolower(c); });
    if (extension == ".json")
      return ParameterFormat::json;
    if (extension == ".xml")
      return ParameterFormat::xml;
    return ParameterFormat::prm;
  }


  void
  apply_override(ParameterHandler &prm, const std::string &assignment)
  {
    const auto equal = assignment.find('=');
    AssertThrow(equal != std::string::npos,
                ExcMessage("--set '" + assignment +
                           "': expected 'Section/Entry=value'."));
    std::string path  = Utilities::trim(assignment.substr(0, equal));
    std::string value = Utilities::trim(assignment.substr(equal + 1));

    std::vector<std::string> sections;
    std::string::size_type   slash;
    while ((slash = path.find('/')) != std::string::npos)
      {
        sections.push_back(Utilities::trim(path.substr(0, slash)));
        path = path.substr(slash + 1);
      }
    const std::string entry = Utilities::trim(path);

    std::string reason;
    if (set_entry(prm, sections, entry, value, reason) != SetResult::ok)
      AssertThrow(false, ExcMessage("--set '" + assignment + "': " + reason));
  }


  unsigned int
  read_dimension(const std::string              &parameter_file,
                 const std::vector<std::string> &overrides)
  {
    check_readable(parameter_file);
    ParameterHandler prm;
    prm.declare_entry("Dimension", "2", Patterns::Integer(2, 3), "");
    parse_file(prm, parameter_file, /*skip_undefined=*/true);
    for (const auto &o : overrides)
      if (Utilities::trim(o.substr(0, o.find('='))) == "Dimension")
        apply_override(prm, o);
    return prm.get_integer("Dimension");
  }


  RunParameters
  read_parameters(const std::string              &parameter_file,
                  const std::vector<std::string> &overrides,
                  ParameterHandler               &prm)
  {
    const unsigned int dim = read_dimension(parameter_file, overrides);
    RunParameters::declare_parameters(prm, dim);
    parse_file(prm, parameter_file, /*skip_undefined=*/false);
    for (const auto &o : overrides)
      apply_override(prm, o);

    RunParameters parameters;
    parameters.parameter_file = parameter_file;
    parameters.parse_parameters(prm);
    AssertThrow(parameters.dimension == dim,
                ExcMessage("Dimension changed between the two passes over '" +
                           parameter_file + "'."));
    return parameters;
  }
} // namespace DynamicContact
