#ifndef dynamic_contact_gmsh_file_h
#define dynamic_contact_gmsh_file_h

#include <deal.II/base/types.h>

#include <map>
#include <string>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * What a Gmsh mesh file (.msh) holds, read by the program itself before
   * deal.II's GridIn sees the file: its format, how many elements of each
   * Gmsh element type, and its named physical groups. deal.II 9.4 reads
   * triangles and tetrahedra into a simplex mesh that this program (a
   * distributed hypercube mesh) cannot use, and does so without a message;
   * the scan lets check_gmsh_cells() refuse such a file with one that says
   * how to recombine the mesh in Gmsh.
   *
   * MSH 2.x and 4.x in ASCII are read; a binary file is recognized (and
   * refused by check_gmsh_cells(): GridIn reads ASCII only).
   */
  struct GmshFileInfo
  {
    /** "2.2", "4.1", ... as in $MeshFormat. */
    std::string version;
    bool        binary = false;
    /** Gmsh element type -> number of elements of that type. */
    std::map<int, unsigned long long> element_types;
    /** A $PhysicalNames entry: dimension, tag, name. */
    struct PhysicalName
    {
      int         dimension;
      int         tag;
      std::string name;
    };
    std::vector<PhysicalName> physical_names;
  };

  /**
   * Scan the Gmsh file @p file; a file that cannot be read or is not a
   * Gmsh mesh is an error naming "Geometry/Mesh file" and the file.
   */
  GmshFileInfo
  scan_gmsh_file(const std::string &file);

  /**
   * Refuse (an error naming "Geometry/Mesh file", the file and the element
   * type found) a mesh this program cannot use in @p dim dimensions:
   * triangles, tetrahedra, prisms or pyramids (with how to recombine them
   * into quadrilaterals or hexahedra in Gmsh), second-order elements, a
   * mesh of the other dimension, a binary file.
   */
  void
  check_gmsh_cells(const GmshFileInfo &info,
                   const std::string  &file,
                   const unsigned int  dim);

  /** The name of Gmsh element type @p type ("3-node triangle"). */
  std::string
  gmsh_element_name(const int type);

  /**
   * The physical groups of dimension @p dim - 1 (the boundary in @p dim
   * dimensions) by name: their tags are the boundary ids deal.II gives
   * the faces.
   */
  std::map<std::string, types::boundary_id>
  gmsh_boundary_names(const GmshFileInfo &info, const unsigned int dim);
} // namespace DynamicContact

#endif
