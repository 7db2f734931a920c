#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/run/mesh_life_cycle.h>
#include <dynamic_contact/run/resources.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace DynamicContact
{
  template <int dim>
  CarriedFields<dim>::CarriedFields(Vector_t  &u,
                                    Vector_t  &w,
                                    const bool per_weight,
                                    const bool with_states)
    : per_weight(per_weight)
    , with_states(with_states)
    , fields{&u, &w, &friction}
  {
    if (with_states)
      fields.push_back(&states);
  }


  template <int dim>
  void
  CarriedFields<dim>::take(const ContactState<dim>    &state,
                           const Discretization<dim>  &discretization,
                           const ContactBoundary<dim> &boundary)
  {
    friction = state.friction_field(discretization, boundary, per_weight);
    if (with_states)
      states = state.state_field(discretization, boundary);
  }


  template <int dim>
  void
  CarriedFields<dim>::give_back(ContactState<dim>          &state,
                                const ContactBoundary<dim> &boundary) const
  {
    state.set_friction_from_field(boundary, friction, per_weight);
    if (with_states)
      state.set_state_from_field(boundary, states);
  }


  template <int dim>
  MeshLifeCycle<dim>::MeshLifeCycle(
    const RunParameters        &parameters,
    ParameterHandler           &prm,
    const Scene<dim>           &scene,
    Discretization<dim>        &discretization,
    const ContactBoundary<dim> &contact_boundary,
    const MPI_Comm              comm)
    : parameters(parameters)
    , scene(scene)
    , discretization(discretization)
    , contact_boundary(contact_boundary)
    , comm(comm)
    , mesh_adaptation(parameters.mesh_refinement, scene, discretization, prm)
  {}


  template <int dim>
  double
  MeshLifeCycle<dim>::create(TimerOutput &timer)
  {
    // The size of the scene is checked before it is allocated.
    const bool rectangle =
      parameters.geometry.type == Parameters::Geometry::Type::rectangle;
    double memory_per_process = 0;
    if (rectangle)
      {
        double n = 1;
        for (const unsigned int r : parameters.geometry.repetitions)
          n *= r;
        memory_per_process = check_resources(parameters, dim, n, comm);
      }
    TimerSection t(timer, "Setup: mesh");
    scene.create_mesh(discretization.triangulation, false);
    if (!rectangle)
      memory_per_process = check_resources(
        parameters, dim, discretization.triangulation.n_cells(0), comm);
    return memory_per_process;
  }


  template <int dim>
  double
  MeshLifeCycle<dim>::initial_dofs_estimate() const
  {
    const unsigned int p = discretization.fe.degree;
    const double       g = std::pow(2., parameters.geometry.global_refinements);
    if (parameters.geometry.type == Parameters::Geometry::Type::rectangle)
      {
        double vertices = 1;
        for (const unsigned int r : parameters.geometry.repetitions)
          vertices *= r * g * p + 1;
        return dim * vertices;
      }
    return dim * std::pow(g * p, dim) *
           discretization.triangulation.n_global_active_cells();
  }


  template <int dim>
  unsigned int
  MeshLifeCycle<dim>::processes_taking_part(std::string &note) const
  {
    const unsigned int n       = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int minimum = parameters.solver.min_dofs_per_process;
    const double       dofs    = initial_dofs_estimate();
    if (n == 1 || minimum == 0 || dofs >= double(n) * minimum)
      return n;
    const unsigned int m =
      std::max(1u, static_cast<unsigned int>(dofs / minimum));
    note = std::to_string(m) + " of " + std::to_string(n) +
           " processes take part (about " +
           std::to_string(static_cast<long long>(std::llround(dofs))) +
           " DoFs in the initial mesh, Solver/Minimum DoFs per process = " +
           std::to_string(minimum) + "); the others wait for them";
    return m;
  }


  template <int dim>
  std::string
  MeshLifeCycle<dim>::summary() const
  {
    std::ostringstream summary;
    summary << dim << "D, Q" << discretization.fe.degree << " elements, "
            << discretization.triangulation.n_global_active_cells()
            << " cells, " << discretization.dof_handler.n_dofs() << " DoFs, "
            << contact_boundary.n_global_nodes() << " contact nodes";
    return summary.str();
  }


  template <int dim>
  void
  MeshLifeCycle<dim>::refine_for_initial_load(
    const Vector_t              &u,
    const Vector_t              &w,
    const std::function<void()> &set_initial_conditions,
    const std::function<void()> &setup_dofs)
  {
    const double k = parameters.time.time_step;
    const double t1 =
      std::min(parameters.time.end_time, mesh_adaptation.lookahead_steps() * k);
    for (unsigned int cycle = 0; cycle < mesh_adaptation.max_cycles(); ++cycle)
      {
        set_initial_conditions();
        if (!flag_cells(0., t1, k, u, w))
          break;
        const auto before = mesh_adaptation.fingerprint();
        discretization.triangulation.execute_coarsening_and_refinement();
        setup_dofs();
        if (mesh_adaptation.fingerprint() == before)
          break;
      }
  }


  template <int dim>
  bool
  MeshLifeCycle<dim>::adapt(const double                 t0,
                            const double                 t1,
                            const double                 k,
                            Vector_t                    &u,
                            Vector_t                    &w,
                            ContactState<dim>           &contact_state,
                            const std::function<void()> &setup_dofs)
  {
    // What the next step needs, as finite element fields: u, w, and the
    // friction forces as a traction at the nodes of Gamma_3.
    CarriedFields<dim> carried(u,
                               w,
                               true,
                               parameters.friction.slip_length.active());
    bool               changed = false;
    for (unsigned int cycle = 0; cycle < mesh_adaptation.max_cycles(); ++cycle)
      {
        if (!flag_cells(t0, t1, k, u, w))
          break;
        carried.take(contact_state, discretization, contact_boundary);
        const auto before = mesh_adaptation.fingerprint();
        refine_and_transfer(discretization, carried.vectors(), setup_dofs);
        carried.give_back(contact_state, contact_boundary); // the new nodes
        changed = true;
        if (mesh_adaptation.fingerprint() == before)
          break;
      }
    return changed;
  }


  template <int dim>
  bool
  MeshLifeCycle<dim>::flag_cells(const double    t0,
                                 const double    t1,
                                 const double    k,
                                 const Vector_t &u,
                                 const Vector_t &w)
  {
    const Vector_t u_ghosted = discretization.expanded(u),
                   w_ghosted = discretization.expanded(w);
    return mesh_adaptation.flag_cells(
      t0, t1, k, penetrating_nodes(u), u_ghosted, w_ghosted);
  }


  template <int dim>
  std::vector<Point<dim>>
  MeshLifeCycle<dim>::penetrating_nodes(const Vector_t &u) const
  {
    // Only contact following asks for them (the same on every process).
    if (!mesh_adaptation.needs_contact_points())
      return {};
    std::vector<Point<dim>> local;
    for (const auto &node : contact_boundary.nodes())
      if (node.value(u) * node.normal - node.gap > 0)
        local.push_back(node.position);
    std::vector<Point<dim>> all;
    for (const auto &part : Utilities::MPI::all_gather(comm, local))
      all.insert(all.end(), part.begin(), part.end());
    return all;
  }


  template class CarriedFields<2>;
  template class CarriedFields<3>;
  template class MeshLifeCycle<2>;
  template class MeshLifeCycle<3>;
} // namespace DynamicContact
