#ifndef dynamic_contact_face_load_quadrature_h
#define dynamic_contact_face_load_quadrature_h

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/bulk/scene.h>

#include <memory>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * The integrals of a surface load against the shape functions of a face,
   * F_i = int_face g . phi_i, to a tolerance: a load narrower than the cells
   * (a wheel patch a few centimetres wide on cells of 5 cm) is not resolved
   * by a fixed Gauss rule, and the whole solution scales with the error of
   * its resultant.
   *
   * Each face is integrated with the Gauss rule of degree + 2 points per
   * direction, iterated on 1, 2, 4, ... subintervals per direction, the
   * first rule whose result differs from the one before by at most
   *   tolerance * g_max * |face|
   * in every entry (g_max: the largest |g| at the points of the first rules
   * on every face, on every process). The rule before the first is the
   * Gauss-Lobatto rule of as many points, which has the face's vertices: a
   * load peaked just beyond a face's edge is small at the Gauss points and
   * large there. A face where the load is resolved costs twice the
   * evaluations of the fixed rule; a load narrower than the distance of
   * the points, inside a face, is not seen. The rule of a face depends
   * only on the load at the time of the call: the same answer in a resumed
   * run and on any number of processes. Boundary conditions/Load quadrature
   * tolerance = 0 is the fixed Gauss rule of degree + 2 points.
   */
  template <int dim>
  class FaceLoadQuadrature
  {
  public:
    /** A face that carries a load (Scene::face_load()). */
    struct Face
    {
      typename DoFHandler<dim>::active_cell_iterator cell;
      unsigned int                                   face;
      Function<dim>                                 *load;
    };

    explicit FaceLoadQuadrature(const Discretization<dim> &discretization);

    /**
     * values[f](i) = int_{face f} g(t) . phi_i for every shape function of
     * the face's cell (zero for those that vanish on the face), the loads of
     * @p scene at time @p t. Collective: every process calls it, with its
     * own faces.
     */
    void
    integrate(const Scene<dim>            &scene,
              const double                 t,
              const std::vector<Face>     &faces,
              std::vector<Vector<double>> &values) const;

    /** At most 2^max_level subintervals per direction on a face. */
    static constexpr unsigned int max_level = dim == 2 ? 7 : 4;

  private:
    const Discretization<dim> &discretization;

    /**
     * rules[0]: Gauss-Lobatto with degree + 2 points per direction;
     * rules[1 + l]:
     * Gauss with degree + 2 points iterated on 2^l subintervals. Built when
     * first needed.
     */
    mutable std::vector<std::unique_ptr<FEFaceValues<dim>>> rules;
    /** The load's value at a point. */
    mutable Vector<double> value;
    /** For each face of a cell: its shape functions and their components. */
    mutable std::vector<std::vector<std::pair<unsigned int, unsigned int>>>
      face_dofs;

    /**
     * Integrate face @p face with rule @p rule into @p result; returns the
     * largest |g| at its points. @p area receives the face's measure.
     */
    double
    integrate_with(const unsigned int rule,
                   const Face        &face,
                   Vector<double>    &result,
                   double            &area) const;
  };
} // namespace DynamicContact

#endif
