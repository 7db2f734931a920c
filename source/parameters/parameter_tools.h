#ifndef dynamic_contact_parameter_tools_h
#define dynamic_contact_parameter_tools_h

// Helpers shared by the translation units that declare and parse the
// sections of a parameter file (source/parameters/parameters.cc,
// source/parameters/run_parameters.cc,
// source/parameters/solver_parameters.cc); internal to the library. Defined
// in source/parameters/parameter_tools.cc.

#include <deal.II/base/parameter_handler.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/number_or_auto.h>
#include <dynamic_contact/parameters/parameters.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace DynamicContact
{
  namespace ParameterTools
  {
    using namespace dealii;

    /** "0; 0" with @p n zeros (a vector-valued default). */
    std::string
    zeros(const unsigned int n);

    /** Throw an ExcMessage with @p message unless @p condition. */
    void
    require(const bool condition, const std::string &message);

    /**
     * A list of boundary ids (Boundary conditions/@p list): numbers 0 to
     * 255, or names of physical groups of the Gmsh mesh (@p names, read
     * from the mesh file when the first name is met).
     */
    std::vector<types::boundary_id>
    parse_ids(const std::string          &text,
              const std::string          &list,
              const Parameters::Geometry &geometry,
              const unsigned int          dim,
              std::optional<std::map<std::string, types::boundary_id>> &names);

    /**
     * Declare a subsection @p name holding a function of space and time in
     * the format of Functions::ParsedFunction.
     */
    void
    declare_function(ParameterHandler  &prm,
                     const std::string &name,
                     const unsigned int dim,
                     const std::string &default_expression,
                     const std::string &documentation);
  } // namespace ParameterTools
} // namespace DynamicContact

#endif
