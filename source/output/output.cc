#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_out_faces.h>

#include <dynamic_contact/base/error_messages.h>
#include <dynamic_contact/base/failure.h>
#include <dynamic_contact/base/mpi_gather.h>
#include <dynamic_contact/output/output.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iomanip>
#include <map>
#include <set>
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
  namespace
  {
    /**
     * One row of doubles per node of @p boundary, all of one @p width (the
     * state last, as a number), as one flat list: position, u_nu, w_nu,
     * pressure, with @p friction the tangential slip velocity and traction
     * and mu, then the displacement (and the state).
     */
    template <int dim>
    std::vector<double>
    contact_rows(const ContactBoundary<dim>               &boundary,
                 const std::vector<ContactNodeState<dim>> &states,
                 const Vector_t                           &u,
                 const Vector_t                           &w,
                 const bool                                friction,
                 const unsigned int                        width)
    {
      const auto         &nodes = boundary.nodes();
      std::vector<double> rows;
      rows.reserve(nodes.size() * width);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const auto &node = nodes[i];
          const auto &s    = states[i];
          for (unsigned int d = 0; d < dim; ++d)
            rows.push_back(node.position[d]);
          rows.push_back(s.normal.u_nu);
          rows.push_back(s.normal.w_nu);
          rows.push_back(s.normal.pressure);
          if (friction)
            {
              const Tensor<1, dim> w_tau = node.tangential(node.value(w));
              for (unsigned int j = 0; j < dim - 1; ++j)
                rows.push_back(w_tau * node.tangents[j]);
              // The traction the foundation exerts against the slip:
              // -lambda_i / m_i, in the tangent basis.
              for (unsigned int j = 0; j < dim - 1; ++j)
                rows.push_back(-(s.friction_force * node.tangents[j]) /
                               node.weight);
              rows.push_back(s.mu);
            }
          const Tensor<1, dim> displacement = node.value(u);
          for (unsigned int d = 0; d < dim; ++d)
            rows.push_back(displacement[d]);
          if (friction)
            rows.push_back(
              static_cast<double>(s.state)); // last: printed as text
          Assert(rows.size() == (i + 1) * width, ExcInternalError());
        }
      return rows;
    }


    /**
     * The text of the contact csv file at @p time: the header and every
     * process's rows (@p gathered, each @p width long), sorted by
     * position.
     */
    template <int dim>
    std::string
    contact_csv_text(const std::vector<std::vector<double>> &gathered,
                     const unsigned int                      width,
                     const double                            time,
                     const bool                              friction)
    {
      std::vector<std::vector<double>> all;
      for (const auto &part : gathered)
        for (std::size_t pos = 0; pos < part.size(); pos += width)
          all.emplace_back(part.begin() + pos, part.begin() + pos + width);
      std::sort(all.begin(),
                all.end(),
                [](const std::vector<double> &a, const std::vector<double> &b) {
                  for (unsigned int d = 0; d < dim; ++d)
                    if (a[d] != b[d])
                      return a[d] < b[d];
                  return false;
                });

      std::string out = (dim == 2 ? "time,x,y" : "time,x,y,z");
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
      const std::string time_field = scientific(time, 10);
      for (const auto &row : all)
        {
          const unsigned int n_numbers = row.size() - (friction ? 1 : 0);
          out += time_field;
          for (unsigned int c = 0; c < n_numbers; ++c)
            out += "," + scientific(row[c], 10);
          if (friction)
            out +=
              std::string(",") + to_string(static_cast<FrictionState>(
                                   static_cast<unsigned char>(row.back())));
          out += '\n';
        }
      return out;
    }
  } // namespace


  template <int dim>
  void
  write_contact_csv(OutputDirectory                          &directory,
                    const std::string                        &name,
                    const double                              time,
                    const ContactBoundary<dim>               &boundary,
                    const std::vector<ContactNodeState<dim>> &states,
                    const Vector_t                           &u,
                    const Vector_t                           &w,
                    const bool                                friction,
                    const MPI_Comm                            comm)
  {
    // One row of doubles per node, all of one width (the state last, as a
    // number), gathered to rank 0 as one flat list per process.
    const unsigned int width = 2 * dim + 3 + (friction ? 2 * (dim - 1) + 2 : 0);
    const std::vector<double> rows =
      contact_rows(boundary, states, u, w, friction, width);

    const auto gathered = gather_values(comm, rows, 0);
    collectively_on_rank_zero(comm, [&]() {
      const std::string out =
        contact_csv_text<dim>(gathered, width, time, friction);
      directory.claim(name);
      write_file(directory.file(name), out);
    });
  }


  // ------------------------------------------------------------- VtuWriter
  template <int dim>
  int
  contact_state_code(const ContactNodeState<dim> &s)
  {
    if (s.state == FrictionState::stick)
      return 2;
    if (s.state == FrictionState::slip)
      return 3;
    return s.normal.pressure > 0 ? 1 : 0;
  }



  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)        \
  template void write_contact_csv<dim>(         \
    OutputDirectory &,                          \
    const std::string &,                        \
    const double,                               \
    const ContactBoundary<dim> &,               \
    const std::vector<ContactNodeState<dim>> &, \
    const Vector_t &,                           \
    const Vector_t &,                           \
    const bool,                                 \
    const MPI_Comm);                            \
  template int contact_state_code<dim>(const ContactNodeState<dim> &);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
