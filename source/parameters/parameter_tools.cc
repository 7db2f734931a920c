// The helpers shared by the translation units that declare and parse the
// sections of a parameter file (parameter_tools.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/gmsh_file.h>
#include <dynamic_contact/parameters/parameters.h>

#include "parameter_tools.h"

#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace DynamicContact
{
  namespace ParameterTools
  {
    std::string
    zeros(const unsigned int n)
    {
      std::string s = "0";
      for (unsigned int i = 1; i < n; ++i)
        s += "; 0";
      return s;
    }

    std::vector<types::boundary_id>
    parse_ids(const std::string          &text,
              const std::string          &list,
              const Parameters::Geometry &geometry,
              const unsigned int          dim,
              std::optional<std::map<std::string, types::boundary_id>> &names)
    {
      std::vector<types::boundary_id> ids;
      for (const auto &item : Utilities::split_string_list(text))
        {
          const std::string entry = "Boundary conditions/" + list;
          if (!item.empty() &&
              item.find_first_not_of("0123456789") == std::string::npos)
            {
              const long id = item.size() > 3 ? 256 : std::stol(item);
              require(id <= 255,
                      entry + ": boundary id " + item +
                        " is out of range (0 to 255).");
              ids.push_back(static_cast<types::boundary_id>(id));
              continue;
            }
          require(!item.empty(),
                  entry + " = '" + text + "': an empty item in the list.");
          require(geometry.type == Parameters::Geometry::Type::gmsh,
                  entry + ": '" + item +
                    "' is not a boundary id (a number from 0 to 255); names "
                    "of physical groups need Geometry/Type = gmsh (the "
                    "rectangle's ids are 0/1 at x = min/max, 2/3 at y = "
                    "min/max, 4/5 at z = min/max).");
          if (!names)
            {
              // A mesh the program cannot use is the first thing to say.
              const GmshFileInfo info = scan_gmsh_file(geometry.mesh_file);
              check_gmsh_cells(info, geometry.mesh_file, dim);
              names = gmsh_boundary_names(info, dim);
            }
          const auto found = names->find(item);
          if (found == names->end())
            {
              std::string known;
              for (const auto &[name, id] : *names)
                known += (known.empty() ? "" : ", ") + ("'" + name + "'") +
                         " (" + std::to_string(id) + ")";
              require(false,
                      entry + ": '" + item +
                        "' is neither a boundary id nor the name of a "
                        "physical group of dimension " +
                        std::to_string(dim - 1) + " in Geometry/Mesh file '" +
                        geometry.mesh_file + "' (" +
                        (known.empty() ? std::string("it names none") :
                                         "its names: " + known) +
                        ").");
            }
          ids.push_back(found->second);
        }
      return ids;
    }

    void
    require(const bool condition, const std::string &message)
    {
      AssertThrow(condition, ExcMessage(message));
    }

    /**
     * Declare a subsection @p name holding a function of space and time in
     * the format of Functions::ParsedFunction (entries "Function constants",
     * "Function expression", "Variable names").
     */
    void
    declare_function(ParameterHandler  &prm,
                     const std::string &name,
                     const unsigned int dim,
                     const std::string &default_expression,
                     const std::string &documentation)
    {
      prm.enter_subsection(name);
      prm.declare_entry("Function constants",
                        "",
                        Patterns::Anything(),
                        "Constants used in the expression, as name=value "
                        "pairs separated by commas, e.g. 'F=1e10, c=2'.");
      prm.declare_entry("Function expression",
                        default_expression,
                        Patterns::Anything(),
                        documentation);
      prm.declare_entry("Variable names",
                        dim == 2 ? "x,y,t" : "x,y,z,t",
                        Patterns::Anything(),
                        "Names of the space coordinates and of time in the "
                        "expression.");
      prm.leave_subsection();
    }

  } // namespace ParameterTools
} // namespace DynamicContact
