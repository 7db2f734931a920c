#ifndef dynamic_contact_parameter_tools_h
#define dynamic_contact_parameter_tools_h

// Helpers shared by the translation units that declare and parse the
// sections of a parameter file (source/parameters/parameters.cc,
// source/parameters/run_parameters.cc,
// source/parameters/solver_parameters.cc); internal to the library. Defined
// in source/parameters/parameter_tools.cc.

#include <deal.II/base/parameter_handler.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/parameters/parameters.h>

#include <functional>
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

    /**
     * The number that the whole of @p text is (read by @p read, e.g.
     * std::stol or std::stod), or std::nullopt for 'auto'; @p error
     * (CollectiveError) where it is neither or fails @p valid.
     */
    template <typename Number, typename Read>
    std::optional<Number>
    number_or_auto(const std::string                 &text,
                   const Read                        &read,
                   const std::function<bool(Number)> &valid,
                   const std::string                 &error)
    {
      if (text == "auto")
        return std::nullopt;
      std::size_t end   = 0;
      Number      value = 0;
      bool        read_ = false;
      try
        {
          value = read(text, &end);
          read_ = true;
        }
      catch (...)
        {}
      require(read_ && end == text.size() && valid(value), error);
      return value;
    }

  } // namespace ParameterTools
} // namespace DynamicContact

#endif
