#ifndef dynamic_contact_bulk_load_h
#define dynamic_contact_bulk_load_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/face_load_quadrature.h>
#include <dynamic_contact/bulk/linear_algebra.h>
#include <dynamic_contact/bulk/scene.h>

#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The load vector f_n = (f_0(t), v) + (f_2(t), v)_Gamma_2 of BulkOperator:
   * the locally owned cells with a load (Scene::carries_load) and their
   * loaded faces, found by the first assembly on a mesh, and the quadrature
   * of the surface loads (FaceLoadQuadrature).
   */
  template <int dim>
  class BulkLoad
  {
  public:
    explicit BulkLoad(const Discretization<dim> &discretization);

    /** Forget the loaded cells: the mesh changed. */
    void
    reinit()
    {
      loaded_cells_scene = nullptr;
    }

    /** BulkOperator::assemble_load_vector(). */
    void
    assemble(const Scene<dim> &scene, const double t, Vector_t &load) const;

  private:
    const Discretization<dim> &discretization;

    /**
     * The locally owned cells with a load, found by the first assemble() on
     * a mesh: the load of a step is assembled on them alone.
     */
    mutable std::vector<typename DoFHandler<dim>::active_cell_iterator>
                              loaded_cells;
    mutable const Scene<dim> *loaded_cells_scene = nullptr;
    /** Their loaded faces, and the index of each face's cell in the list. */
    mutable std::vector<typename FaceLoadQuadrature<dim>::Face> loaded_faces;
    mutable std::vector<unsigned int>   loaded_face_cell;
    mutable std::vector<Vector<double>> face_values;
    FaceLoadQuadrature<dim>             face_quadrature;
  };
} // namespace DynamicContact

#endif
