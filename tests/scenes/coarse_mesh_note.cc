// The advice the run's header gives for a large coarse rectangle on
// several processes (coarse_mesh_note): every process of a
// parallel::distributed::Triangulation holds the whole coarse mesh, so
// the program suggests the same mesh from fewer Repetitions and more
// Global refinements.
//  - no advice on one process or below 10^5 coarse cells; the advised
//    repetitions are the given ones halved while all are even, the
//    refinements grow by as many halvings, up to 20 in all; with an
//    adaptive mesh the advice raises the refinement levels by as much;
//    none possible (an odd repetition): the general advice;
//  - the advised mesh is the same mesh: the same active cells, the same
//    vertices and the same boundary faces with the same ids (colorized
//    box, as Geometry/Type = rectangle makes it), checked on small boxes
//    in 2D and 3D with the halvings the advice would make (and a control
//    without boundary ids, which the comparison must tell apart).

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <dynamic_contact/bulk/scene.h>

#include "test_tools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

using namespace DynamicContact;
using test_tools::out;

namespace
{
  void
  advise(const std::vector<unsigned int> &repetitions,
         const unsigned int               refinements,
         const unsigned int               processes,
         const bool                       adaptive = false)
  {
    out() << "repetitions";
    for (const unsigned int r : repetitions)
      out() << ' ' << r;
    out() << ", " << refinements << " refinements, " << processes
          << " processes" << (adaptive ? ", adaptive" : "") << ": ";
    const std::string note =
      coarse_mesh_note(repetitions, refinements, processes, adaptive);
    out() << (note.empty() ? "(none)" : note) << '\n';
  }


  // Sorted (rounded) coordinates of a mesh's vertices and of its boundary
  // faces' centres with their ids.
  template <int dim>
  std::pair<std::vector<std::array<long, dim>>,
            std::vector<std::pair<std::array<long, dim>, unsigned int>>>
  fingerprint(const Triangulation<dim> &tria, const double h)
  {
    const auto key = [h](const Point<dim> &p) {
      std::array<long, dim> k;
      for (unsigned int d = 0; d < dim; ++d)
        k[d] = std::lround(p[d] / h * 1024);
      return k;
    };
    std::vector<std::array<long, dim>> vertices;
    for (unsigned int v = 0; v < tria.n_vertices(); ++v)
      if (tria.get_used_vertices()[v])
        vertices.push_back(key(tria.get_vertices()[v]));
    std::vector<std::pair<std::array<long, dim>, unsigned int>> faces;
    for (const auto &cell : tria.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          faces.emplace_back(key(face->center()), face->boundary_id());
    std::sort(vertices.begin(), vertices.end());
    std::sort(faces.begin(), faces.end());
    return {vertices, faces};
  }


  template <int dim>
  void
  same_mesh(const std::vector<unsigned int> &repetitions,
            const unsigned int               refinements,
            const unsigned int               halvings,
            const bool                       control = false)
  {
    Point<dim> p1, p2;
    for (unsigned int d = 0; d < dim; ++d)
      {
        p1[d] = -0.3 * (d + 1);
        p2[d] = 1.7 + d;
      }
    std::vector<unsigned int> fewer = repetitions;
    for (unsigned int &r : fewer)
      r >>= halvings;
    Triangulation<dim> given, advised;
    GridGenerator::subdivided_hyper_rectangle(given, repetitions, p1, p2, true);
    given.refine_global(refinements);
    // The control: boundary ids left at 0, which the check must see.
    GridGenerator::subdivided_hyper_rectangle(
      advised, fewer, p1, p2, !control);
    advised.refine_global(refinements + halvings);
    // The smallest cell width sets the rounding of the coordinates.
    double h = 1e300;
    for (unsigned int d = 0; d < dim; ++d)
      h = std::min(h,
                   (p2[d] - p1[d]) / (repetitions[d] << refinements));
    const bool same = given.n_active_cells() == advised.n_active_cells() &&
                      fingerprint(given, h) == fingerprint(advised, h);
    out() << dim << "D, repetitions";
    for (const unsigned int r : repetitions)
      out() << ' ' << r;
    out() << " + " << refinements << " refinements against";
    for (const unsigned int r : fewer)
      out() << ' ' << r;
    out() << " + " << refinements + halvings
          << (control ? " (control, without boundary ids)" : "") << ": "
          << given.n_active_cells()
          << " cells, " << (same ? "the same mesh" : "DIFFERENT MESHES")
          << '\n';
  }
} // namespace


int
main()
{
  advise({320, 32, 32}, 0, 16);
  advise({320, 32, 32}, 0, 1);
  advise({220, 22, 22}, 1, 8);
  advise({310, 31, 31}, 0, 16);
  advise({80, 8, 8}, 0, 16);
  advise({400, 250}, 1, 2);
  advise({1024, 128}, 0, 3);
  advise({128, 128}, 0, 2);
  advise({320, 32, 32}, 1, 4, true);
  advise({1024, 1024}, 12, 2);

  same_mesh<2>({12, 8}, 0, 2);
  same_mesh<2>({20, 6}, 1, 1);
  same_mesh<3>({16, 4, 4}, 0, 2);
  same_mesh<3>({10, 2, 2}, 1, 1);
  same_mesh<3>({16, 4, 4}, 0, 2, true);
}
