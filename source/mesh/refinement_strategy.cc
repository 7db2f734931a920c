#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/error_estimator.h>

#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/mesh/refinement_strategy.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

namespace DynamicContact
{
  template <int dim>
  bool
  cell_near(const typename Triangulation<dim>::active_cell_iterator &cell,
            const std::vector<Point<dim>>                           &points,
            const double                                             window)
  {
    const Point<dim> c = cell->center();
    const double     r = window + 0.5 * cell->diameter();
    for (const auto &p : points)
      if (c.distance_square(p) <= r * r)
        return true;
    return false;
  }


  namespace
  {
    /**
     * A Window entry: a length >= 0, or 'auto' (returned as -1), named
     * @p entry in the error.
     */
    double
    parse_window(const std::string &text, const std::string &entry)
    {
      if (text == "auto")
        return -1;
      double value = -1;
      try
        {
          std::size_t end = 0;
          value           = std::stod(text, &end);
          if (end != text.size())
            value = -1;
        }
      catch (...)
        {}
      AssertThrow(std::isfinite(value) && value >= 0,
                  ExcMessage(entry + ": '" + text +
                             "' is neither a length >= 0 nor 'auto'."));
      return value;
    }


    /**
     * The thickness of the body: the smallest side of the bounding box of
     * the coarse mesh (which every process holds), a length of the scene.
     */
    template <int dim>
    double
    body_thickness(const Triangulation<dim> &tria)
    {
      Point<dim> lo, hi;
      bool       first = true;
      for (const auto &cell : tria.cell_iterators_on_level(0))
        for (const auto v : cell->vertex_indices())
          {
            const Point<dim> &p = cell->vertex(v);
            for (unsigned int c = 0; c < dim; ++c)
              {
                lo[c] = first ? p[c] : std::min(lo[c], p[c]);
                hi[c] = first ? p[c] : std::max(hi[c], p[c]);
              }
            first = false;
          }
      double thickness = hi[0] - lo[0];
      for (unsigned int c = 1; c < dim; ++c)
        thickness = std::min(thickness, hi[c] - lo[c]);
      return thickness;
    }


    /** @p window, or for 'auto' (-1) @p factor times the body's thickness. */
    template <int dim>
    double
    resolved_window(const double              window,
                    const double              factor,
                    const Triangulation<dim> &tria)
    {
      return window >= 0 ? window : factor * body_thickness(tria);
    }


    /**
     * Declare the entry Window of a strategy that gives the finest level
     * near some points: "Cells closer than this (m) to @p near get the
     * finest level.", then @p note and the meaning of 'auto': @p factor
     * (a word) the body's thickness.
     */
    void
    declare_window(ParameterHandler  &prm,
                   const std::string &near,
                   const std::string &note,
                   const std::string &factor)
    {
      prm.declare_entry("Window",
                        "auto",
                        Patterns::Anything(),
                        "Cells closer than this (m) to " + near +
                          " get the finest level. " + note +
                          "'auto': " + factor +
                          " the body's thickness (the smallest side of the "
                          "coarse mesh's bounding box).");
    }


    /**
     * The levels that the finest level within @p window of @p points asks
     * for: the maximum level near a point, -1 (no wish) elsewhere.
     * @p points: a vector of points, or a reference to one that outlives
     * the levels.
     */
    template <int dim, typename Points>
    typename RefinementStrategy<dim>::Levels
    finest_near(Points points, const double window)
    {
      return
        [window, points = std::move(points)](const auto        &cell,
                                             const unsigned int max_level) {
          return cell_near<dim>(cell, points, window) ?
                   static_cast<int>(max_level) :
                   -1;
        };
    }
  } // namespace


  template <int dim>
  std::vector<std::unique_ptr<const RefinementStrategy<dim>>>
  RefinementStrategy<dim>::create(ParameterHandler               &prm,
                                  const std::vector<std::string> &names)
  {
    const ScopedSubsection section(prm, "Mesh refinement");
    std::vector<std::unique_ptr<const RefinementStrategy<dim>>> strategies;
    for (const auto &name : names)
      strategies.push_back(
        PluginRegistry<RefinementStrategy<dim>>::instance().create(name, prm));
    return strategies;
  }


  void
  declare_refinement_strategies(ParameterHandler &prm)
  {
    const auto &strategies = PluginRegistry<RefinementStrategy<2>>::instance();
    prm.declare_entry(
      "Strategy",
      "none",
      Patterns::List(Patterns::Selection("none|" + strategies.names())),
      "How the mesh adapts, a list of: 'none' (a uniform mesh). " +
        strategies.documentation() +
        " With several, every cell gets the finest level any of them asks "
        "for; cells none asks for are coarsened towards the minimum level "
        "(behind the load). Each strategy has its parameters in the "
        "subsection of its name.");
    strategies.declare_subsections(prm);
  }


  namespace
  {
    /**
     * The points where the load (traction or body force) is large at some
     * time of [t0, t1] (every process): its magnitude sampled at face and
     * cell quadrature points, above @p threshold times its maximum.
     */
    template <int dim>
    std::vector<Point<dim>>
    large_load_points(const AdaptationContext<dim> &c, const double threshold)
    {
      const auto  &d     = c.discretization;
      const auto  &scene = c.scene;
      const double t0 = c.t0, t1 = c.t1, k = c.k;
      const bool   body_force = scene.has_body_force();

      std::vector<double> times;
      for (double t = t0; t <= t1 * (1 + 1e-12) + 1e-300; t += k)
        times.push_back(t);
      if (times.empty() || times.back() < t1)
        times.push_back(t1);

      // Sample the load magnitude at face (traction) and cell (body force)
      // quadrature points, at every time; keep each point's largest value.
      const QGauss<dim - 1>   face_quadrature(2);
      const QGauss<dim>       quadrature(2);
      FEFaceValues<dim>       fe_face(d.mapping,
                                d.fe,
                                face_quadrature,
                                update_quadrature_points);
      FEValues<dim>           fe_values =
        d.cell_values(quadrature, update_quadrature_points);
      std::vector<Point<dim>> points;
      std::vector<double>     magnitude;
      Vector<double>          value(dim);
      auto sample = [&](const Point<dim> &p, Function<dim> &f) {
        double largest = 0;
        for (const double t : times)
          {
            f.set_time(t);
            f.vector_value(p, value);
            largest = std::max(largest, value.l2_norm());
          }
        points.push_back(p);
        magnitude.push_back(largest);
      };
      for (const auto &cell : d.triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            // The traction (not the contact source of manufactured scenes).
            for (const auto f : cell->face_indices())
              if (scene.face_load(cell, f) == &scene.traction())
                {
                  fe_face.reinit(cell, f);
                  for (const auto &p : fe_face.get_quadrature_points())
                    sample(p, scene.traction());
                }
            if (body_force)
              {
                fe_values.reinit(cell);
                for (const auto &p : fe_values.get_quadrature_points())
                  sample(p, scene.body_force());
              }
          }
      const double largest =
        Utilities::MPI::max(magnitude.empty() ?
                              0. :
                              *std::max_element(magnitude.begin(),
                                                magnitude.end()),
                            d.comm);

      std::vector<Point<dim>> large;
      if (largest > 0)
        for (unsigned int i = 0; i < points.size(); ++i)
          if (magnitude[i] >= threshold * largest)
            large.push_back(points[i]);
      std::vector<Point<dim>> all;
      for (const auto &part : Utilities::MPI::all_gather(d.comm, large))
        all.insert(all.end(), part.begin(), part.end());
      return all;
    }

    /**
     * 'load following': the maximum level within Window of a point where
     * the traction (or body force) is large at some time until the next
     * adaptation, from the expressions.
     */
    template <int dim>
    class LoadFollowing : public RefinementStrategy<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_window(prm,
                       "a point where the load is large",
                       "It must reach from the loaded boundary to the "
                       "contact boundary if both should be fine. ",
                       "twice");
        prm.declare_entry("Threshold",
                          "0.05",
                          Patterns::Double(0, 1),
                          "The load is large where its magnitude exceeds "
                          "this fraction of its maximum.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        window    = parse_window(prm.get("Window"),
                              "Mesh refinement/Load following/Window");
        threshold = prm.get_double("Threshold");
      }

      typename RefinementStrategy<dim>::Levels
      levels(const AdaptationContext<dim> &context) const override
      {
        return finest_near<dim>(
          large_load_points(context, threshold),
          resolved_window(this->window,
                          2.,
                          context.discretization.triangulation));
      }

    private:
      double window    = -1; // auto
      double threshold = 0.05;
    };


    /**
     * 'contact following': the maximum level within Window of a node that
     * penetrates the foundation.
     */
    template <int dim>
    class ContactFollowing : public RefinementStrategy<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        declare_window(prm,
                       "a node that penetrates the foundation",
                       "",
                       "half");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        window = parse_window(prm.get("Window"),
                              "Mesh refinement/Contact following/Window");
      }

      typename RefinementStrategy<dim>::Levels
      levels(const AdaptationContext<dim> &context) const override
      {
        return finest_near<dim>(
          std::cref(context.contact_points),
          resolved_window(this->window,
                          0.5,
                          context.discretization.triangulation));
      }

      bool
      needs_contact_points() const override
      {
        return true;
      }

    private:
      double window = -1; // auto
    };


    /**
     * 'error indicator': one level up for the cells with the largest
     * Kelly indicator of u and w (normalized sum), one down for the
     * smallest, the others keep their level.
     */
    template <int dim>
    class ErrorIndicator : public RefinementStrategy<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Refine fraction",
                          "0.3",
                          Patterns::Double(0, 1),
                          "Fraction of the cells refined.");
        prm.declare_entry("Coarsen fraction",
                          "0.1",
                          Patterns::Double(0, 1),
                          "Fraction of the cells coarsened.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        refine_fraction  = prm.get_double("Refine fraction");
        coarsen_fraction = prm.get_double("Coarsen fraction");
        AssertThrow(refine_fraction + coarsen_fraction <= 1,
                    ExcMessage("Mesh refinement/Error indicator: Refine "
                               "fraction + Coarsen fraction must not exceed "
                               "1."));
      }

      typename RefinementStrategy<dim>::Levels
      levels(const AdaptationContext<dim> &context) const override
      {
        auto         &d    = context.discretization;
        auto         &tria = d.triangulation;
        Vector<float> eu(tria.n_active_cells()), ew(tria.n_active_cells());
        const QGauss<dim - 1> q(d.fe.degree + 1);
        KellyErrorEstimator<dim>::estimate(
          d.mapping, d.dof_handler, q, {}, context.u, eu);
        KellyErrorEstimator<dim>::estimate(
          d.mapping, d.dof_handler, q, {}, context.w, ew);
        const double mu =
          Utilities::MPI::max(static_cast<double>(eu.linfty_norm()), d.comm);
        const double mw =
          Utilities::MPI::max(static_cast<double>(ew.linfty_norm()), d.comm);
        Vector<float> indicator(tria.n_active_cells());
        for (unsigned int i = 0; i < indicator.size(); ++i)
          indicator(i) =
            (mu > 0 ? eu(i) / mu : 0.) + (mw > 0 ? ew(i) / mw : 0.);
        // p4est's parallel selection of the largest and smallest fractions
        // works on flags: read them and clear them again.
        parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
          tria, indicator, refine_fraction, coarsen_fraction);
        std::map<unsigned int, int> change; // active cell index -> +-1
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              if (cell->refine_flag_set())
                change[cell->active_cell_index()] = 1;
              else if (cell->coarsen_flag_set())
                change[cell->active_cell_index()] = -1;
              cell->clear_refine_flag();
              cell->clear_coarsen_flag();
            }
        return [change](const auto &cell, const unsigned int) {
          const auto found = change.find(cell->active_cell_index());
          return static_cast<int>(cell->level()) +
                 (found != change.end() ? found->second : 0);
        };
      }

    private:
      double refine_fraction  = 0.3;
      double coarsen_fraction = 0.1;
    };
  } // namespace


  DYNAMIC_CONTACT_REGISTER_STRATEGY(
    LoadFollowing,
    "load following",
    "the finest level in a window around where the "
    "traction and body force are large, predicted until the next "
    "adaptation from their expressions.");
  DYNAMIC_CONTACT_REGISTER_STRATEGY(
    ContactFollowing,
    "contact following",
    "the finest level around the nodes that penetrate the foundation.");
  DYNAMIC_CONTACT_REGISTER_STRATEGY(
    ErrorIndicator,
    "error indicator",
    "Kelly's indicator on displacement and velocity: the largest 'Refine "
    "fraction' of the cells refined, the smallest 'Coarsen fraction' "
    "coarsened.");

  template class RefinementStrategy<2>;
  template class RefinementStrategy<3>;
  template bool
  cell_near<2>(const Triangulation<2>::active_cell_iterator &,
               const std::vector<Point<2>> &,
               const double);
  template bool
  cell_near<3>(const Triangulation<3>::active_cell_iterator &,
               const std::vector<Point<3>> &,
               const double);
} // namespace DynamicContact
