#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>

#include <dynamic_contact/error_messages.h>
#include <dynamic_contact/failure.h>
#include <dynamic_contact/output.h>

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace DynamicContact
{

  // --------------------------------------------------------- TimeSeriesRow
  void
  TimeSeriesRow::add(const std::string &name, const double value)
  {
    entries.emplace_back(name, scientific(value, 10));
  }

  void
  TimeSeriesRow::add_integer(const std::string &name, const long long value)
  {
    entries.emplace_back(name, std::to_string(value));
  }

  double
  TimeSeriesRow::get(const std::string &name) const
  {
    for (const auto &[n, v] : entries)
      if (n == name)
        return std::stod(v);
    AssertThrow(false, ExcMessage("No column '" + name + "' in the row."));
    return 0;
  }


  // ------------------------------------------------------ TimeSeriesWriter
  TimeSeriesWriter::TimeSeriesWriter(OutputDirectory &directory,
                                     const MPI_Comm   comm,
                                     const bool       append)
    : comm(comm)
    , root(Utilities::MPI::this_mpi_process(comm) == 0)
    , header_written(append)
  {
    collectively(comm, [&]() {
      if (root)
        {
          directory.claim("time_series.csv");
          out.open(directory.file("time_series.csv"), append);
        }
    });
  }

  void
  TimeSeriesWriter::write(const TimeSeriesRow &row)
  {
    collectively(comm, [&]() {
      if (!root)
        return;
      std::string text;
      if (!header_written)
        {
          for (unsigned int i = 0; i < row.columns().size(); ++i)
            text += (i ? "," : "") + row.columns()[i].first;
          text += '\n';
        }
      for (unsigned int i = 0; i < row.columns().size(); ++i)
        text += (i ? "," : "") + row.columns()[i].second;
      text += '\n';
      out.append(text);
      header_written = true;
    });
  }

  void
  TimeSeriesWriter::close()
  {
    collectively(comm, [&]() {
      if (root)
        out.close();
    });
  }


  // ----------------------------------------------------------- contact csv
  template <int dim>
  void
  write_contact_csv(OutputDirectory &                         directory,
                    const std::string &                       name,
                    const ContactBoundary<dim> &              boundary,
                    const std::vector<ContactNodeState<dim>> &states,
                    const Vector_t &                          u,
                    const Vector_t &                          w,
                    const bool                                friction,
                    const MPI_Comm                            comm)
  {
    const auto &                     nodes = boundary.nodes();
    std::vector<std::vector<double>> rows;
    rows.reserve(nodes.size());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const auto &         node = nodes[i];
        const auto &         s    = states[i];
        std::vector<double>  row;
        for (unsigned int d = 0; d < dim; ++d)
          row.push_back(node.position[d]);
        row.push_back(s.normal.u_nu);
        row.push_back(s.normal.w_nu);
        row.push_back(s.normal.pressure);
        if (friction)
          {
            const Tensor<1, dim> w_tau = node.tangential(node.value(w));
            for (unsigned int j = 0; j < dim - 1; ++j)
              row.push_back(w_tau * node.tangents[j]);
            // The traction the foundation exerts against the slip:
            // -lambda_i / m_i, in the tangent basis.
            for (unsigned int j = 0; j < dim - 1; ++j)
              row.push_back(-(s.friction_force * node.tangents[j]) /
                            node.weight);
            row.push_back(s.mu);
          }
        const Tensor<1, dim> displacement = node.value(u);
        for (unsigned int d = 0; d < dim; ++d)
          row.push_back(displacement[d]);
        if (friction)
          row.push_back(static_cast<double>(s.state)); // last: printed as text
        rows.push_back(row);
      }

    const auto gathered = Utilities::MPI::gather(comm, rows, 0);
    collectively(comm, [&]() {
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;

      std::vector<std::vector<double>> all;
      for (const auto &part : gathered)
        all.insert(all.end(), part.begin(), part.end());
      std::sort(all.begin(),
                all.end(),
                [](const std::vector<double> &a, const std::vector<double> &b) {
                  for (unsigned int d = 0; d < dim; ++d)
                    if (a[d] != b[d])
                      return a[d] < b[d];
                  return false;
                });

      std::string out = (dim == 2 ? "x,y" : "x,y,z");
      out += ",u_nu,w_nu,normal_pressure";
      if (friction)
        out += std::string(dim == 2 ? ",w_tau,tangential_traction" :
                                      ",w_tau_1,w_tau_2,tangential_traction_1,"
                                      "tangential_traction_2") +
               ",mu";
      out += (dim == 2 ? ",u_x,u_y" : ",u_x,u_y,u_z");
      if (friction)
        out += ",state";
      out += '\n';
      for (const auto &row : all)
        {
          const unsigned int n_numbers = row.size() - (friction ? 1 : 0);
          for (unsigned int c = 0; c < n_numbers; ++c)
            out += (c ? "," : "") + scientific(row[c], 10);
          if (friction)
            out += std::string(",") + to_string(static_cast<ContactState>(
                           static_cast<unsigned char>(row.back())));
          out += '\n';
        }
      directory.claim(name);
      write_file(directory.file(name), out);
    });
  }


  // ------------------------------------------------------------- VtuWriter
  template <int dim>
  VtuWriter<dim>::VtuWriter(OutputDirectory &  directory,
                            const MPI_Comm     comm,
                            const unsigned int subdivisions)
    : directory(directory)
    , comm(comm)
    , subdivisions(subdivisions)
  {}


  template <int dim>
  std::vector<std::string>
  VtuWriter<dim>::file_names(const unsigned int step,
                             const unsigned int n_processes)
  {
    char base[32];
    std::snprintf(base, sizeof(base), "solution_%05u", step);
    std::vector<std::string> names = {std::string(base) + ".pvtu"};
    for (unsigned int p = 0; p < n_processes; ++p)
      names.push_back(std::string(base) + "." + std::to_string(p) + ".vtu");
    return names;
  }


  template <int dim>
  void
  VtuWriter<dim>::write_index()
  {
    collectively(comm, [&]() {
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      std::ostringstream pvd;
      DataOutBase::write_pvd_record(pvd, records);
      directory.claim("solution.pvd");
      replace_file(directory.file("solution.pvd"), pvd.str());
    });
  }


  template <int dim>
  void
  VtuWriter<dim>::write(const unsigned int                        step,
                        const double                              time,
                        const Discretization<dim> &               d,
                        const KelvinVoigtMaterial<dim> &          material,
                        const ContactBoundary<dim> &              boundary,
                        const std::vector<ContactNodeState<dim>> &states,
                        const Vector_t &                          u,
                        const Vector_t &                          w,
                        const bool                                friction)
  {
    const Vector_t u_ghosted = d.expanded(u), w_ghosted = d.expanded(w);

    // Nodal fields of Gamma_3: in the vector space (traction) and in the
    // scalar space (pressure, friction data).
    Vector_t traction_owned, traction;
    d.reinit_owned(traction_owned);
    TrilinosWrappers::MPI::Vector pressure_owned, pressure, mu_owned, mu,
      state_owned, state, slip_owned, slip;
    for (auto *v : {&pressure_owned, &mu_owned, &state_owned, &slip_owned})
      v->reinit(d.scalar_locally_owned, d.comm);
    {
      const auto &                         nodes = boundary.nodes();
      std::vector<types::global_dof_index> vi, si;
      std::vector<double>                  tv, pv, mv, sv, rv;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const Tensor<1, dim> t =
            (-states[i].normal.pressure * nodes[i].normal) -
            states[i].friction_force / nodes[i].weight;
          for (unsigned int c = 0; c < dim; ++c)
            {
              vi.push_back(nodes[i].dofs[c]);
              tv.push_back(t[c]);
            }
          si.push_back(nodes[i].scalar_dof);
          pv.push_back(states[i].normal.pressure);
          mv.push_back(states[i].mu);
          sv.push_back(static_cast<double>(states[i].state));
          rv.push_back(states[i].slip_rate);
        }
      traction_owned.set(vi, tv);
      pressure_owned.set(si, pv);
      mu_owned.set(si, mv);
      state_owned.set(si, sv);
      slip_owned.set(si, rv);
      traction_owned.compress(VectorOperation::insert);
      for (auto *v : {&pressure_owned, &mu_owned, &state_owned, &slip_owned})
        v->compress(VectorOperation::insert);
    }
    d.reinit_ghosted(traction);
    traction = traction_owned;
    for (auto [owned, ghosted] : {std::make_pair(&pressure_owned, &pressure),
                                  std::make_pair(&mu_owned, &mu),
                                  std::make_pair(&state_owned, &state),
                                  std::make_pair(&slip_owned, &slip)})
      {
        ghosted->reinit(d.scalar_locally_owned,
                        d.scalar_locally_relevant,
                        d.comm);
        *ghosted = *owned;
      }

    // Stress: cell averages of sigma = E eps(u) + C eps(w).
    const unsigned int n_cells = d.triangulation.n_active_cells();
    const unsigned int n_components = dim * (dim + 1) / 2;
    std::vector<Vector<float>> stress(n_components, Vector<float>(n_cells));
    Vector<float>              von_mises(n_cells), subdomain(n_cells);
    {
      const QGauss<dim>                    quadrature(d.fe.degree + 1);
      FEValues<dim>                        fe_values(d.mapping,
                              d.fe,
                              quadrature,
                              update_gradients | update_JxW_values);
      const FEValuesExtractors::Vector     displacement(0);
      std::vector<SymmetricTensor<2, dim>> eps_u(quadrature.size()),
        eps_w(quadrature.size());
      for (const auto &cell : d.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values[displacement].get_function_symmetric_gradients(u_ghosted,
                                                                     eps_u);
            fe_values[displacement].get_function_symmetric_gradients(w_ghosted,
                                                                     eps_w);
            SymmetricTensor<2, dim> sigma;
            double                  sigma_zz = 0, volume = 0;
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                sigma += material.stress(eps_u[q], eps_w[q]) * fe_values.JxW(q);
                sigma_zz += material.out_of_plane_stress(eps_u[q], eps_w[q]) *
                            fe_values.JxW(q);
                volume += fe_values.JxW(q);
              }
            sigma /= volume;
            sigma_zz /= volume;
            const unsigned int index = cell->active_cell_index();
            for (unsigned int c = 0; c < n_components; ++c)
              stress[c](index) = sigma.access_raw_entry(c);
            von_mises(index) = von_mises_stress(sigma, sigma_zz);
            subdomain(index) = cell->subdomain_id();
          }
    }

    DataOut<dim> data_out;
    data_out.attach_triangulation(d.triangulation);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(dim,
                   DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(d.dof_handler,
                             u_ghosted,
                             std::vector<std::string>(dim, "displacement"),
                             vector_field);
    data_out.add_data_vector(d.dof_handler,
                             w_ghosted,
                             std::vector<std::string>(dim, "velocity"),
                             vector_field);
    data_out.add_data_vector(d.dof_handler,
                             traction,
                             std::vector<std::string>(dim, "contact_traction"),
                             vector_field);
    data_out.add_data_vector(d.scalar_dof_handler, pressure, "contact_pressure");
    if (friction)
      {
        data_out.add_data_vector(d.scalar_dof_handler, mu, "friction_coefficient");
        data_out.add_data_vector(d.scalar_dof_handler,
                                 state,
                                 "contact_state");
        data_out.add_data_vector(d.scalar_dof_handler, slip, "slip_rate");
      }
    const char *names2[] = {"stress_xx", "stress_yy", "stress_xy"};
    const char *names3[] = {"stress_xx",
                            "stress_yy",
                            "stress_zz",
                            "stress_xy",
                            "stress_xz",
                            "stress_yz"};
    for (unsigned int c = 0; c < n_components; ++c)
      data_out.add_data_vector(stress[c],
                               dim == 2 ? names2[c] : names3[c],
                               DataOut<dim>::type_cell_data);
    data_out.add_data_vector(von_mises,
                             "von_mises_stress",
                             DataOut<dim>::type_cell_data);
    data_out.add_data_vector(subdomain,
                             "subdomain",
                             DataOut<dim>::type_cell_data);
    data_out.build_patches(d.mapping,
                           subdivisions > 0 ? subdivisions : d.fe.degree);

    // The piece of each process and the record of rank 0 (the names of
    // DataOut::write_vtu_with_pvtu_record), each write checked.
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    const auto         names =
      file_names(step, Utilities::MPI::n_mpi_processes(comm));
    collectively(comm, [&]() { directory.claim(names); });
    collectively(comm, [&]() {
      std::ostringstream piece;
      data_out.write_vtu(piece);
      write_file(directory.file(names[1 + rank]), piece.str());
      if (rank == 0)
        {
          std::ostringstream record;
          data_out.write_pvtu_record(
            record,
            std::vector<std::string>(names.begin() + 1, names.end()));
          write_file(directory.file(names[0]), record.str());
        }
    });
    records.emplace_back(time, names[0]);
    write_index();
  }


  template void
  write_contact_csv<2>(OutputDirectory &,
                       const std::string &,
                       const ContactBoundary<2> &,
                       const std::vector<ContactNodeState<2>> &,
                       const Vector_t &,
                       const Vector_t &,
                       const bool,
                       const MPI_Comm);
  template void
  write_contact_csv<3>(OutputDirectory &,
                       const std::string &,
                       const ContactBoundary<3> &,
                       const std::vector<ContactNodeState<3>> &,
                       const Vector_t &,
                       const Vector_t &,
                       const bool,
                       const MPI_Comm);
  template class VtuWriter<2>;
  template class VtuWriter<3>;
} // namespace DynamicContact
