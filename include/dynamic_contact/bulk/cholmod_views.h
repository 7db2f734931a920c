#ifndef dynamic_contact_cholmod_views_h
#define dynamic_contact_cholmod_views_h

#include <suitesparse/cholmod.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace DynamicContact
{
  /**
   * The entries of the owned row @p r of @p A with a global column at most
   * @p last (the row's global index: the upper triangle read as a column),
   * as (global column, value) pairs sorted by column, into @p row.
   */
  inline void
  sorted_row(const Epetra_CrsMatrix                           &A,
             const int                                         r,
             const SuiteSparse_long                            last,
             std::vector<std::pair<SuiteSparse_long, double>> &row)
  {
    int     count;
    double *values;
    int    *indices;
    A.ExtractMyRowView(r, count, values, indices);
    row.clear();
    for (int k = 0; k < count; ++k)
      {
        const SuiteSparse_long c = A.GCID(indices[k]);
        if (c <= last)
          row.emplace_back(c, values[k]);
      }
    std::sort(row.begin(), row.end());
  }


  /**
   * CHOLMOD's view of a symmetric matrix of order @p n given by its upper
   * triangle column by column (compressed sparse columns, 64-bit indices,
   * sorted): what BulkSolver's Cholesky factorization and
   * benchmarks/direct_comparison.cc hand to cholmod_l_analyze/factorize. The
   * arrays are not copied and must outlive the view.
   */
  inline cholmod_sparse
  upper_triangle_view(const std::size_t       n,
                      const SuiteSparse_long *start,
                      const SuiteSparse_long *index,
                      const double           *values)
  {
    cholmod_sparse S;
    S.nrow   = n;
    S.ncol   = n;
    S.nzmax  = start[n];
    S.p      = const_cast<SuiteSparse_long *>(start);
    S.i      = const_cast<SuiteSparse_long *>(index);
    S.nz     = nullptr;
    S.x      = const_cast<double *>(values);
    S.z      = nullptr;
    S.stype  = 1;
    S.itype  = CHOLMOD_LONG;
    S.xtype  = CHOLMOD_REAL;
    S.dtype  = CHOLMOD_DOUBLE;
    S.sorted = 1;
    S.packed = 1;
    return S;
  }

  /**
   * CHOLMOD's view of @p n_columns dense columns of length @p n,
   * column-major, not copied.
   */
  inline cholmod_dense
  dense_view(const std::size_t n,
             const std::size_t n_columns,
             const double     *data)
  {
    cholmod_dense d;
    d.nrow  = n;
    d.ncol  = n_columns;
    d.nzmax = n * n_columns;
    d.d     = n;
    d.x     = const_cast<double *>(data);
    d.z     = nullptr;
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    return d;
  }
} // namespace DynamicContact

#endif
