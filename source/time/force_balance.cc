#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>

#include <dynamic_contact/time/force_balance.h>

#include <set>

namespace DynamicContact
{
  namespace
  {
    /** Constrained by a clamped or roller condition (not a hanging node). */
    template <int dim>
    bool
    supported(const Discretization<dim> &d, const types::global_dof_index dof)
    {
      return d.constraints.is_constrained(dof) &&
             !d.hanging_node_constraints.is_constrained(dof);
    }

    /**
     * Adds to @p residual the point @p q's part of a cell's residual of the
     * scheme's equation, (a - g) phi_i + sigma : eps(phi_i) times JxW, with
     * the inertia a = rho (w - w_old)/k, the load g and the stress sigma
     * at the point.
     */
    template <int dim>
    void
    add_point_residual(const FEValues<dim>           &fe_values,
                       const unsigned int             q,
                       const Tensor<1, dim>          &a,
                       const Vector<double>          &g,
                       const SymmetricTensor<2, dim> &sigma,
                       Vector<double>                &residual)
    {
      const FEValuesExtractors::Vector displacement(0);
      const auto                      &fe = fe_values.get_fe();
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        {
          const unsigned int c = fe.system_to_component_index(i).first;
          residual(i) +=
            ((a[c] - g(c)) * fe_values.shape_value(i, q) +
             scalar_product(sigma,
                            fe_values[displacement].symmetric_gradient(i, q))) *
            fe_values.JxW(q);
        }
    }


    /**
     * A loaded face's force @p face_value (its integrals per cell DoF) into
     * the applied force, and on a cell with a support out of its residual.
     * The shape functions sum to one: a face's force is the sum of its
     * integrals per component.
     */
    template <int dim>
    void
    add_face_load(const FiniteElement<dim> &fe,
                  const Vector<double>     &face_value,
                  const bool                has_support,
                  Tensor<1, dim>           &applied,
                  Vector<double>           &residual)
    {
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        {
          const double F_i = face_value(i);
          applied[fe.system_to_component_index(i).first] += F_i;
          if (has_support)
            residual(i) -= F_i;
        }
    }
  } // namespace


  template <int dim>
  void
  ForceBalanceEvaluator<dim>::reinit()
  {
    const auto &d = discretization;
    d.reinit_owned(volume_weights);
    const QGauss<dim>                    quadrature(d.fe.degree + 1);
    FEValues<dim>                        fe_values =
      d.cell_values(quadrature, update_values | update_JxW_values);
    std::vector<types::global_dof_index> dofs(d.fe.n_dofs_per_cell());
    Vector<double>                       local(d.fe.n_dofs_per_cell());
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          local = 0;
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              const unsigned int c = d.fe.system_to_component_index(i).first;
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                local(i) +=
                  fe_values.shape_value_component(i, q, c) * fe_values.JxW(q);
            }
          cell->get_dof_indices(dofs);
          volume_weights.add(dofs, local);
        }
    volume_weights.compress(VectorOperation::add);

    // The component of each owned DoF, and the cells with work.
    component.assign(d.locally_owned.n_elements(), 0);
    cells.clear();
    faces.clear();
    face_cell.clear();
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          bool has_support = false;
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              if (d.locally_owned.is_element(dofs[i]))
                component[d.locally_owned.index_within_set(dofs[i])] =
                  d.fe.system_to_component_index(i).first;
              has_support = has_support || supported(d, dofs[i]);
            }
          if (has_support || scene.carries_load(cell))
            {
              for (const auto f : cell->face_indices())
                if (Function<dim> *const g = scene.face_load(cell, f))
                  {
                    faces.push_back({cell, f, g});
                    face_cell.push_back(cells.size());
                  }
              cells.push_back({cell, has_support});
            }
        }

    // Where each owned DoF sits in a ghosted vector.
    Vector_t ghosted;
    d.reinit_ghosted(ghosted);
    const auto &map = ghosted.trilinos_partitioner();
    ghosted_index.clear();
    ghosted_index.reserve(d.locally_owned.n_elements());
    for (const auto dof : d.locally_owned)
      ghosted_index.push_back(
        map.LID(static_cast<TrilinosWrappers::types::int_type>(dof)));
  }


  template <int dim>
  void
  ForceBalanceEvaluator<dim>::integrate_face_loads(
    const double      t,
    const TimeScheme &scheme) const
  {
    // The surface loads of the step, face by face: theta F(t) + (1 -
    // theta) F(t - k), integrated as the load vector integrates them.
    face_quadrature.integrate(scene, t, faces, face_values);
    if (!scheme.is_backward_euler())
      {
        face_quadrature.integrate(scene,
                                  t - scheme.time_step(),
                                  faces,
                                  old_face_values);
        for (unsigned int f = 0; f < faces.size(); ++f)
          scheme.weigh(face_values[f], old_face_values[f]);
      }
  }


  template <int dim>
  void
  ForceBalanceEvaluator<dim>::body_forces(const double       t,
                                          const TimeScheme  &scheme,
                                          const Vector_t    &u,
                                          const Vector_t    &w_theta,
                                          const Vector_t    &w,
                                          const Vector_t    &w_old,
                                          ForceBalance<dim> &b) const
  {
    const auto  &d = discretization;
    const double k = scheme.time_step();
    // The load of the scheme's equation at a point: theta f(t) + (1 - theta)
    // f(t - k) (Scene::step_load), f(t - k) computed into value_old.
    Vector<double>                   value_old(dim);
    const auto                      &fe = d.fe;
    const unsigned int               n  = fe.n_dofs_per_cell();
    const QGauss<dim>                quadrature(fe.degree + 2);
    FEValues<dim>                    fe_values =
      d.cell_values(quadrature,
                    update_values | update_gradients |
                      update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<1, dim>>      w_q(quadrature.size()),
      w_old_q(quadrature.size());
    std::vector<SymmetricTensor<2, dim>> eps_u(quadrature.size()),
      eps_w(quadrature.size());
    std::vector<types::global_dof_index> dofs(n);
    Vector<double>                       value(dim), residual(n);
    const bool                           body_force = scene.has_body_force();
    // value = the step's load g at x, and its part of the applied force.
    const auto load_at =
      [&](Function<dim> &g, const Point<dim> &x, const double JxW) {
        scene.step_load(g, x, t, scheme, value, value_old);
        for (unsigned int c = 0; c < dim; ++c)
          b.applied[c] += value(c) * JxW;
      };

    integrate_face_loads(t, scheme);
    unsigned int face = 0;
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        const auto &[cell, has_support] = cells[c];
        fe_values.reinit(cell);
        if (has_support)
          {
            cell->get_dof_indices(dofs);
            fe_values[displacement].get_function_values(w, w_q);
            fe_values[displacement].get_function_values(w_old, w_old_q);
            fe_values[displacement].get_function_symmetric_gradients(u, eps_u);
            fe_values[displacement].get_function_symmetric_gradients(w_theta,
                                                                     eps_w);
          }
        residual = 0;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            value = 0;
            if (body_force)
              load_at(scene.body_force(),
                      fe_values.quadrature_point(q),
                      fe_values.JxW(q));
            if (has_support)
              {
                const Tensor<1, dim> a =
                  material.density() * (w_q[q] - w_old_q[q]) / k;
                const SymmetricTensor<2, dim> sigma =
                  material.stress(eps_u[q], eps_w[q]);
                add_point_residual(fe_values, q, a, value, sigma, residual);
              }
          }
        for (; face < faces.size() && face_cell[face] == c; ++face)
          add_face_load(
            fe, face_values[face], has_support, b.applied, residual);
        // At a supported DoF the equation is balanced by the support's
        // force (the boundary term of the weak form): it is the residual.
        if (has_support)
          for (unsigned int i = 0; i < n; ++i)
            if (supported(d, dofs[i]))
              b.reaction[fe.system_to_component_index(i).first] += residual(i);
      }
  }


  template <int dim>
  ForceBalance<dim>
  ForceBalanceEvaluator<dim>::compute(
    const ContactBoundary<dim>               &boundary,
    const std::vector<ContactNodeState<dim>> &states,
    const double                              t,
    const TimeScheme                         &scheme,
    const Vector_t                           &u,
    const Vector_t                           &w_theta,
    const Vector_t                           &w,
    const Vector_t                           &w_old) const
  {
    const auto       &d = discretization;
    const double      k = scheme.time_step();
    ForceBalance<dim> b;
    // Inertia: rho/k sum_i (int phi_i) (w - w_old)_i, per component.
    {
      const double *weights = volume_weights.begin();
      const double *w_local = w.begin(), *w_old_local = w_old.begin();
      for (std::size_t index = 0; index < component.size(); ++index)
        {
          const int l = ghosted_index[index];
          b.inertia[component[index]] +=
            weights[index] * (w_local[l] - w_old_local[l]);
        }
      b.inertia *= material.density() / k;
    }
    body_forces(t, scheme, u, w_theta, w, w_old, b);

    // The foundation's force, and its part at supported components.
    const auto &nodes = boundary.nodes();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const Tensor<1, dim> f =
          states[i].normal_force(nodes[i].weight) * nodes[i].normal +
          states[i].friction_force;
        b.contact -= f;
        for (unsigned int c = 0; c < dim; ++c)
          if (supported(d, nodes[i].dofs[c]))
            b.reaction[c] += f[c];
      }

    for (auto *v : {&b.applied, &b.contact, &b.reaction, &b.inertia})
      for (unsigned int c = 0; c < dim; ++c)
        (*v)[c] = Utilities::MPI::sum((*v)[c], d.comm);
    return b;
  }


  template class ForceBalanceEvaluator<2>;
  template class ForceBalanceEvaluator<3>;
} // namespace DynamicContact
