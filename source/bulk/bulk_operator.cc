#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>

#include <functional>
#include <set>
#include <unordered_map>

#include <dynamic_contact/bulk/bulk_operator.h>

namespace DynamicContact
{
  template <int dim>
  BulkOperator<dim>::BulkOperator(const Discretization<dim>      &d,
                                  const KelvinVoigtMaterial<dim> &material,
                                  const bool                      strain_norm)
    : discretization(d)
    , material(material)
    , strain_norm(strain_norm)
    , forms(d, material)
    , face_quadrature(d)
  {}


  template <int dim>
  void
  BulkOperator<dim>::reinit(const bool store)
  {
    reinit(store, true);
  }


  template <int dim>
  void
  BulkOperator<dim>::reinit(const bool store, const bool store_newton_matrix)
  {
    Assert(store_newton_matrix || !store,
           ExcMessage("Stored forms come with a stored K0."));
    loaded_cells_scene = nullptr; // the mesh changed
    stored             = store;
    newton_stored      = store_newton_matrix;
    // Every component with every other (K0 and the stiffness matrices),
    // and each component with itself alone (M: phi_i . phi_j vanishes
    // between components).
    Table<2, DoFTools::Coupling> all(dim, dim), same(dim, dim);
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int d = 0; d < dim; ++d)
        {
          all(c, d)  = DoFTools::always;
          same(c, d) = (c == d ? DoFTools::always : DoFTools::none);
        }
    std::vector<std::pair<TrilinosWrappers::SparsityPattern *,
                          Table<2, DoFTools::Coupling> *>>
      patterns;
    if (newton_stored)
      patterns.emplace_back(&pattern, &all);
    else
      pattern.clear();
    if (stored)
      patterns.emplace_back(&mass_pattern, &same);
    else
      mass_pattern.clear();
    for (auto [p, couplings] : patterns)
      {
        p->reinit(discretization.locally_owned,
                  discretization.locally_owned,
                  discretization.locally_relevant,
                  discretization.comm);
        DoFTools::make_sparsity_pattern(discretization.dof_handler,
                                        *couplings,
                                        *p,
                                        discretization.constraints,
                                        /*keep_constrained_dofs=*/false,
                                        Utilities::MPI::this_mpi_process(
                                          discretization.comm));
        p->compress();
      }
    if (newton_stored)
      bulk_matrix.reinit(pattern);
    else
      bulk_matrix.clear();
    for (Matrix_t *m : {&mass_matrix,
                        &elasticity_matrix,
                        &viscosity_matrix,
                        &strain_matrix})
      m->clear();
    if (stored)
      {
        forms.clear();
        assemble_forms();
      }
    else
      forms.reinit();
    current = TimeScheme();
    discretization.reinit_owned(tmp);
  }


  namespace
  {
    /**
     * The bulk assembly's loop: on each locally owned cell (each owned or
     * ghost cell that @p take accepts, if given), @p point(value, eps, JxW)
     * at each point of the quadrature QGauss(p + 1) with the shape
     * functions' values and symmetric gradients, then @p cell(dofs).
     */
    template <int dim, typename Point, typename Cell>
    void
    for_each_point(
      const Discretization<dim> &discretization,
      const Point               &point,
      const Cell                &cell_done,
      const std::function<bool(
        const typename DoFHandler<dim>::active_cell_iterator &)> &take = {})
    {
      const auto        &fe = discretization.fe;
      const QGauss<dim>  quadrature(fe.degree + 1);
      FEValues<dim>      fe_values = discretization.cell_values(
        quadrature, update_values | update_gradients | update_JxW_values);
      const unsigned int n = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> dofs(n);
      std::vector<SymmetricTensor<2, dim>> eps(n);
      std::vector<Tensor<1, dim>>          value(n);
      const FEValuesExtractors::Vector     displacement(0);
      for (const auto &cell :
           discretization.dof_handler.active_cell_iterators())
        if (take ? (!cell->is_artificial() && take(cell)) :
                   cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                for (unsigned int i = 0; i < n; ++i)
                  {
                    eps[i] = fe_values[displacement].symmetric_gradient(i, q);
                    value[i] = fe_values[displacement].value(i, q);
                  }
                point(value, eps, fe_values.JxW(q));
              }
            cell->get_dof_indices(dofs);
            cell_done(dofs);
          }
    }
  } // namespace


  template <int dim>
  void
  BulkOperator<dim>::assemble_forms()
  {
    mass_matrix.reinit(mass_pattern);
    elasticity_matrix.reinit(pattern);
    if (strain_norm)
      strain_matrix.reinit(pattern);
    if (material.has_viscosity())
      viscosity_matrix.reinit(pattern);

    const unsigned int n = discretization.fe.n_dofs_per_cell();
    FullMatrix<double> local_mass(n, n), local_elasticity(n, n),
      local_viscosity(n, n), local_strain(n, n);
    const auto &E = material.elasticity();
    const auto &C = material.viscosity();
    for_each_point(
      discretization,
      [&](const std::vector<Tensor<1, dim>>          &phi,
          const std::vector<SymmetricTensor<2, dim>> &eps,
          const double                                JxW) {
        for (unsigned int i = 0; i < n; ++i)
          {
            const auto E_eps_i = E * eps[i];
            const auto C_eps_i =
              material.has_viscosity() ? C * eps[i] : E_eps_i;
            for (unsigned int j = 0; j < n; ++j)
              {
                local_mass(i, j) += phi[i] * phi[j] * JxW;
                local_elasticity(i, j) += (E_eps_i * eps[j]) * JxW;
                if (strain_norm)
                  local_strain(i, j) += (eps[i] * eps[j]) * JxW;
                if (material.has_viscosity())
                  local_viscosity(i, j) += (C_eps_i * eps[j]) * JxW;
              }
          }
      },
      [&](const std::vector<types::global_dof_index> &dofs) {
        const auto &constraints = discretization.constraints;
        constraints.distribute_local_to_global(local_mass, dofs, mass_matrix);
        constraints.distribute_local_to_global(local_elasticity,
                                               dofs,
                                               elasticity_matrix);
        if (strain_norm)
          constraints.distribute_local_to_global(local_strain,
                                                 dofs,
                                                 strain_matrix);
        if (material.has_viscosity())
          constraints.distribute_local_to_global(local_viscosity,
                                                 dofs,
                                                 viscosity_matrix);
        for (auto *local :
             {&local_mass, &local_elasticity, &local_viscosity, &local_strain})
          *local = 0;
      });
    mass_matrix.compress(VectorOperation::add);
    elasticity_matrix.compress(VectorOperation::add);
    if (strain_norm)
      strain_matrix.compress(VectorOperation::add);
    if (material.has_viscosity())
      viscosity_matrix.compress(VectorOperation::add);
  }


  template <int dim>
  void
  BulkOperator<dim>::set_time_step(const TimeScheme &scheme)
  {
    Assert(scheme.time_step() > 0,
           ExcMessage("The time step must be positive."));
    if (scheme == current)
      return;
    kernel = BulkKernel<dim>(scheme, material);
    if (stored)
      {
        // K0 = (rho/k) M + theta A + theta^2 k B.
        bulk_matrix.copy_from(elasticity_matrix);
        bulk_matrix *= scheme.elasticity_coefficient();
        bulk_matrix.add(scheme.mass_coefficient(material.density()),
                        mass_matrix);
        if (material.has_viscosity())
          bulk_matrix.add(scheme.viscosity_coefficient(), viscosity_matrix);
      }
    else if (newton_stored)
      assemble_bulk_matrix(scheme);
    current = scheme;
  }


  template <int dim>
  template <typename Take, typename CellDone>
  void
  BulkOperator<dim>::for_each_cell_matrix(const BulkKernel<dim> &K,
                                          const Take            &take,
                                          const CellDone        &cell_done) const
  {
    // K0 = (rho/k) M + theta A + theta^2 k B, cell by cell.
    const unsigned int n = discretization.fe.n_dofs_per_cell();
    FullMatrix<double> local(n, n);
    std::vector<SymmetricTensor<2, dim>> stress(n);
    std::vector<Tensor<1, dim>>          inertia(n);
    for_each_point(
      discretization,
      [&](const std::vector<Tensor<1, dim>>          &value,
          const std::vector<SymmetricTensor<2, dim>> &eps,
          const double                                JxW) {
        for (unsigned int i = 0; i < n; ++i)
          {
            stress[i]  = (K.stiffness * eps[i]) * JxW;
            inertia[i] = value[i] * (K.mass * JxW);
          }
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            local(i, j) += inertia[i] * value[j] + stress[i] * eps[j];
      },
      [&](const std::vector<types::global_dof_index> &dofs) {
        cell_done(local, dofs);
        local = 0;
      },
      take);
  }


  template <int dim>
  void
  BulkOperator<dim>::assemble_bulk_matrix(const TimeScheme &scheme)
  {
    bulk_matrix = 0;
    for_each_cell_matrix(
      BulkKernel<dim>(scheme, material),
      std::function<bool(const typename DoFHandler<dim>::active_cell_iterator &)>(),
      [&](const FullMatrix<double>                   &local,
          const std::vector<types::global_dof_index> &dofs) {
        discretization.constraints.distribute_local_to_global(local,
                                                              dofs,
                                                              bulk_matrix);
      });
    bulk_matrix.compress(VectorOperation::add);
  }


  template <int dim>
  void
  BulkOperator<dim>::newton_vmult(Vector_t &dst, const Vector_t &src) const
  {
    if (newton_stored)
      bulk_matrix.vmult(dst, src);
    else
      forms.vmult(kernel, dst, src);
  }


  namespace
  {
    /**
     * Every process's @p nodes, in the order of the processes; @p first is
     * set to where this process's own nodes begin.
     */
    template <int dim>
    std::vector<std::array<types::global_dof_index, dim>>
    all_processes_nodes(
      const MPI_Comm                                               comm,
      const std::vector<std::array<types::global_dof_index, dim>> &nodes,
      unsigned int                                                &first)
    {
      const auto per_process = Utilities::MPI::all_gather(comm, nodes);
      std::vector<std::array<types::global_dof_index, dim>> all;
      first = 0;
      for (unsigned int r = 0; r < per_process.size(); ++r)
        {
          if (r == Utilities::MPI::this_mpi_process(comm))
            first = all.size();
          all.insert(all.end(), per_process[r].begin(), per_process[r].end());
        }
      return all;
    }


    /** Which node and component each DoF of the @p nodes is. */
    template <int dim>
    std::unordered_map<types::global_dof_index,
                       std::pair<unsigned int, unsigned int>>
    node_and_component_of(
      const std::vector<std::array<types::global_dof_index, dim>> &nodes)
    {
      std::unordered_map<types::global_dof_index,
                         std::pair<unsigned int, unsigned int>>
        node_of;
      for (unsigned int p = 0; p < nodes.size(); ++p)
        for (unsigned int a = 0; a < dim; ++a)
          node_of[nodes[p][a]] = {p, a};
      return node_of;
    }


    /**
     * A local DoF resolved into the nodes' DoFs: (node, component,
     * coefficient), as condensation resolves it.
     */
    struct NodePart
    {
      unsigned int node, component;
      double       coefficient;
    };


    /**
     * Resolve each of a cell's @p dofs into the nodes' DoFs (@p node_of),
     * through @p constraints, into @p parts. Returns whether any of them
     * touches a node.
     */
    bool
    resolve_into_nodes(
      const std::vector<types::global_dof_index> &dofs,
      const AffineConstraints<double>            &constraints,
      const std::unordered_map<types::global_dof_index,
                               std::pair<unsigned int, unsigned int>> &node_of,
      std::vector<std::vector<NodePart>>                              &parts)
    {
      const unsigned int n   = parts.size();
      bool               any = false;
      for (unsigned int i = 0; i < n; ++i)
        {
          parts[i].clear();
          const auto add = [&](const types::global_dof_index g,
                               const double                  c) {
            const auto found = node_of.find(g);
            if (found != node_of.end())
              parts[i].push_back(
                {found->second.first, found->second.second, c});
          };
          if (!constraints.is_constrained(dofs[i]))
            add(dofs[i], 1.);
          else if (const auto *entries =
                     constraints.get_constraint_entries(dofs[i]))
            for (const auto &[master, c] : *entries)
              add(master, c);
          any = any || !parts[i].empty();
        }
      return any;
    }


    /**
     * A constrained DoF's row and column are the stored K0's stand-in:
     * only its diagonal, here the mean of the node's other diagonal entries.
     */
    template <int dim>
    void
    stand_in_for_constrained_dofs(
      const std::vector<std::array<types::global_dof_index, dim>> &nodes,
      const AffineConstraints<double>                             &constraints,
      std::vector<Tensor<2, dim>>                                 &blocks)
    {
      for (unsigned int p = 0; p < nodes.size(); ++p)
        {
          double       sum  = 0;
          unsigned int free = 0;
          for (unsigned int a = 0; a < dim; ++a)
            if (!constraints.is_constrained(nodes[p][a]))
              {
                sum += blocks[p][a][a];
                ++free;
              }
          for (unsigned int a = 0; a < dim; ++a)
            if (constraints.is_constrained(nodes[p][a]))
              {
                for (unsigned int b = 0; b < dim; ++b)
                  blocks[p][a][b] = blocks[p][b][a] = 0;
                blocks[p][a][a] = free > 0 ? sum / free : 1.;
              }
        }
    }
  } // namespace


  template <int dim>
  std::vector<Tensor<2, dim>>
  BulkOperator<dim>::newton_blocks(
    const std::vector<std::array<types::global_dof_index, dim>> &nodes) const
  {
    std::vector<Tensor<2, dim>> blocks(nodes.size());
    if (newton_stored)
      {
        for (unsigned int p = 0; p < nodes.size(); ++p)
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int b = 0; b < dim; ++b)
              blocks[p][a][b] = bulk_matrix.el(nodes[p][a], nodes[p][b]);
        return blocks;
      }

    // Every process's nodes: each process sums what its own cells give to
    // any of them (a cell whose hanging node hangs on a node need not be
    // a ghost of the node's owner), then the sums are added up.
    const MPI_Comm     comm    = discretization.comm;
    unsigned int       first   = 0;
    const auto         all     = all_processes_nodes<dim>(comm, nodes, first);
    const auto         node_of = node_and_component_of<dim>(all);
    const auto        &constraints = discretization.constraints;
    const unsigned int n           = discretization.fe.n_dofs_per_cell();
    std::vector<std::vector<NodePart>>   parts(n);
    std::vector<types::global_dof_index> cell_dofs(n);
    std::vector<double>                  sums(all.size() * dim * dim, 0.);
    for_each_cell_matrix(
      kernel,
      std::function<bool(
        const typename DoFHandler<dim>::active_cell_iterator &)>(
        [&](const typename DoFHandler<dim>::active_cell_iterator &cell) {
          if (!cell->is_locally_owned())
            return false;
          cell->get_dof_indices(cell_dofs);
          return resolve_into_nodes(cell_dofs, constraints, node_of, parts);
        }),
      [&](const FullMatrix<double> &local,
          const std::vector<types::global_dof_index> &) {
        for (unsigned int i = 0; i < n; ++i)
          for (const NodePart &r : parts[i])
            for (unsigned int j = 0; j < n; ++j)
              for (const NodePart &c : parts[j])
                if (c.node == r.node)
                  sums[(r.node * dim + r.component) * dim + c.component] +=
                    r.coefficient * local(i, j) * c.coefficient;
      });
    Utilities::MPI::sum(sums, comm, sums);
    for (unsigned int p = 0; p < nodes.size(); ++p)
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          blocks[p][a][b] = sums[((first + p) * dim + a) * dim + b];
    stand_in_for_constrained_dofs<dim>(nodes, constraints, blocks);
    return blocks;
  }


  template <int dim>
  const Matrix_t &
  BulkOperator<dim>::matrix(const Form form) const
  {
    switch (form)
      {
        case Form::mass:
          return mass_matrix;
        case Form::elasticity:
          return elasticity_matrix;
        case Form::viscosity:
          return viscosity_matrix;
        default:
          return strain_matrix;
      }
  }


  template <int dim>
  double
  BulkOperator<dim>::product(const Form      form,
                             const Vector_t &x,
                             const Vector_t &y) const
  {
    if (!stored)
      return forms.product(form, x, y);
    matrix(form).vmult(tmp, y);
    return x * tmp;
  }


  template <int dim>
  void
  BulkOperator<dim>::vmult(const Form      form,
                           Vector_t       &dst,
                           const Vector_t &src) const
  {
    if (stored)
      matrix(form).vmult(dst, src);
    else
      forms.vmult(form, dst, src);
  }


  template <int dim>
  void
  BulkOperator<dim>::memory_consumption(MemoryItems &items) const
  {
    // Epetra keeps one graph (the column indices) per pattern, shared by
    // the matrices made from it; each matrix adds its values.
    const double rows  = discretization.locally_owned.n_elements();
    const auto   graph = [&](const std::string                       &name,
                           const TrilinosWrappers::SparsityPattern &p) {
      items.push_back({name,
                       double(p.trilinos_sparsity_pattern().NumMyNonzeros()) *
                           sizeof(int) +
                         rows * 2 * sizeof(int),
                       false});
    };
    const auto values = [&](const std::string &name, const Matrix_t &A) {
      items.push_back(
        {name, stored_values_bytes(A) + rows * sizeof(double *), false});
    };
    if (newton_stored)
      graph("sparsity pattern (shared)", pattern);
    if (stored)
      {
        graph("sparsity pattern of M", mass_pattern);
        values("mass matrix M", mass_matrix);
        values("elasticity matrix", elasticity_matrix);
        if (material.has_viscosity())
          values("viscosity matrix", viscosity_matrix);
        if (strain_norm)
          values("strain matrix (norm of V)", strain_matrix);
      }
    else
      items.push_back({"bulk forms (matrix-free cell data)",
                       forms.memory_consumption(),
                       false});
    if (newton_stored)
      values("bulk matrix K0", bulk_matrix);
  }


  template <int dim>
  void
  BulkOperator<dim>::assemble_load_vector(const Scene<dim> &scene,
                                          const double      t,
                                          Vector_t         &load) const
  {
    load                  = 0;
    const bool body_force = scene.has_body_force();
    const bool traction =
      scene.has_traction() && !scene.boundary_conditions().traction.empty();
    const bool source = scene.has_contact_source() &&
                        !scene.boundary_conditions().contact.empty();
    if (!body_force && !traction && !source)
      return;
    scene.set_time(t);

    const auto                          &fe = discretization.fe;
    const unsigned int                   n  = fe.n_dofs_per_cell();
    const QGauss<dim>                    quadrature(fe.degree + 2);
    FEValues<dim>                        fe_values = discretization.cell_values(
      quadrature, update_values | update_quadrature_points | update_JxW_values);
    Vector<double>                       local(n);
    Vector<double>                       value(dim);
    std::vector<types::global_dof_index> dofs(n);

    if (loaded_cells_scene != &scene)
      {
        loaded_cells.clear();
        loaded_faces.clear();
        loaded_face_cell.clear();
        for (const auto &cell :
             discretization.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && scene.carries_load(cell))
            {
              for (const auto f : cell->face_indices())
                if (Function<dim> *const g = scene.face_load(cell, f))
                  {
                    loaded_faces.push_back({cell, f, g});
                    loaded_face_cell.push_back(loaded_cells.size());
                  }
              loaded_cells.push_back(cell);
            }
        loaded_cells_scene = &scene;
      }
    // The surface loads, face by face, to their tolerance (collective).
    face_quadrature.integrate(scene, t, loaded_faces, face_values);
    unsigned int face = 0;
    for (unsigned int c = 0; c < loaded_cells.size(); ++c)
      {
        const auto &cell = loaded_cells[c];
        local            = 0;
        if (body_force)
          {
            fe_values.reinit(cell);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                scene.body_force().vector_value(fe_values.quadrature_point(q),
                                                value);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    const unsigned int c =
                      fe.system_to_component_index(i).first;
                    local(i) +=
                      value(c) * fe_values.shape_value(i, q) * fe_values.JxW(q);
                  }
              }
          }
        for (; face < loaded_faces.size() && loaded_face_cell[face] == c;
             ++face)
          local += face_values[face];
        // Every listed cell carries a load (a body force, a loaded face).
        cell->get_dof_indices(dofs);
        discretization.constraints.distribute_local_to_global(local,
                                                              dofs,
                                                              load);
      }
    load.compress(VectorOperation::add);
  }


  template class BulkOperator<2>;
  template class BulkOperator<3>;
} // namespace DynamicContact
