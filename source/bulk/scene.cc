#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/gmsh_file.h>
#include <dynamic_contact/bulk/scene.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace DynamicContact
{
  namespace
  {
    /**
     * Parse the function in subsection @p path (e.g. {"Boundary conditions",
     * "Traction"}) of @p prm into a ParsedFunction; errors name the path.
     */
    template <int dim>
    std::unique_ptr<Functions::ParsedFunction<dim>>
    parse_function(ParameterHandler                              &prm,
                   const std::vector<std::string>                &path,
                   const unsigned int                             n_components,
                   bool                                          &nonzero,
                   std::map<const Function<dim> *,
                            std::pair<std::string, std::string>> &expressions)
    {
      std::string name;
      for (const auto &s : path)
        name += s + "/";
      auto function =
        std::make_unique<Functions::ParsedFunction<dim>>(n_components);
      for (const auto &s : path)
        prm.enter_subsection(s);
      std::string expression;
      try
        {
          const SilenceStderr silence;
          expression = prm.get("Function expression");
          function->parse_parameters(prm);
          // Evaluate once: muparser reports some errors only then.
          Vector<double> values(n_components);
          function->vector_value(Point<dim>(), values);
        }
      catch (const std::exception &e)
        {
          for (unsigned int i = 0; i < path.size(); ++i)
            prm.leave_subsection();
          AssertThrow(false,
                      ExcMessage(name + "Function expression: cannot use '" +
                                 expression + "' (" +
                                 std::to_string(n_components) +
                                 " component(s), separated by ';'): " +
                                 expression_error_message(e)));
        }
      for (unsigned int i = 0; i < path.size(); ++i)
        prm.leave_subsection();

      // An expression that is literally zero in every component costs nothing.
      nonzero = false;
      for (const auto &c : Utilities::split_string_list(expression, ';'))
        if (c != "0" && c != "0.0" && c != "0." && c != "0e0")
          nonzero = true;
      expressions[function.get()] = {name.substr(0, name.size() - 1),
                                     expression};
      return function;
    }
  } // namespace


  template <int dim>
  Scene<dim>::Scene(const RunParameters &parameters, ParameterHandler &prm)
    : geometry(parameters.geometry)
    , boundaries(parameters.boundary_conditions)
    , traction_ids(boundaries.traction.begin(), boundaries.traction.end())
    , contact_ids(boundaries.contact.begin(), boundaries.contact.end())
  {
    bool unused;
    traction_function =
      parse_function<dim>(prm,
                          {"Boundary conditions", "Traction function"},
                          dim,
                          traction_nonzero,
                          expressions);
    body_force_function = parse_function<dim>(
      prm, {"Body force"}, dim, body_force_nonzero, expressions);
    initial_displacement_function = parse_function<dim>(
      prm, {"Initial conditions", "Displacement"}, dim, unused, expressions);
    initial_velocity_function = parse_function<dim>(
      prm, {"Initial conditions", "Velocity"}, dim, unused, expressions);
    initial_gap_function = parse_function<dim>(
      prm, {"Foundation", "Initial gap"}, 1, unused, expressions);
    contact_source_function =
      parse_function<dim>(prm,
                          {"Boundary conditions", "Contact source"},
                          dim,
                          contact_source_nonzero,
                          expressions);

    // The exact solution is optional: an empty expression means none.
    prm.enter_subsection("Exact solution");
    prm.enter_subsection("Displacement");
    const bool exact = !Utilities::trim(prm.get("Function expression")).empty();
    prm.leave_subsection();
    prm.leave_subsection();
    if (exact)
      {
        exact_displacement_function = parse_function<dim>(
          prm, {"Exact solution", "Displacement"}, dim, unused, expressions);
        exact_velocity_function = parse_function<dim>(
          prm, {"Exact solution", "Velocity"}, dim, unused, expressions);
      }
  }


  namespace
  {
    /**
     * The vertices of the locally owned cells of @p tria, each once: all of
     * them (@p body), those on the traction boundaries (@p on_traction) and
     * those on the contact boundaries (@p on_contact).
     */
    template <int dim>
    void
    owned_vertices(const Triangulation<dim>           &tria,
                   const std::set<types::boundary_id> &traction_ids,
                   const std::set<types::boundary_id> &contact_ids,
                   std::vector<Point<dim>>            &body,
                   std::vector<Point<dim>>            &on_traction,
                   std::vector<Point<dim>>            &on_contact)
    {
      std::set<unsigned int> body_seen, traction_seen, contact_seen;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            for (const unsigned int v : cell->vertex_indices())
              if (body_seen.insert(cell->vertex_index(v)).second)
                body.push_back(cell->vertex(v));
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary())
                {
                  const bool traction = traction_ids.count(face->boundary_id());
                  const bool contact  = contact_ids.count(face->boundary_id());
                  for (const unsigned int v : face->vertex_indices())
                    {
                      if (traction &&
                          traction_seen.insert(face->vertex_index(v)).second)
                        on_traction.push_back(face->vertex(v));
                      if (contact &&
                          contact_seen.insert(face->vertex_index(v)).second)
                        on_contact.push_back(face->vertex(v));
                    }
                }
          }
    }


    /**
     * The message for the first value of @p f at the @p points and the
     * times @p at that is not finite (naming @p f by its entry in
     * @p expressions, and the time if @p time_dependent), or an empty
     * string. Leaves @p f at time 0.
     */
    template <int dim>
    std::string
    first_non_finite_value(
      Function<dim>                 &f,
      const std::vector<Point<dim>> &points,
      const std::vector<double>     &at,
      const bool                     time_dependent,
      const std::map<const Function<dim> *, std::pair<std::string, std::string>>
        &expressions)
    {
      Vector<double> values(f.n_components);
      for (const double t : at)
        {
          f.set_time(t);
          for (const auto &p : points)
            {
              f.vector_value(p, values);
              for (unsigned int c = 0; c < f.n_components; ++c)
                if (!std::isfinite(values[c]))
                  {
                    const auto &[name, expression] = expressions.at(&f);
                    std::ostringstream m;
                    m << name << "/Function expression '" << expression
                      << "' is not finite";
                    if (f.n_components > 1)
                      m << " (component " << c + 1 << ")";
                    m << ": "
                      << (std::isnan(values[c]) ? "nan" :
                          values[c] > 0         ? "inf" :
                                                  "-inf")
                      << " at x = (";
                    for (unsigned int d = 0; d < dim; ++d)
                      m << (d ? ", " : "") << p[d];
                    m << ")";
                    if (time_dependent)
                      m << ", t = " << t;
                    m << ".";
                    f.set_time(0);
                    return m.str();
                  }
            }
        }
      f.set_time(0);
      return std::string();
    }
  } // namespace


  template <int dim>
  std::string
  Scene<dim>::non_finite_value(const Triangulation<dim>  &tria,
                               const std::vector<double> &times,
                               const bool                 initial) const
  {
    std::vector<Point<dim>> body, on_traction, on_contact;
    owned_vertices(
      tria, traction_ids, contact_ids, body, on_traction, on_contact);

    std::string               problem;
    const std::vector<double> zero = {0.};
    const auto                run  = [&](Function<dim>                 &f,
                         const std::vector<Point<dim>> &points,
                         const std::vector<double>     &at,
                         const bool                     time_dependent) {
      if (problem.empty())
        problem =
          first_non_finite_value(f, points, at, time_dependent, expressions);
    };
    run(*traction_function, on_traction, times, true);
    run(*contact_source_function, on_contact, times, true);
    run(*initial_gap_function, on_contact, zero, false);
    if (body_force_nonzero)
      run(*body_force_function, body, times, true);
    if (initial)
      {
        run(*initial_displacement_function, body, zero, false);
        run(*initial_velocity_function, body, zero, false);
      }
    if (exact_displacement_function)
      {
        run(*exact_displacement_function, body, times, true);
        run(*exact_velocity_function, body, times, true);
      }
    return problem;
  }


  template <int dim>
  void
  Scene<dim>::set_time(const double t) const
  {
    traction_function->set_time(t);
    body_force_function->set_time(t);
    contact_source_function->set_time(t);
  }


  std::string
  coarse_mesh_note(const std::vector<unsigned int> &repetitions,
                   const unsigned int               global_refinements,
                   const unsigned int               n_processes,
                   const bool                       adaptive)
  {
    double coarse = 1;
    for (const unsigned int r : repetitions)
      coarse *= r;
    if (n_processes < 2 || coarse < 1e5)
      return "";
    std::vector<unsigned int> fewer = repetitions;
    unsigned int              more  = 0;
    const auto                even  = [&fewer]() {
      for (const unsigned int r : fewer)
        if (r % 2 != 0)
          return false;
      return true;
    };
    // Geometry/Global refinements is at most 20.
    for (; even() && global_refinements + more < 20; ++more)
      for (unsigned int &r : fewer)
        r /= 2;
    std::ostringstream note;
    note << "every process holds the whole coarse mesh ("
         << static_cast<std::uint64_t>(coarse)
         << " cells of Geometry/Repetitions); ";
    if (more == 0)
      note << "fewer Repetitions with more Global refinements give a mesh "
              "of which a process holds only its part";
    else
      {
        note << "Repetitions = ";
        for (unsigned int d = 0; d < fewer.size(); ++d)
          note << (d > 0 ? ", " : "") << fewer[d];
        note << " with Global refinements = " << global_refinements + more
             << " give the same mesh, of which a process holds only its part";
        if (adaptive)
          note << " (with Mesh refinement/Minimum level and Maximum level "
                  "raised by "
               << more << ")";
      }
    return note.str();
  }


  template <int dim>
  void
  Scene<dim>::create_mesh(parallel::distributed::Triangulation<dim> &tria,
                          const bool refine_globally) const
  {
    if (geometry.type == Parameters::Geometry::Type::rectangle)
      {
        Point<dim> p1, p2;
        for (unsigned int d = 0; d < dim; ++d)
          {
            p1[d] = geometry.lower_left[d];
            p2[d] = geometry.upper_right[d];
          }
        GridGenerator::subdivided_hyper_rectangle(
          tria, geometry.repetitions, p1, p2, /*colorize=*/true);
      }
    else
      {
        // deal.II 9.4 reads triangles and tetrahedra into a simplex mesh
        // this program cannot use (without a message): look first.
        check_gmsh_cells(scan_gmsh_file(geometry.mesh_file),
                         geometry.mesh_file,
                         dim);
        GridIn<dim> grid_in;
        grid_in.attach_triangulation(tria);
        std::ifstream in(geometry.mesh_file);
        AssertThrow(static_cast<bool>(in),
                    ExcMessage("Geometry/Mesh file: cannot open '" +
                               geometry.mesh_file + "'."));
        try
          {
            grid_in.read_msh(in);
          }
        catch (const std::exception &e)
          {
            AssertThrow(false,
                        ExcMessage("Geometry/Mesh file: cannot read '" +
                                   geometry.mesh_file + "' as a Gmsh mesh in " +
                                   std::to_string(dim) +
                                   "D: " + error_message(e)));
          }
      }
    check_boundary_ids(tria);
    if (refine_globally)
      tria.refine_global(geometry.global_refinements);
  }


  template <int dim>
  void
  Scene<dim>::check_boundary_ids(const Triangulation<dim> &tria) const
  {
    // The coarse mesh is known to every process: no communication needed.
    std::set<types::boundary_id> mesh_ids;
    for (const auto &cell : tria.cell_iterators_on_level(0))
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          mesh_ids.insert(face->boundary_id());

    std::map<types::boundary_id, std::string> assigned;
    for (const auto &[id, list] : boundaries.all_ids())
      assigned[id] = list;

    // Where the ids come from, for the messages.
    std::string ids;
    for (const auto id : mesh_ids)
      ids += (ids.empty() ? "" : ", ") + std::to_string(id);
    const std::string mesh = geometry.type == Parameters::Geometry::Type::gmsh ?
                               "the mesh of Geometry/Mesh file '" +
                                 geometry.mesh_file +
                                 "' (its boundary ids: " + ids + ")" :
                               "the mesh (its boundary ids: " + ids + ")";

    // First what the prm names, then what it leaves out.
    for (const auto &[id, list] : assigned)
      AssertThrow(mesh_ids.count(id) == 1,
                  ExcMessage("Boundary conditions/" + list + ": boundary id " +
                             std::to_string(id) + " does not exist in " + mesh +
                             "."));
    for (const auto id : mesh_ids)
      AssertThrow(assigned.count(id) == 1,
                  ExcMessage("Boundary conditions: boundary id " +
                             std::to_string(id) + " of " + mesh +
                             " is not assigned a condition; list it in one "
                             "of Clamped, Roller, Traction, Contact, Free."));
  }


  template <int dim>
  Function<dim> *
  Scene<dim>::face_load(const typename Triangulation<dim>::cell_iterator &cell,
                        const unsigned int f) const
  {
    if (!cell->face(f)->at_boundary())
      return nullptr;
    const types::boundary_id id = cell->face(f)->boundary_id();
    if (traction_nonzero && traction_ids.count(id))
      return traction_function.get();
    if (contact_source_nonzero && contact_ids.count(id))
      return contact_source_function.get();
    return nullptr;
  }


  template <int dim>
  bool
  Scene<dim>::carries_load(
    const typename Triangulation<dim>::cell_iterator &cell) const
  {
    if (body_force_nonzero)
      return true;
    for (const auto f : cell->face_indices())
      if (face_load(cell, f) != nullptr)
        return true;
    return false;
  }


  template <int dim>
  void
  Scene<dim>::step_load(Function<dim>    &f,
                        const Point<dim> &p,
                        const double      t,
                        const TimeScheme &scheme,
                        Vector<double>   &value,
                        Vector<double>   &old_value) const
  {
    set_time(t);
    f.vector_value(p, value);
    if (!scheme.is_backward_euler())
      {
        set_time(t - scheme.time_step());
        f.vector_value(p, old_value);
        scheme.weigh(value, old_value);
      }
  }


  template class Scene<2>;
  template class Scene<3>;
} // namespace DynamicContact
