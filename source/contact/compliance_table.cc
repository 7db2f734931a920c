#include <deal.II/base/mpi.h>

#include <dynamic_contact/base/timing.h>
#include <dynamic_contact/contact/compliance_table.h>

namespace DynamicContact
{
  template <int dim>
  void
  ComplianceTable<dim>::reinit()
  {
    const auto &all = gathered.all_nodes();
    columns.assign(all.size(), {});
    made.assign(all.size(), false);
    full_columns.assign(dim * all.size(), {});
    full_column_stored.assign(all.size(), false);
    stored_full_columns = 0;
    max_owned_dofs =
      Utilities::MPI::max(problem.discretization.locally_owned.n_elements(),
                          problem.discretization.comm);
  }


  template <int dim>
  void
  ComplianceTable<dim>::forget()
  {
    for (auto &c : columns)
      c.clear();
    made.assign(made.size(), false);
    for (auto &c : full_columns)
      std::vector<double>().swap(c);
    full_column_stored.assign(full_column_stored.size(), false);
    stored_full_columns = 0;
  }


  template <int dim>
  bool
  ComplianceTable<dim>::holds_tables() const
  {
    return Utilities::MPI::this_mpi_process(
             problem.boundary.get_mpi_communicator()) == 0;
  }


  template <int dim>
  void
  ComplianceTable<dim>::subtract(const std::vector<Tensor<1, dim>> &forces,
                                 const std::vector<unsigned int>   &nodes,
                                 std::vector<Tensor<1, dim>>       &w) const
  {
    for (const unsigned int j : nodes)
      for (unsigned int i = 0; i < w.size(); ++i)
        w[i] -= columns[j][i] * forces[j];
  }


  template <int dim>
  bool
  ComplianceTable<dim>::apply_full_columns(
    const std::vector<Tensor<1, dim>> &f,
    const std::vector<unsigned int>   &nodes,
    Vector_t                          &x) const
  {
    for (const unsigned int j : nodes)
      if (!full_column_stored[j])
        return false;
    TimerSection t(problem.timer, "Bulk: sums of compliance columns");
    x            = 0;
    double    *y = x.trilinos_vector()[0];
    const auto n = problem.discretization.locally_owned.n_elements();
    for (const unsigned int j : nodes)
      for (unsigned int c = 0; c < dim; ++c)
        if (f[j][c] != 0)
          {
            const double  a      = f[j][c];
            const double *column = full_columns[dim * j + c].data();
            for (std::size_t i = 0; i < n; ++i)
              y[i] += a * column[i];
          }
    problem.discretization.constraints.set_zero(x);
    return true;
  }


  template <int dim>
  void
  ComplianceTable<dim>::memory_consumption(MemoryItems &items) const
  {
    double c = 0, full = 0;
    for (const auto &column : columns)
      c += column.size() * sizeof(Tensor<2, dim>);
    for (const auto &column : full_columns)
      full += column.size() * sizeof(double);
    // The same items on every process (a process may own none of them).
    items.push_back({"compliance C of Gamma_3", c, false});
    items.push_back({"whole responses to Gamma_3", full, false});
  }

  template class ComplianceTable<2>;
  template class ComplianceTable<3>;
} // namespace DynamicContact
