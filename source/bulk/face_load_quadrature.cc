#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <dynamic_contact/bulk/face_load_quadrature.h>

#include <algorithm>
#include <cmath>

namespace DynamicContact
{
  template <int dim>
  FaceLoadQuadrature<dim>::FaceLoadQuadrature(
    const Discretization<dim> &discretization)
    : discretization(discretization)
    , rules(max_level + 2)
    , value(dim)
  {}


  template <int dim>
  double
  FaceLoadQuadrature<dim>::integrate_with(const unsigned int rule,
                                          const Face        &face,
                                          Vector<double>    &result,
                                          double            &area) const
  {
    const auto        &fe = discretization.fe;
    const unsigned int q  = fe.degree + 2;
    if (!rules[rule])
      {
        const Quadrature<dim - 1> quadrature =
          rule == 0 ? Quadrature<dim - 1>(QGaussLobatto<dim - 1>(q)) :
          rule == 1 ?
                      Quadrature<dim - 1>(QGauss<dim - 1>(q)) :
                      Quadrature<dim - 1>(
                        QIterated<dim - 1>(QGauss<1>(q), 1u << (rule - 1)));
        rules[rule] = std::make_unique<FEFaceValues<dim>>(
          discretization.mapping,
          fe,
          quadrature,
          update_values | update_quadrature_points | update_JxW_values);
      }
    FEFaceValues<dim> &fe_face = *rules[rule];
    fe_face.reinit(face.cell, face.face);
    const unsigned int n = fe.n_dofs_per_cell();
    result.reinit(n);
    area          = 0;
    double g_max  = 0;
    Function<dim> &g = *face.load;
    if (face_dofs.empty())
      for (const unsigned int f : GeometryInfo<dim>::face_indices())
        {
          face_dofs.emplace_back();
          for (unsigned int i = 0; i < n; ++i)
            if (fe.has_support_on_face(i, f))
              face_dofs.back().emplace_back(
                i, fe.system_to_component_index(i).first);
        }
    const auto &dofs = face_dofs[face.face];
    for (unsigned int p = 0; p < fe_face.n_quadrature_points; ++p)
      {
        g.vector_value(fe_face.quadrature_point(p), value);
        g_max = std::max(g_max, value.l2_norm());
        const double JxW = fe_face.JxW(p);
        area += JxW;
        for (const auto &[i, c] : dofs)
          result(i) += value(c) * fe_face.shape_value(i, p) * JxW;
      }
    return g_max;
  }


  template <int dim>
  void
  FaceLoadQuadrature<dim>::integrate(const Scene<dim>            &scene,
                                     const double                 t,
                                     const std::vector<Face>     &faces,
                                     std::vector<Vector<double>> &values) const
  {
    scene.set_time(t);
    const double tolerance =
      scene.boundary_conditions().load_quadrature_tolerance;
    values.resize(faces.size());
    if (tolerance == 0)
      {
        double area = 0;
        for (unsigned int f = 0; f < faces.size(); ++f)
          integrate_with(1, faces[f], values[f], area);
        return;
      }

    // On every face the Gauss rule and the Gauss-Lobatto rule of as many
    // points, which has the vertices (a load peaked just beyond a face's
    // edge is large there and small at the Gauss points), and the scale
    // g_max of the load.
    const auto max_difference = [](const Vector<double> &a,
                                   const Vector<double> &b) {
      double d = 0;
      for (unsigned int i = 0; i < a.size(); ++i)
        d = std::max(d, std::abs(a(i) - b(i)));
      return d;
    };
    std::vector<Vector<double>> lobatto(faces.size());
    std::vector<double>         areas(faces.size());
    double                      g_max = 0, area = 0;
    for (unsigned int f = 0; f < faces.size(); ++f)
      g_max = std::max({g_max,
                        integrate_with(1, faces[f], values[f], areas[f]),
                        integrate_with(0, faces[f], lobatto[f], area)});
    g_max = Utilities::MPI::max(g_max, discretization.comm);

    // Finer rules where the last two differ by more than the tolerance.
    Vector<double> coarse;
    for (unsigned int f = 0; f < faces.size(); ++f)
      {
        const double allowed    = tolerance * g_max * areas[f];
        double       difference = max_difference(values[f], lobatto[f]);
        unsigned int level      = 0;
        while (difference > allowed && level < max_level)
          {
            ++level;
            coarse.swap(values[f]);
            integrate_with(1 + level, faces[f], values[f], area);
            difference = max_difference(values[f], coarse);
          }
      }
  }


  template class FaceLoadQuadrature<2>;
  template class FaceLoadQuadrature<3>;
} // namespace DynamicContact
