// The transfer of fields between meshes (refine_and_transfer): a finite
// element function refined and coarsened back is returned exactly, on a
// distributed mesh with hanging nodes and clamped boundaries (fields in
// master form).

#include <dynamic_contact/bulk/discretization.h>
#include <dynamic_contact/mesh/mesh_adaptation.h>

#include "test_tools.h"

using namespace DynamicContact;

template <int dim>
void
check(const unsigned int degree)
{
  Discretization<dim> d(MPI_COMM_WORLD, degree);
  test_tools::make_box(d.triangulation, 4);
  d.triangulation.refine_global(1);
  Parameters::BoundaryConditions bc;
  bc.clamped = {0};
  d.setup_dofs(bc);

  // A smooth field in master form.
  const Vector_t original = test_tools::cosine_field(d);
  Vector_t       field    = original;

  // Refine the cells of the left half (hanging nodes appear) ...
  test_tools::flag_left_half(d.triangulation);
  refine_and_transfer(d, {&field}, [&]() { d.setup_dofs(bc); });
  test_tools::check(d.triangulation.n_global_active_cells() >
                      (dim == 2 ? 64u : 512u),
                    std::to_string(dim) + "D Q" + std::to_string(degree) +
                      ": refined");
  // ... and coarsen them back.
  for (const auto &cell : d.triangulation.active_cell_iterators())
    if (cell->is_locally_owned() && cell->level() == 2)
      cell->set_coarsen_flag();
  refine_and_transfer(d, {&field}, [&]() { d.setup_dofs(bc); });
  test_tools::check(d.triangulation.n_global_active_cells() ==
                      (dim == 2 ? 64u : 512u),
                    std::to_string(dim) + "D Q" + std::to_string(degree) +
                      ": coarsened back");

  field -= original;
  test_tools::check(field.linfty_norm() <= 1e-14 * original.linfty_norm(),
                    std::to_string(dim) + "D Q" + std::to_string(degree) +
                      ": the field is returned exactly");
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  test_tools::for_each_element({{2, 1}, {2, 2}, {3, 1}},
                               [](const auto dim, const unsigned int degree) {
                                 check<decltype(dim)::value>(degree);
                               });
}
