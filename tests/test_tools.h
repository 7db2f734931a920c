#ifndef dynamic_contact_tests_test_tools_h
#define dynamic_contact_tests_test_tools_h

// Shared helpers of the .cc tests. deal.II's harness compares the file
// "output" that a test writes (rank 0 only) with NAME.output; the
// simulator's progress on stdout is then discarded.

#include <deal.II/base/function_lib.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/vector_tools_interpolate.h>

#include <dynamic_contact/bulk/discretization.h>

#include <dynamic_contact/laws/material.h>
#include <dynamic_contact/parameters/parameters.h>
#include <dynamic_contact/run/time_loop.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace test_tools
{
  /**
   * The main() of a test of named steps: MPI (one thread per process), then
   * each of @p tests in turn.
   */
  inline int
  run_tests(int                                       argc,
            char                                     *argv[],
            const std::vector<std::function<void()>> &tests)
  {
    dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    for (const auto &test : tests)
      test();
    return 0;
  }


  /** The finite element of a check: its dimension and degree. */
  struct Element
  {
    int          dim;
    unsigned int degree;
  };

  /**
   * @p f(std::integral_constant<int, dim>(), degree) for each of
   * @p elements in turn (dim 2 or 3).
   */
  template <typename F>
  void
  for_each_element(const std::vector<Element> &elements, const F &f)
  {
    for (const Element &e : elements)
      if (e.dim == 2)
        f(std::integral_constant<int, 2>(), e.degree);
      else
        f(std::integral_constant<int, 3>(), e.degree);
  }


  /**
   * The box (0, 2) x (0, 1) (x (0, 1)) of @p n cells in each direction, its
   * boundary ids by face (0 on the left, 2 at the bottom).
   */
  template <int dim>
  void
  make_box(dealii::Triangulation<dim> &triangulation, const unsigned int n)
  {
    dealii::GridGenerator::subdivided_hyper_rectangle(
      triangulation,
      std::vector<unsigned int>(dim, n),
      dealii::Point<dim>(),
      dim == 2 ? dealii::Point<dim>(2., 1.) : dealii::Point<dim>(2., 1., 1.),
      true);
  }

  /** Flag the locally owned cells of the left half (x < 1) for refinement. */
  template <int dim>
  void
  flag_left_half(dealii::Triangulation<dim> &triangulation)
  {
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && cell->center()[0] < 1.)
        cell->set_refine_flag();
  }

  /** Refine the cells of the left half (x < 1): hanging nodes. */
  template <int dim>
  void
  refine_left_half(dealii::Triangulation<dim> &triangulation)
  {
    flag_left_half(triangulation);
    triangulation.execute_coarsening_and_refinement();
  }


  /** The Mandel basis of symmetric tensors (orthonormal for ':'). */
  template <int dim>
  std::vector<dealii::SymmetricTensor<2, dim>>
  mandel_basis()
  {
    std::vector<dealii::SymmetricTensor<2, dim>> basis;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        {
          dealii::SymmetricTensor<2, dim> b;
          b[i][j] = (i == j ? 1. : 1. / std::sqrt(2.));
          basis.push_back(b);
        }
    return basis;
  }


  /**
   * The file the harness compares; written by rank 0 only (by the one
   * process of a test that does not initialize MPI).
   */
  inline std::ostream &
  out()
  {
    static std::ofstream file([]() {
      int initialized = 0;
      MPI_Initialized(&initialized);
      return (initialized == 0 ||
              dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0) ?
               "output" :
               "/dev/null";
    }());
    return file;
  }

  // Text and CSV files (the program's outputs as a user reads them).

  inline std::string
  read_text(const std::filesystem::path &file)
  {
    std::ifstream      in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  inline void
  write_text(const std::filesystem::path &file, const std::string &text)
  {
    std::ofstream out(file, std::ios::binary);
    out << text;
  }

  inline std::vector<std::string>
  lines_of(const std::string &text)
  {
    std::vector<std::string> lines;
    std::istringstream       in(text);
    for (std::string line; std::getline(in, line);)
      lines.push_back(line);
    return lines;
  }

  inline std::string
  trim(const std::string &s)
  {
    const auto begin = s.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos)
      return "";
    const auto end = s.find_last_not_of(" \t\r\n");
    return s.substr(begin, end - begin + 1);
  }

  inline std::vector<std::string>
  split(const std::string &s, const char separator)
  {
    std::vector<std::string> parts;
    std::istringstream       in(s);
    for (std::string part; std::getline(in, part, separator);)
      parts.push_back(trim(part));
    return parts;
  }

  /** The rows of a CSV file, split at commas (blank lines skipped). */
  inline std::vector<std::vector<std::string>>
  read_csv(const std::filesystem::path &file)
  {
    std::vector<std::vector<std::string>> rows;
    for (const auto &line : lines_of(read_text(file)))
      if (!trim(line).empty())
        rows.push_back(split(line, ','));
    return rows;
  }

  /**
   * Functions::CosineFunction (a smooth field) interpolated on @p d, in
   * master form (the constrained entries zero).
   */
  template <int dim>
  DynamicContact::Vector_t
  cosine_field(const DynamicContact::Discretization<dim> &d)
  {
    DynamicContact::Vector_t v;
    d.reinit_owned(v);
    dealii::VectorTools::interpolate(
      d.mapping, d.dof_handler, dealii::Functions::CosineFunction<dim>(dim), v);
    d.constraints.set_zero(v);
    return v;
  }


  /** Whether the first row of a CSV file is @p columns (comma-separated). */
  inline bool
  has_columns(const std::vector<std::vector<std::string>> &rows,
              const std::string                           &columns)
  {
    return !rows.empty() && rows.front() == split(columns, ',');
  }

  /** A scene file of the repository's prm/ directory. */
  inline std::string
  scene(const std::string &name)
  {
    return std::string(REPOSITORY_DIR) + "/prm/" + name;
  }

  /**
   * The settings of Time/Scheme = @p scheme with the spectral radius at
   * infinity @p rho_inf in the scheme's own subsection (Time/Bathe,
   * Time/Sdirk) where it is not the default 0.
   */
  inline std::vector<std::string>
  scheme_settings(const std::string &scheme, const double rho_inf)
  {
    std::vector<std::string> settings = {"Time/Scheme=" + scheme};
    if (rho_inf > 0)
      settings.push_back(
        "Time/" +
        DynamicContact::PluginRegistry<DynamicContact::StepScheme>::subsection(
          scheme) +
        "/Spectral radius at infinity=" + std::to_string(rho_inf));
    return settings;
  }

  /** Fail the test with a message (non-zero exit: the harness reports it). */
  inline void
  check(const bool condition, const std::string &what)
  {
    out() << (condition ? "OK:     " : "FAILED: ") << what << std::endl;
    if (!condition)
      {
        std::cerr << "FAILED: " << what << std::endl;
        std::exit(1);
      }
  }

  /** |a - b| <= tol max(|a|, |b|). */
  inline bool
  close(const double a, const double b, const double tol)
  {
    return std::abs(a - b) <= tol * std::max(std::abs(a), std::abs(b));
  }

  /** A number with n significant digits, for output that compares. */
  inline std::string
  digits(const double x, const unsigned int n = 4)
  {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.*e", n - 1, x);
    return buffer;
  }

  /** d f/d w by central differences (step 1e-6), f a vector function of w. */
  template <int dim, typename F>
  dealii::Tensor<2, dim>
  finite_difference(const F &f, const dealii::Tensor<1, dim> &w)
  {
    const double           h = 1e-6;
    dealii::Tensor<2, dim> J;
    for (unsigned int j = 0; j < dim; ++j)
      {
        dealii::Tensor<1, dim> e;
        e[j]                           = h;
        const dealii::Tensor<1, dim> d = (f(w + e) - f(w - e)) / (2 * h);
        for (unsigned int i = 0; i < dim; ++i)
          J[i][j] = d[i];
      }
    return J;
  }

  /** A quantity of a step: its name (for messages) and its value. */
  template <int dim>
  struct Quantity
  {
    std::string                                                    name;
    std::function<double(const DynamicContact::StepRecord<dim> &)> of;
    /** A force (compared relative to itself), else an energy (relative
     *  to the total energy). */
    bool force;
  };

  /** The quantities the tests compare between runs, by column name. */
  template <int dim>
  Quantity<dim>
  quantity(const std::string &name)
  {
    using R = DynamicContact::StepRecord<dim>;
    static const std::vector<Quantity<dim>> all = {
      {"normal_force", [](const R &r) { return r.normal_force; }, true},
      {"tangential_force", [](const R &r) { return r.tangential_force; }, true},
      {"reaction_force_y",
       [](const R &r) { return r.forces.reaction[1]; },
       true},
      {"kinetic_energy",
       [](const R &r) { return r.terms.energy.kinetic; },
       false},
      {"elastic_energy",
       [](const R &r) { return r.terms.energy.elastic; },
       false},
      {"foundation_energy",
       [](const R &r) { return r.terms.energy.foundation; },
       false},
      {"total_energy",
       [](const R &r) { return r.terms.energy.total(); },
       false},
      {"load_work", [](const R &r) { return r.terms.load_work; }, false},
      {"dissipation", [](const R &r) { return r.terms.dissipation(); }, false},
      {"remesh_energy_change",
       [](const R &r) { return r.remesh_energy_change; },
       false},
      {"dofs", [](const R &r) { return double(r.dofs); }, false},
      {"cells", [](const R &r) { return double(r.cells); }, false}};
    for (const auto &q : all)
      if (q.name == name)
        return q;
    throw std::runtime_error("test_tools::quantity: unknown '" + name + "'");
  }

  /**
   * The largest difference between two runs' time series over the steps
   * after the first, in the columns the solver comparisons use: forces
   * relative to themselves (at least 1 N), energies relative to the total
   * energy (at least 1 J). Infinite if the series differ in length.
   */
  template <int dim>
  double
  largest_difference(const std::vector<DynamicContact::StepRecord<dim>> &a,
                     const std::vector<DynamicContact::StepRecord<dim>> &b)
  {
    if (a.size() != b.size())
      return std::numeric_limits<double>::infinity();
    double worst = 0;
    for (unsigned int n = 1; n < a.size(); ++n)
      {
        const double scale = std::max(a[n].terms.energy.total(), 1.);
        for (const char *column : {"normal_force",
                                   "tangential_force",
                                   "kinetic_energy",
                                   "elastic_energy",
                                   "foundation_energy",
                                   "dissipation"})
          {
            const auto   q = quantity<dim>(column);
            const double x = q.of(a[n]), y = q.of(b[n]);
            worst =
              std::max(worst,
                       q.force ? std::abs(x - y) / std::max(std::abs(x), 1.) :
                                 std::abs(x - y) / scale);
          }
      }
    return worst;
  }

  /** The level of the active cell around @p p (collective). */
  inline int
  level_at(const DynamicContact::Simulator<2> &simulator,
           const dealii::Point<2>             &p)
  {
    const auto &d     = simulator.get_discretization();
    int         level = -1;
    try
      {
        const auto cell =
          dealii::GridTools::find_active_cell_around_point(d.mapping,
                                                           d.triangulation,
                                                           p);
        if (cell.first->is_locally_owned())
          level = cell.first->level();
      }
    catch (...)
      {}
    return dealii::Utilities::MPI::max(level, MPI_COMM_WORLD);
  }

  /**
   * Steel (rho = 7850, E = 2e11, nu = 0.3, plane stress in 2D) with the
   * viscosity tensor of Lame constants (@p viscosity_lambda,
   * @p viscosity_mu).
   */
  template <int dim>
  DynamicContact::KelvinVoigtMaterial<dim>
  steel(const double viscosity_lambda = 0, const double viscosity_mu = 0)
  {
    DynamicContact::Parameters::Material m;
    m.density       = 7850;
    m.young_modulus = 2e11;
    m.poisson_ratio = 0.3;
    m.plane_model =
      DynamicContact::Parameters::Material::PlaneModel::plane_stress;
    m.viscosity_lambda = viscosity_lambda;
    m.viscosity_mu     = viscosity_mu;
    return DynamicContact::KelvinVoigtMaterial<dim>(m);
  }


  /**
   * Read a scene with overrides (quiet, no timings, no VTU by default), run
   * it, and return the simulator for inspection.
   */
  template <int dim>
  std::unique_ptr<DynamicContact::TimeLoop<dim>>
  make(const std::string       &file,
       std::vector<std::string> overrides,
       const MPI_Comm           comm = MPI_COMM_WORLD)
  {
    overrides.insert(overrides.begin(),
                     {"Output/Print timings=false",
                      "Output/Progress every=0",
                      "Output/Write VTU=false"});
    dealii::ParameterHandler prm;
    const auto               parameters =
      DynamicContact::read_parameters(file, overrides, prm);
    return std::make_unique<DynamicContact::TimeLoop<dim>>(parameters,
                                                           prm,
                                                           comm);
  }

  template <int dim>
  std::unique_ptr<DynamicContact::TimeLoop<dim>>
  run(const std::string       &file,
      std::vector<std::string> overrides,
      const MPI_Comm           comm = MPI_COMM_WORLD)
  {
    auto simulator = make<dim>(file, overrides, comm);
    simulator->run();
    return simulator;
  }
} // namespace test_tools

#endif
