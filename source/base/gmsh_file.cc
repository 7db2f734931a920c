#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <dynamic_contact/base/gmsh_file.h>

#include <fstream>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    /** The dimension of Gmsh element type @p type, -1 if not known here. */
    int
    element_dimension(const int type)
    {
      switch (type)
        {
          case 15:
            return 0;
          case 1:
          case 8:
            return 1;
          case 2:
          case 3:
          case 9:
          case 10:
          case 16:
            return 2;
          case 4:
          case 5:
          case 6:
          case 7:
          case 11:
          case 12:
          case 13:
          case 14:
          case 17:
          case 18:
          case 19:
            return 3;
          default:
            return -1;
        }
    }

    bool
    is_first_order_hypercube(const int type)
    {
      return type == 15 || type == 1 || type == 3 || type == 5;
    }

    bool
    is_first_order_simplex_or_wedge(const int type)
    {
      return type == 2 || type == 4 || type == 6 || type == 7;
    }

    /** "'file'" for messages: the parameter and the file. */
    std::string
    where(const std::string &file)
    {
      return "Geometry/Mesh file '" + file + "'";
    }

    [[noreturn]] void
    fail(const std::string &message)
    {
      AssertThrow(false, ExcMessage(message));
      std::abort();
    }

    /** "1234 3-node triangles (Gmsh element type 2)" */
    std::string
    count_of(const GmshFileInfo &info, const int type)
    {
      const auto  n    = info.element_types.at(type);
      std::string name = gmsh_element_name(type);
      if (n != 1)
        name = name.size() > 6 && name.substr(name.size() - 6) == "hedron" ?
                 name.substr(0, name.size() - 2) + "a" :
                 name + "s";
      return std::to_string(n) + " " + name + " (Gmsh element type " +
             std::to_string(type) + ")";
    }
  } // namespace


  std::string
  gmsh_element_name(const int type)
  {
    switch (type)
      {
          // clang-format off
        case 1:  return "2-node line";
        case 2:  return "3-node triangle";
        case 3:  return "4-node quadrilateral";
        case 4:  return "4-node tetrahedron";
        case 5:  return "8-node hexahedron";
        case 6:  return "6-node prism";
        case 7:  return "5-node pyramid";
        case 8:  return "3-node line";
        case 9:  return "6-node triangle";
        case 10: return "9-node quadrilateral";
        case 11: return "10-node tetrahedron";
        case 12: return "27-node hexahedron";
        case 13: return "18-node prism";
        case 14: return "14-node pyramid";
        case 15: return "1-node point";
        case 16: return "8-node quadrilateral";
        case 17: return "20-node hexahedron";
        case 18: return "15-node prism";
        case 19: return "13-node pyramid";
        default: return "element of type " + std::to_string(type);
          // clang-format on
      }
  }


  namespace
  {
    /** The lines of a Gmsh file, numbered, with the errors that name them. */
    class GmshLines
    {
    public:
      GmshLines(std::ifstream &in, const std::string &file)
        : in(in)
        , file(file)
      {}

      std::string        line;
      unsigned long long line_number = 0;

      /** The next line of @p section (a file that ends there is refused). */
      std::string &
      next(const std::string &section)
      {
        if (!std::getline(in, line))
          fail(where(file) + " ends inside its " + section + " section (line " +
               std::to_string(line_number) + "): the file is incomplete.");
        ++line_number;
        if (!line.empty() && line.back() == '\r')
          line.pop_back();
        return line;
      }

      [[noreturn]] void
      malformed(const std::string &section) const
      {
        fail(where(file) + ", line " + std::to_string(line_number) +
             ": cannot read this line of the " + section +
             " section; the file is not a Gmsh mesh file in the MSH 2 or 4 "
             "ASCII format.");
      }

      /** $PhysicalNames: dimension, tag and name of each group. */
      void
      read_physical_names(GmshFileInfo &info)
      {
        const std::string  section = "PhysicalNames";
        std::istringstream s(next(section));
        unsigned long      n = 0;
        if (!(s >> n))
          malformed(section);
        for (unsigned long i = 0; i < n; ++i)
          {
            std::istringstream         entry(next(section));
            GmshFileInfo::PhysicalName name;
            if (!(entry >> name.dimension >> name.tag))
              malformed(section);
            std::string rest;
            std::getline(entry, rest);
            const auto open  = rest.find('"');
            const auto close = rest.rfind('"');
            if (open == std::string::npos || close == open)
              malformed(section);
            name.name = rest.substr(open + 1, close - open - 1);
            info.physical_names.push_back(name);
          }
      }

      /** $Elements: how many elements of each type (MSH 2 or 4). */
      void
      read_elements(GmshFileInfo &info)
      {
        const std::string  section = "Elements";
        const int          major   = std::atoi(info.version.c_str());
        std::istringstream s(next(section));
        if (major == 2)
          {
            unsigned long long n = 0;
            if (!(s >> n))
              malformed(section);
            for (unsigned long long i = 0; i < n; ++i)
              {
                std::istringstream e(next(section));
                unsigned long long id   = 0;
                int                type = 0;
                if (!(e >> id >> type))
                  malformed(section);
                ++info.element_types[type];
              }
          }
        else
          {
            unsigned long long blocks = 0, n = 0;
            if (!(s >> blocks >> n))
              malformed(section);
            for (unsigned long long b = 0; b < blocks; ++b)
              {
                std::istringstream e(next(section));
                // 4.1: entityDim entityTag elementType count;
                // 4.0: entityTag entityDim elementType count.
                long long          a = 0, c = 0;
                int                type  = 0;
                unsigned long long count = 0;
                if (!(e >> a >> c >> type >> count))
                  malformed(section);
                info.element_types[type] += count;
                for (unsigned long long i = 0; i < count; ++i)
                  next(section);
              }
          }
      }

    private:
      std::ifstream     &in;
      const std::string &file;
    };
  } // namespace


  GmshFileInfo
  scan_gmsh_file(const std::string &file)
  {
    std::ifstream in(file, std::ios::binary);
    if (!in)
      fail(where(file) + ": cannot open the file.");
    GmshFileInfo info;
    GmshLines    lines(in, file);
    std::string &line = lines.line;

    bool first = true;
    while (std::getline(in, line))
      {
        ++lines.line_number;
        if (!line.empty() && line.back() == '\r')
          line.pop_back();
        line = Utilities::trim(line);
        if (line.empty())
          continue;
        if (first && line != "$MeshFormat")
          {
            if (line == "$NOD")
              fail(where(file) +
                   " is in the MSH 1 format; save it in the format 2.2 or "
                   "4.1 (gmsh -format msh22, or msh41).");
            fail(where(file) + " is not a Gmsh mesh file (its first line "
                               "is not $MeshFormat).");
          }
        first = false;
        if (line.empty() || line[0] != '$')
          continue;
        const std::string section = line.substr(1);
        const std::string end     = "$End" + section;
        if (section == "MeshFormat")
          {
            std::istringstream s(lines.next(section));
            int                file_type = 0;
            s >> info.version >> file_type;
            if (!s)
              lines.malformed(section);
            info.binary = (file_type == 1);
            if (info.binary)
              return info; // the rest is not text
            const int major = std::atoi(info.version.c_str());
            if (major != 2 && major != 4)
              fail(where(file) + " is in the MSH " + info.version +
                   " format; save it in the format 2.2 or 4.1.");
          }
        else if (section == "PhysicalNames")
          lines.read_physical_names(info);
        else if (section == "Elements")
          lines.read_elements(info);
        // Skip the rest of the section (or all of one not read here).
        while (Utilities::trim(line) != end)
          lines.next(section);
      }
    if (first)
      fail(where(file) + " is empty.");
    if (info.version.empty())
      fail(where(file) + " has no $MeshFormat section.");
    return info;
  }


  namespace
  {
    /** How to make a mesh of quadrilaterals (@p dim 2) or hexahedra in Gmsh. */
    std::string
    recombine_advice(const unsigned int dim)
    {
      return dim == 2 ?
               "Recombine the mesh into quadrilaterals in Gmsh: add "
               "'Mesh.RecombineAll = 1;' (or 'Recombine Surface{...};') and "
               "'Mesh.SubdivisionAlgorithm = 1;' (every cell a quadrilateral) "
               "to the .geo file, or run 'gmsh -2 -setnumber Mesh.RecombineAll "
               "1 -setnumber Mesh.SubdivisionAlgorithm 1 -format msh41 "
               "file.geo'." :
               "Make hexahedra in Gmsh: add 'Mesh.SubdivisionAlgorithm = 2;' "
               "(every cell split into hexahedra) to the .geo file, or "
               "extrude a recombined surface ('Extrude {...} { Surface{...}; "
               "Layers{n}; Recombine; }'), or run 'gmsh -3 -setnumber "
               "Mesh.SubdivisionAlgorithm 2 -format msh41 file.geo'.";
    }


    /**
     * Fail unless the mesh's dimension @p mesh_dim (that of its
     * highest-dimensional element) is @p dim; @p cells names the cells the
     * program needs.
     */
    void
    check_mesh_dimension(const GmshFileInfo &info,
                         const std::string  &file,
                         const unsigned int  dim,
                         const int           mesh_dim,
                         const std::string  &cells)
    {
      if (mesh_dim != static_cast<int>(dim))
        {
          std::string found;
          for (const auto &[type, n] : info.element_types)
            if (n > 0 && element_dimension(type) == mesh_dim)
              found += (found.empty() ? "" : ", ") + count_of(info, type);
          fail(where(file) + " is a mesh of dimension " +
               std::to_string(mesh_dim) + " (" + found + "), not " +
               std::to_string(dim) + ": set Dimension = " +
               std::to_string(mesh_dim) + " or use a mesh of " + cells +
               (mesh_dim == 2 && dim == 3 ?
                  "; a 3D mesh of a 2D one: extrude it in Gmsh (with "
                  "'Layers{n}; Recombine;')." :
                  "."));
        }
    }


    /**
     * Fail if the mesh holds first-order simplices, prisms or pyramids of
     * dimension @p dim or @p dim - 1 (the cells first: tetrahedra before
     * the triangles of their faces).
     */
    void
    check_no_simplices(const GmshFileInfo &info,
                       const std::string  &file,
                       const unsigned int  dim,
                       const std::string  &cells)
    {
      int simplex = -1;
      for (const auto &[type, n] : info.element_types)
        if (n > 0 && is_first_order_simplex_or_wedge(type) &&
            element_dimension(type) >= static_cast<int>(dim) - 1 &&
            (simplex < 0 ||
             element_dimension(type) > element_dimension(simplex)))
          simplex = type;
      if (simplex >= 0)
        {
          const int type = simplex;
          fail(where(file) + " holds " + count_of(info, type) +
               ": this program needs a mesh of " + cells + " in " +
               std::to_string(dim) + "D (deal.II's distributed meshes). " +
               recombine_advice(dim));
        }
    }


    /**
     * Fail if the mesh holds elements other than first-order hypercubes
     * (unknown ones or second-order ones).
     */
    void
    check_first_order_hypercubes(const GmshFileInfo &info,
                                 const std::string  &file,
                                 const std::string  &cells)
    {
      for (const auto &[type, n] : info.element_types)
        if (n > 0 && !is_first_order_hypercube(type))
          {
            if (element_dimension(type) < 0)
              fail(where(file) + " holds " + count_of(info, type) +
                   ", which this program does not read; it needs a mesh of "
                   "first-order " +
                   cells + ".");
            fail(where(file) + " holds " + count_of(info, type) +
                 ": second-order elements. The program needs "
                 "first-order " +
                 cells +
                 " (Gmsh: Mesh.ElementOrder = 1, the default; Finite "
                 "element/Polynomial degree sets the degree of the finite "
                 "elements).");
          }
    }
  } // namespace


  void
  check_gmsh_cells(const GmshFileInfo &info,
                   const std::string  &file,
                   const unsigned int  dim)
  {
    const std::string cells = dim == 2 ? "quadrilaterals" : "hexahedra";
    if (info.binary)
      fail(where(file) + " is a binary .msh file (MSH " + info.version +
           "); the program reads ASCII .msh files: save it without "
           "'binary' (Gmsh: Mesh.Binary = 0; or 'gmsh -" +
           std::to_string(dim) + " -format msh41 file.geo' without -bin).");

    // The dimension of the mesh: that of its highest-dimensional element.
    int mesh_dim = -1;
    for (const auto &[type, n] : info.element_types)
      if (n > 0)
        mesh_dim = std::max(mesh_dim, element_dimension(type));
    if (mesh_dim < 0)
      fail(where(file) + " holds no elements.");
    check_mesh_dimension(info, file, dim, mesh_dim, cells);

    // Then simplices, prisms and pyramids: the common mistake (Gmsh's
    // default mesh is of triangles or tetrahedra).
    check_no_simplices(info, file, dim, cells);
    check_first_order_hypercubes(info, file, cells);
  }


  std::map<std::string, types::boundary_id>
  gmsh_boundary_names(const GmshFileInfo &info, const unsigned int dim)
  {
    std::map<std::string, types::boundary_id> names;
    for (const auto &p : info.physical_names)
      if (p.dimension == static_cast<int>(dim) - 1 && p.tag >= 0)
        names.emplace(p.name, static_cast<types::boundary_id>(p.tag));
    return names;
  }
} // namespace DynamicContact
