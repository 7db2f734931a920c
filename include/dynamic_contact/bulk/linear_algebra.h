#ifndef dynamic_contact_linear_algebra_h
#define dynamic_contact_linear_algebra_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

namespace DynamicContact
{
  /**
   * The distributed linear algebra of the program, in one place: Trilinos
   * (Epetra) vectors and sparse matrices, as in deal.II's step-40 and
   * step-42.
   */
  using Vector_t = dealii::TrilinosWrappers::MPI::Vector;
  using Matrix_t = dealii::TrilinosWrappers::SparseMatrix;

  /**
   * The bytes of a matrix's values on this process (its column indices are
   * its pattern's graph, which the matrices of one pattern share).
   */
  inline double
  stored_values_bytes(const Matrix_t &A)
  {
    return double(A.trilinos_matrix().NumMyNonzeros()) * sizeof(double);
  }
} // namespace DynamicContact

#endif
