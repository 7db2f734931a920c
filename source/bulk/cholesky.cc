#include <deal.II/lac/lapack_templates.h>

#include <dynamic_contact/base/mpi_gather.h>
#include <dynamic_contact/bulk/cholesky.h>
#include <dynamic_contact/bulk/cholmod_views.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace DynamicContact
{
  Cholesky::Cholesky(const MPI_Comm comm)
    : comm(comm)
    , n_processes(Utilities::MPI::n_mpi_processes(comm))
    , rank(Utilities::MPI::this_mpi_process(comm))
  {
    cholmod_l_start(&common);
    common.print      = 0; // errors are reported by the checks below
    common.supernodal = CHOLMOD_AUTO; // supernodal unless L is very sparse
  }


  Cholesky::~Cholesky()
  {
    free_workspace();
    if (factor != nullptr)
      cholmod_l_free_factor(&factor, &common);
    cholmod_l_finish(&common);
  }


  namespace
  {
    /**
     * The upper triangle of the symmetric @p A, packed for the exchange:
     * row r read as column r, its entries with index <= r; for each owned
     * row the global row, the count, the columns and the values.
     */
    std::vector<double>
    packed_owned_rows(const Epetra_CrsMatrix &A)
    {
      std::vector<double> packed;
      packed.reserve(A.NumMyNonzeros() + 2 * A.NumMyRows());
      std::vector<std::pair<SuiteSparse_long, double>> row;
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          const SuiteSparse_long global_row = A.GRID(r);
          sorted_row(A, r, global_row, row);
          packed.push_back(global_row);
          packed.push_back(row.size());
          for (const auto &entry : row)
            packed.push_back(entry.first);
          for (const auto &entry : row)
            packed.push_back(entry.second);
        }
      return packed;
    }


    /**
     * Unpack every process's packed rows (@p parts): where each row's data
     * begins (@p row_data, by global row), the global rows in the order
     * received (@p gathered_rows) and how many each process sent
     * (@p counts, @p displacements).
     */
    void
    unpack_gathered_rows(const std::vector<std::vector<double>> &parts,
                         std::vector<const double *>            &row_data,
                         std::vector<SuiteSparse_long>          &gathered_rows,
                         std::vector<int>                       &counts,
                         std::vector<int>                       &displacements)
    {
      for (unsigned int p = 0; p < parts.size(); ++p)
        {
          displacements[p] = gathered_rows.size();
          for (std::size_t k = 0; k < parts[p].size();
               k += 2 + 2 * static_cast<std::size_t>(parts[p][k + 1]))
            {
              gathered_rows.push_back(parts[p][k]);
              row_data[gathered_rows.back()] = &parts[p][k];
            }
          counts[p] = gathered_rows.size() - displacements[p];
        }
    }


    /**
     * The compressed columns of the upper triangle from the unpacked rows
     * @p row_data of the @p n rows: column starts @p start, row indices
     * @p index and @p value (reserving @p capacity entries).
     */
    void
    upper_triangle_columns(const std::vector<const double *> &row_data,
                           const SuiteSparse_long             n,
                           const std::size_t                  capacity,
                           std::vector<SuiteSparse_long>     &start,
                           std::vector<SuiteSparse_long>     &index,
                           std::vector<double>               &value)
    {
      index.reserve(capacity);
      value.reserve(capacity);
      for (SuiteSparse_long r = 0; r < n; ++r)
        {
          const std::size_t count = row_data[r][1];
          for (std::size_t k = 0; k < count; ++k)
            {
              index.push_back(row_data[r][2 + k]);
              value.push_back(row_data[r][2 + count + k]);
            }
          start.push_back(index.size());
        }
    }
  } // namespace


  void
  Cholesky::factorize(const Epetra_CrsMatrix              &A,
                      const std::vector<SuiteSparse_long> &trailing)
  {
    // The upper triangle, column by column: row r of the (symmetric)
    // matrix read as column r, its entries with index <= r; each process
    // packs its rows (global row, count, columns, values), every process
    // gets every row.
    const std::vector<double>   packed = packed_owned_rows(A);
    const SuiteSparse_long      n      = A.NumGlobalRows();
    std::vector<const double *> row_data(n, nullptr);
    const auto                  parts = all_gather_values(comm, packed);
    gathered_rows.clear();
    counts.assign(n_processes, 0);
    displacements.assign(n_processes, 0);
    unpack_gathered_rows(parts, row_data, gathered_rows, counts, displacements);
    in_order = true;
    for (SuiteSparse_long k = 0; k < n; ++k)
      in_order = in_order && gathered_rows[k] == k;
    std::vector<SuiteSparse_long> start(1, 0), index;
    std::vector<double>           value;
    upper_triangle_columns(row_data, n, packed.size(), start, index, value);
    const bool same_pattern = factor != nullptr && start == pattern_start &&
                              index == pattern_index &&
                              trailing == trailing_rows;
    pattern_start = std::move(start);
    pattern_index = std::move(index);
    values        = std::move(value);
    trailing_rows = trailing;

    cholmod_sparse S = upper_triangle_view(n,
                                           pattern_start.data(),
                                           pattern_index.data(),
                                           values.data());
    if (!same_pattern)
      {
        if (factor != nullptr)
          cholmod_l_free_factor(&factor, &common);
        factor = cholmod_l_analyze(&S, &common);
        AssertThrow(factor != nullptr && common.status == CHOLMOD_OK,
                    ExcMessage("The analysis of the bulk matrix for its "
                               "factorization (CHOLMOD) failed."));
        trailing_used = false;
        if (!trailing_rows.empty())
          analyze_with_trailing_rows(S);
      }
    AssertThrow(cholmod_l_factorize(&S, factor, &common) &&
                  common.status == CHOLMOD_OK,
                ExcMessage("The factorization of the bulk matrix failed "
                           "(CHOLMOD: it is not positive definite)."));
  }


  bool
  Cholesky::replicated() const
  {
    return n_processes > 1;
  }


  void
  Cholesky::solve_owned(const double      *B,
                        double            *X,
                        const unsigned int n_columns,
                        const std::size_t  n_owned)
  {
    if (!replicated())
      {
        solve(B, X, n_columns);
        return;
      }
    const std::size_t n = factor->n;
    whole_B.resize(n * n_columns);
    whole_X.resize(n * n_columns);
    for (unsigned int c = 0; c < n_columns; ++c)
      gather(B + c * n_owned, whole_B.data() + c * n);
    solve(whole_B.data(), whole_X.data(), n_columns);
    for (unsigned int c = 0; c < n_columns; ++c)
      owned_part(whole_X.data() + c * n, X + c * n_owned);
  }


  void
  Cholesky::owned_part(const double *whole, double *owned) const
  {
    const SuiteSparse_long *rows = gathered_rows.data() + displacements[rank];
    for (int k = 0; k < counts[rank]; ++k)
      owned[k] = whole[rows[k]];
  }


  void
  Cholesky::solve(const double *B, double *X, const unsigned int n_columns)
  {
    const std::size_t n = factor->n;
    cholmod_dense     b = dense_view(n, n_columns, B);
    // The workspace (and the solution) are reused while the number of
    // columns is the same.
    if (x != nullptr && x->ncol != n_columns)
      free_workspace();
    AssertThrow(
      cholmod_l_solve2(
        CHOLMOD_A, factor, &b, nullptr, &x, nullptr, &y, &e, &common) &&
        common.status == CHOLMOD_OK,
      ExcMessage("A solve with the bulk matrix failed."));
    std::memcpy(X, x->x, sizeof(double) * n * n_columns);
  }


  bool
  Cholesky::has_trailing_rows() const
  {
    return trailing_used;
  }


  double
  Cholesky::factor_entries() const
  {
    return common.lnz;
  }


  void
  Cholesky::inverse_block(std::vector<double> &inverse,
                          const bool           on_every_process) const
  {
    Assert(factor != nullptr && factor->is_super && trailing_used,
           ExcInternalError());
    const SuiteSparse_long n = factor->n;
    const SuiteSparse_long m = trailing_rows.size();
    // Replicated: process 0's block for all, so that every process's
    // dense Newton iteration sees the same numbers.
    if (rank != 0)
      {
        inverse.clear();
        if (on_every_process)
          {
            inverse.resize(m * m);
            MPI_Bcast(inverse.data(), m * m, MPI_DOUBLE, 0, comm);
          }
        return;
      }
    const SuiteSparse_long first = n - m;
    // L_22, column-major. Supernode s holds the columns super[s] ..
    // super[s+1] - 1, their rows s[pi[s]] .. s[pi[s+1] - 1] (the supernode's
    // own columns first) and the values column-major from x[px[s]].
    const auto *super = static_cast<const SuiteSparse_long *>(factor->super);
    const auto *pi    = static_cast<const SuiteSparse_long *>(factor->pi);
    const auto *px    = static_cast<const SuiteSparse_long *>(factor->px);
    const auto *rows  = static_cast<const SuiteSparse_long *>(factor->s);
    const auto *x     = static_cast<const double *>(factor->x);
    std::vector<double> factor22(m * m, 0.);
    for (std::size_t sn = 0; sn < factor->nsuper; ++sn)
      {
        const SuiteSparse_long n_rows = pi[sn + 1] - pi[sn];
        for (SuiteSparse_long k = std::max(super[sn], first);
             k < super[sn + 1];
             ++k)
          {
            const double *column = x + px[sn] + (k - super[sn]) * n_rows;
            for (SuiteSparse_long r = k - super[sn]; r < n_rows; ++r)
              factor22[(rows[pi[sn] + r] - first) + (k - first) * m] =
                column[r];
          }
      }
    inverse.assign(m * m, 0.);
    for (SuiteSparse_long j = 0; j < m; ++j)
      inverse[j + j * m] = 1;
    const types::blas_int size = m;
    types::blas_int       info = 0;
    potrs("L",
          &size,
          &size,
          factor22.data(),
          &size,
          inverse.data(),
          &size,
          &info);
    AssertThrow(info == 0,
                ExcMessage("The inversion of the Schur complement of the "
                           "bulk matrix on Gamma_3 failed (LAPACK potrs)."));
    if (replicated() && on_every_process)
      MPI_Bcast(inverse.data(), m * m, MPI_DOUBLE, 0, comm);
  }


  namespace
  {
    /**
     * Two orders of the @p S with the @p trailing_rows last, in the order
     * given: the fill-reducing order @p fill_order of the analysis with
     * these rows moved to the end, and a constrained minimum degree order
     * (CAMD, the trailing rows as the set ordered last) where CAMD succeeds.
     */
    std::vector<std::vector<SuiteSparse_long>>
    orders_with_trailing_last(
      cholmod_sparse                      &S,
      const SuiteSparse_long              *fill_order,
      const std::vector<SuiteSparse_long> &trailing_rows,
      cholmod_common                      &common)
    {
      const SuiteSparse_long n = S.nrow;
      std::vector<char>      trailing(n, 0);
      for (const SuiteSparse_long r : trailing_rows)
        trailing[r] = 1;
      const auto with_trailing_last = [&](const SuiteSparse_long *base) {
        std::vector<SuiteSparse_long> order;
        order.reserve(n);
        for (SuiteSparse_long k = 0; k < n; ++k)
          if (!trailing[base[k]])
            order.push_back(base[k]);
        order.insert(order.end(), trailing_rows.begin(), trailing_rows.end());
        return order;
      };
      std::vector<std::vector<SuiteSparse_long>> orders;
      orders.push_back(with_trailing_last(fill_order));
      {
        std::vector<SuiteSparse_long> member(trailing.begin(), trailing.end()),
          camd_order(n);
        if (cholmod_l_camd(
              &S, nullptr, 0, member.data(), camd_order.data(), &common))
          orders.push_back(with_trailing_last(camd_order.data()));
      }
      return orders;
    }


    /**
     * The analysis of @p S in each of the given @p orders (supernodal, not
     * postordered); the one with the fewest factor entries is returned,
     * with its entries in common.lnz. The other settings of @p common are
     * restored.
     */
    cholmod_factor *
    smallest_given_order_analysis(
      cholmod_sparse                             &S,
      std::vector<std::vector<SuiteSparse_long>> &orders,
      cholmod_common                             &common)
    {
      const int nmethods            = common.nmethods;
      const int ordering            = common.method[0].ordering;
      const int postorder           = common.postorder;
      const int supernodal          = common.supernodal;
      common.nmethods               = 1;
      common.method[0].ordering     = CHOLMOD_GIVEN;
      common.postorder              = false;
      common.supernodal             = CHOLMOD_SUPERNODAL;
      cholmod_factor *with_trailing = nullptr;
      double          entries       = 0;
      for (auto &order : orders)
        {
          cholmod_factor *candidate =
            cholmod_l_analyze_p(&S, order.data(), nullptr, 0, &common);
          AssertThrow(candidate != nullptr && common.status == CHOLMOD_OK &&
                        std::equal(order.begin(),
                                   order.end(),
                                   static_cast<SuiteSparse_long *>(
                                     candidate->Perm)),
                      ExcMessage("The analysis of the bulk matrix for its "
                                 "factorization (CHOLMOD) failed."));
          if (with_trailing == nullptr || common.lnz < entries)
            {
              if (with_trailing != nullptr)
                cholmod_l_free_factor(&with_trailing, &common);
              with_trailing = candidate;
              entries       = common.lnz;
            }
          else
            cholmod_l_free_factor(&candidate, &common);
        }
      common.lnz                = entries;
      common.nmethods           = nmethods;
      common.method[0].ordering = ordering;
      common.postorder          = postorder;
      common.supernodal         = supernodal;
      return with_trailing;
    }
  } // namespace


  void
  Cholesky::analyze_with_trailing_rows(cholmod_sparse &S)
  {
    const double fill_entries = common.lnz;
    // Two orders with the trailing rows last, in the order given: the
    // fill-reducing order of the analysis with these rows moved to the
    // end, and a constrained minimum degree order (CAMD, the trailing
    // rows as the set ordered last), which is often much better where
    // the moved rows would leave a large separator behind; the one with
    // the smaller factor is kept.
    auto orders = orders_with_trailing_last(
      S, static_cast<SuiteSparse_long *>(factor->Perm), trailing_rows, common);
    cholmod_factor *with_trailing =
      smallest_given_order_analysis(S, orders, common);
    // The dense trailing block makes every solve dearer: taken while it
    // at most doubles the factor. Below that (the paper's scene, the 3D
    // rail 80 x 8 x 8) a solve costs a little more and the compliance
    // columns it saves many solves; on the paper domain 256 x 16, a strip
    // 16 cells deep under 514 DoFs of Gamma_3, a solve costs several
    // times as much and the run is slower than with the columns by solves
    // (doc/algorithms.md, "Condensed").
    // The same choice on every process (a collective path follows it).
    trailing_used =
      Utilities::MPI::min(int(common.lnz <= max_growth * fill_entries),
                          comm) == 1;
    if (trailing_used)
      {
        cholmod_l_free_factor(&factor, &common);
        factor = with_trailing;
      }
    else
      {
        cholmod_l_free_factor(&with_trailing, &common);
        common.lnz = fill_entries;
      }
  }


  void
  Cholesky::gather(const double *owned, double *whole)
  {
    double *target = whole;
    if (!in_order)
      {
        gather_buffer.resize(factor->n);
        target = gather_buffer.data();
      }
    MPI_Allgatherv(owned,
                   counts[rank],
                   MPI_DOUBLE,
                   target,
                   counts.data(),
                   displacements.data(),
                   MPI_DOUBLE,
                   comm);
    if (!in_order)
      for (std::size_t k = 0; k < gathered_rows.size(); ++k)
        whole[gathered_rows[k]] = gather_buffer[k];
  }


  void
  Cholesky::free_workspace()
  {
    for (cholmod_dense **d : {&x, &y, &e})
      if (*d != nullptr)
        cholmod_l_free_dense(d, &common);
  }
} // namespace DynamicContact
