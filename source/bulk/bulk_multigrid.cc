#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/repartitioning_policy_tools.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>
#include <deal.II/matrix_free/tools.h>
#include <deal.II/multigrid/mg_coarse.h>
#include <deal.II/multigrid/mg_matrix.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/multigrid/multigrid.h>

#include <dynamic_contact/base/memory_report.h>
#include <dynamic_contact/bulk/bulk_kernel.h>
#include <dynamic_contact/bulk/bulk_multigrid.h>
#include <dynamic_contact/bulk/bulk_solver.h>
#include <dynamic_contact/bulk/cell_operators.h>

#include <algorithm>

namespace DynamicContact
{
  namespace
  {
    using LevelVector = LinearAlgebra::distributed::Vector<double>;

    /**
     * K0 on one level of the hierarchy: applied cell by cell, or by the
     * stored matrix of the finest level; constrained rows as the identity
     * (cell by cell) or as condensation left them (stored). The cell data
     * are the level's own, or (on the finest level) the bulk forms' where
     * they have them: the same mesh, constraints and quadrature.
     */
    template <int dim, int degree>
    class LevelOperator : public Subscriptor
    {
    public:
      using value_type = double;
      using Evaluation = FEEvaluation<dim, degree, degree + 1, dim, double>;

      LevelOperator(const Discretization<dim>       &discretization,
                    const DoFHandler<dim>           &dof_handler,
                    const AffineConstraints<double> &constraints,
                    const BulkKernel<dim>           &kernel,
                    const Matrix_t                  *stored,
                    const MatrixFree<dim, double>   *shared_cell_data)
        : constraints(constraints)
        , kernel(kernel)
        , stored(stored)
        , matrix_free(shared_cell_data ? *shared_cell_data : own_cell_data)
      {
        if (shared_cell_data == nullptr)
          reinit_cell_data(own_cell_data,
                           discretization.mapping,
                           dof_handler,
                           constraints);
        Assert(&matrix_free.get_dof_handler() == &dof_handler,
               ExcMessage("The shared cell data are of another mesh."));
        constrained = matrix_free.get_constrained_dofs();
        compute_inverse_diagonal();
      }

      void
      initialize_dof_vector(LevelVector &v) const
      {
        matrix_free.initialize_dof_vector(v);
      }

      types::global_dof_index
      m() const
      {
        return matrix_free.get_vector_partitioner()->size();
      }
      types::global_dof_index
      n() const
      {
        return m();
      }
      double
      el(const unsigned int, const unsigned int) const
      {
        Assert(false, ExcNotImplemented());
        return 0;
      }

      void
      vmult(LevelVector &dst, const LevelVector &src) const
      {
        if (stored)
          stored->vmult(dst, src);
        else
          {
            matrix_free.cell_loop(&LevelOperator::apply_range, this, dst, src,
                                  /*zero_dst_vector=*/true);
            for (const unsigned int i : constrained)
              dst.local_element(i) = src.local_element(i);
          }
      }
      void
      Tvmult(LevelVector &dst, const LevelVector &src) const
      {
        vmult(dst, src);
      }
      void
      vmult_add(LevelVector &dst, const LevelVector &src) const
      {
        LevelVector tmp;
        tmp.reinit(dst, true);
        vmult(tmp, src);
        dst += tmp;
      }
      void
      Tvmult_add(LevelVector &dst, const LevelVector &src) const
      {
        vmult_add(dst, src);
      }

      const std::shared_ptr<DiagonalMatrix<LevelVector>> &
      inverse_diagonal() const
      {
        return inverse;
      }

      /** The level's matrix, assembled (for the coarsest level). */
      void
      assemble(Matrix_t &matrix) const
      {
        const auto &dofs = matrix_free.get_dof_handler();
        const MPI_Comm comm = dofs.get_triangulation().get_communicator();
        const IndexSet owned    = dofs.locally_owned_dofs();
        const IndexSet relevant = DoFTools::extract_locally_relevant_dofs(dofs);
        TrilinosWrappers::SparsityPattern pattern(owned, owned, relevant, comm);
        DoFTools::make_sparsity_pattern(dofs, pattern, constraints, false);
        pattern.compress();
        matrix.reinit(pattern);
        MatrixFreeTools::compute_matrix(matrix_free,
                                        constraints,
                                        matrix,
                                        &LevelOperator::local_apply,
                                        this);
      }

    private:
      const AffineConstraints<double>                  &constraints;
      const BulkKernel<dim>                             kernel;
      const Matrix_t                                   *stored;
      /** The level's own cell data (unless shared). */
      MatrixFree<dim, double>                           own_cell_data;
      /** The cell data used: own_cell_data or the shared ones. */
      const MatrixFree<dim, double>                    &matrix_free;
      std::vector<unsigned int>                         constrained;
      std::shared_ptr<DiagonalMatrix<LevelVector>>      inverse =
        std::make_shared<DiagonalMatrix<LevelVector>>();

      /** K0 on one cell batch (MatrixFreeTools' interface). */
      void
      local_apply(Evaluation &phi) const
      {
        kernel.apply(phi);
      }

      void
      apply_range(const MatrixFree<dim, double>               &mf,
                  LevelVector                                 &dst,
                  const LevelVector                           &src,
                  const std::pair<unsigned int, unsigned int> &range) const
      {
        Evaluation phi(mf, range);
        for (unsigned int batch = range.first; batch < range.second; ++batch)
          {
            phi.reinit(batch);
            phi.read_dof_values(src);
            local_apply(phi);
            phi.distribute_local_to_global(dst);
          }
      }

      void
      compute_inverse_diagonal()
      {
        LevelVector &diagonal = inverse->get_vector();
        matrix_free.initialize_dof_vector(diagonal);
        if (stored)
          {
            const IndexSet &owned =
              matrix_free.get_dof_handler().locally_owned_dofs();
            for (unsigned int k = 0; k < diagonal.locally_owned_size(); ++k)
              diagonal.local_element(k) =
                stored->diag_element(owned.nth_index_in_set(k));
          }
        else
          MatrixFreeTools::compute_diagonal(matrix_free,
                                            diagonal,
                                            &LevelOperator::local_apply,
                                            this);
        for (auto &d : diagonal)
          d = std::abs(d) > 1e-300 ? 1. / d : 1.;
      }
    };


    /**
     * The coarsest level: a factorization (KLU) if it is small, else one
     * V-cycle of the AMG of its matrix (BulkAMG: ML with the rigid-body
     * modes).
     */
    class CoarseSolve : public MGCoarseGridBase<LevelVector>
    {
    public:
      template <int dim>
      CoarseSolve(const Matrix_t            &matrix,
                  std::unique_ptr<Matrix_t>  owned,
                  const Mapping<dim>        &mapping,
                  const DoFHandler<dim>     &dofs)
        : owned(std::move(owned))
      {
        if (matrix.m() <= largest_factorized_coarse_level(dim))
          {
            direct = std::make_unique<TrilinosWrappers::SolverDirect>(
              control,
              TrilinosWrappers::SolverDirect::AdditionalData(false,
                                                             "Amesos_Klu"));
            direct->initialize(matrix);
          }
        else
          {
            amg = std::make_unique<BulkAMG>();
            amg->initialize(matrix, mapping, dofs);
          }
      }

      void
      operator()(const unsigned int,
                 LevelVector       &dst,
                 const LevelVector &src) const override
      {
        if (direct)
          direct->solve(dst, src);
        else
          amg->vmult(dst, src);
      }

      double
      memory_consumption() const
      {
        return amg ? amg->memory_consumption() : 0.;
      }

    private:
      /** The coarsest level's matrix, unless it is the stored K0. */
      std::unique_ptr<Matrix_t>                               owned;
      mutable SolverControl                                   control;
      mutable std::unique_ptr<TrilinosWrappers::SolverDirect> direct;
      std::unique_ptr<BulkAMG>                                amg;
    };


    /**
     * The mesh hierarchy: the mesh itself (last), and the meshes its cells
     * of the finest level l, then l - 1, ... are coarsened away from, down
     * to the coarse mesh (first). Truncating level by level keeps every
     * coarser mesh balanced (2:1) where the mesh is, so that it is nested
     * in the finer one (coarsening every cell that can be, as
     * Triangulation::coarsen_global() does, leaves a locally refined mesh
     * unbalanced, and balancing it again refines cells the finer mesh does
     * not have). The coarser meshes are fully distributed triangulations
     * made from the coarsened mesh's description: a coarsened copy of the
     * mesh keeps the finer mesh's vertices and faces (deal.II does not
     * compact them), a made one only its own cells. Each coarse cell goes
     * to the process that owns its first child, so that the transfers stay
     * on the process where they can. The hierarchy stops above a mesh that
     * would leave some process without a cell (deal.II 9.4's fully
     * distributed triangulation cannot be made with an empty process), or
     * that p4est could not truncate (a family of cells split between
     * processes is not coarsened): its coarsest level is then the last
     * mesh made.
     */
    template <int dim>
    std::vector<std::shared_ptr<const Triangulation<dim>>>
    coarsening_sequence(const parallel::distributed::Triangulation<dim> &fine)
    {
      const unsigned int top = fine.n_global_levels() - 1;
      std::vector<std::shared_ptr<const Triangulation<dim>>> levels(top + 1);
      levels[top].reset(&fine, [](const auto *) {});
      if (top == 0)
        return levels;
      const MPI_Comm comm = fine.get_communicator();
      const RepartitioningPolicyTools::FirstChildPolicy<dim> policy(fine);
      parallel::distributed::Triangulation<dim> coarsened(
        comm, fine.get_mesh_smoothing());
      coarsened.copy_triangulation(fine);
      for (unsigned int level = top; level > 0; --level)
        {
          for (const auto &cell : coarsened.active_cell_iterators())
            if (cell->is_locally_owned() &&
                static_cast<unsigned int>(cell->level()) == level)
              cell->set_coarsen_flag();
          coarsened.execute_coarsening_and_refinement();
          int finest = 0;
          for (const auto &cell : coarsened.active_cell_iterators())
            if (cell->is_locally_owned())
              finest = std::max(finest, cell->level());
          if (Utilities::MPI::max(finest, comm) >= static_cast<int>(level))
            return std::vector<std::shared_ptr<const Triangulation<dim>>>(
              levels.begin() + level, levels.end());
          // The cells each process would own.
          const auto   partition = policy.partition(coarsened);
          const auto   n_ranks   = Utilities::MPI::n_mpi_processes(comm);
          std::vector<unsigned int> owned(n_ranks, 0);
          if (partition.size() == 0)
            owned[Utilities::MPI::this_mpi_process(comm)] =
              coarsened.n_locally_owned_active_cells();
          else
            for (const double rank : partition)
              ++owned[static_cast<unsigned int>(rank)];
          Utilities::MPI::sum(owned, comm, owned);
          if (*std::min_element(owned.begin(), owned.end()) == 0)
            return std::vector<std::shared_ptr<const Triangulation<dim>>>(
              levels.begin() + level, levels.end());
          auto made =
            std::make_shared<parallel::fullydistributed::Triangulation<dim>>(
              comm);
          for (const auto id : fine.get_manifold_ids())
            if (id != numbers::flat_manifold_id)
              made->set_manifold(id, fine.get_manifold(id));
          made->create_triangulation(
            TriangulationDescription::Utilities::
              create_description_from_triangulation(coarsened, partition));
          levels[level - 1] = made;
        }
      return levels;
    }


    template <int dim, int degree>
    class BulkMultigrid : public BulkPreconditioner
    {
    public:
      using Operator = LevelOperator<dim, degree>;
      using Smoother =
        PreconditionChebyshev<Operator, LevelVector, DiagonalMatrix<LevelVector>>;
      using Transfer = MGTransferGlobalCoarsening<dim, LevelVector>;

      BulkMultigrid(const Discretization<dim>      &discretization,
                    const KelvinVoigtMaterial<dim> &material,
                    const TimeScheme               &scheme,
                    const Matrix_t                 *finest_matrix,
                    const MatrixFree<dim, double>  *finest_cell_data)
        : discretization(discretization)
      {
        const HeapGrowth growth;
        triangulations = coarsening_sequence(discretization.triangulation);
        const unsigned int top = triangulations.size() - 1;
        dof_handlers.resize(0, top);
        constraints.resize(0, top);
        operators.resize(0, top);
        transfers.resize(0, top);

        const BulkKernel<dim> kernel(scheme, material);
        make_level_operators(kernel, finest_matrix, finest_cell_data);
        make_transfer();
        make_smoother();
        make_coarse_solve(finest_matrix);

        multigrid = std::make_unique<Multigrid<LevelVector>>(
          level_matrices, *coarse, *transfer, smoother, smoother, 0, top);
        preconditioner =
          std::make_unique<PreconditionMG<dim, LevelVector, Transfer>>(
            discretization.dof_handler, *multigrid, *transfer);
        operators[top]->initialize_dof_vector(src_work);
        operators[top]->initialize_dof_vector(dst_work);
        held = growth.measured();
        return_free_memory();
      }

      void
      vmult(Vector_t &dst, const Vector_t &src) const override
      {
        copy_owned(src, src_work);
        preconditioner->vmult(dst_work, src_work);
        copy_owned(dst_work, dst);
      }

      double
      memory_consumption() const override
      {
        return held;
      }

      bool
      memory_measured() const override
      {
        return true;
      }

    private:
      const Discretization<dim>                              &discretization;
      std::vector<std::shared_ptr<const Triangulation<dim>>>  triangulations;
      MGLevelObject<std::unique_ptr<DoFHandler<dim>>>         dof_handlers;
      MGLevelObject<AffineConstraints<double>>                constraints;
      MGLevelObject<std::unique_ptr<Operator>>                operators;
      MGLevelObject<MGTwoLevelTransfer<dim, LevelVector>>     transfers;
      std::unique_ptr<Transfer>                               transfer;
      MGSmootherPrecondition<Operator, Smoother, LevelVector> smoother;
      mg::Matrix<LevelVector>                                 level_matrices;
      std::unique_ptr<CoarseSolve>                            coarse;
      std::unique_ptr<Multigrid<LevelVector>>                 multigrid;
      std::unique_ptr<PreconditionMG<dim, LevelVector, Transfer>>
                          preconditioner;
      mutable LevelVector src_work, dst_work;
      double              held = 0;

      /**
       * On each level, the DoFs and constraints (those of the
       * discretization on the finest) and K0 with @p kernel (on the finest
       * from @p finest_matrix or @p finest_cell_data where given).
       */
      void
      make_level_operators(const BulkKernel<dim>         &kernel,
                           const Matrix_t                *finest_matrix,
                           const MatrixFree<dim, double> *finest_cell_data)
      {
        const unsigned int top = triangulations.size() - 1;
        for (unsigned int level = 0; level <= top; ++level)
          {
            const bool finest = (level == top);
            if (!finest)
              {
                dof_handlers[level] =
                  std::make_unique<DoFHandler<dim>>(*triangulations[level]);
                dof_handlers[level]->distribute_dofs(discretization.fe);
                auto &c = constraints[level];
                c.reinit(
                  DoFTools::extract_locally_relevant_dofs(*dof_handlers[level]));
                DoFTools::make_hanging_node_constraints(*dof_handlers[level],
                                                        c);
                discretization.add_boundary_constraints(*dof_handlers[level],
                                                        c);
                c.close();
              }
            operators[level] = std::make_unique<Operator>(
              discretization,
              dofs(level),
              level_constraints(level),
              kernel,
              finest ? finest_matrix : nullptr,
              finest ? finest_cell_data : nullptr);
          }
      }

      /** The geometric transfers between consecutive levels. */
      void
      make_transfer()
      {
        const unsigned int top = triangulations.size() - 1;
        for (unsigned int level = 0; level < top; ++level)
          transfers[level + 1].reinit_geometric_transfer(
            dofs(level + 1),
            dofs(level),
            level_constraints(level + 1),
            level_constraints(level));
        transfer = std::make_unique<Transfer>(
          transfers, [this](const unsigned int level, LevelVector &v) {
            operators[level]->initialize_dof_vector(v);
          });
      }

      /** Chebyshev smoothers (degree 2) with each level's diagonal. */
      void
      make_smoother()
      {
        const unsigned int top = triangulations.size() - 1;
        MGLevelObject<typename Smoother::AdditionalData> data(0, top);
        for (unsigned int level = 0; level <= top; ++level)
          {
            data[level].preconditioner      = operators[level]->inverse_diagonal();
            data[level].smoothing_range     = 20.;
            data[level].degree              = 2;
            data[level].eig_cg_n_iterations = 20;
          }
        smoother.initialize(operators, data);
        level_matrices.initialize(operators);
      }

      /**
       * The solver of the coarsest level: K0 assembled there, or the
       * stored @p finest_matrix where the mesh is its own coarsest level.
       */
      void
      make_coarse_solve(const Matrix_t *finest_matrix)
      {
        const unsigned int top = triangulations.size() - 1;
        // A mesh that cannot be coarsened is its own coarsest level: then
        // the stored K0 serves (if there is one).
        std::unique_ptr<Matrix_t> coarse_matrix;
        if (top > 0 || finest_matrix == nullptr)
          {
            coarse_matrix = std::make_unique<Matrix_t>();
            operators[0]->assemble(*coarse_matrix);
          }
        const Matrix_t &coarsest =
          coarse_matrix ? *coarse_matrix : *finest_matrix;
        coarse = std::make_unique<CoarseSolve>(coarsest,
                                               std::move(coarse_matrix),
                                               discretization.mapping,
                                               dofs(0));
      }

      const DoFHandler<dim> &
      dofs(const unsigned int level) const
      {
        return level + 1 == triangulations.size() ?
                 discretization.dof_handler :
                 *dof_handlers[level];
      }
      const AffineConstraints<double> &
      level_constraints(const unsigned int level) const
      {
        return level + 1 == triangulations.size() ?
                 discretization.constraints :
                 constraints[level];
      }
    };
  } // namespace


  template <int dim>
  std::unique_ptr<BulkPreconditioner>
  create_bulk_multigrid(const Discretization<dim>      &discretization,
                        const KelvinVoigtMaterial<dim> &material,
                        const TimeScheme               &scheme,
                        const Matrix_t                 *finest_matrix,
                        const MatrixFree<dim, double>  *finest_cell_data)
  {
    switch (discretization.fe.degree)
      {
        case 1:
          return std::make_unique<BulkMultigrid<dim, 1>>(discretization,
                                                         material,
                                                         scheme,
                                                         finest_matrix,
                                                         finest_cell_data);
        case 2:
          return std::make_unique<BulkMultigrid<dim, 2>>(discretization,
                                                         material,
                                                         scheme,
                                                         finest_matrix,
                                                         finest_cell_data);
        default:
          AssertThrow(false,
                      ExcMessage("Solver/Preconditioner = GMG is made for "
                                 "elements of degree 1 and 2."));
      }
    return nullptr;
  }


  // For 2D and 3D.
#define DYNAMIC_CONTACT_INSTANTIATE(dim)                              \
  template std::unique_ptr<BulkPreconditioner> create_bulk_multigrid( \
    const Discretization<dim> &,                                      \
    const KelvinVoigtMaterial<dim> &,                                 \
    const TimeScheme &,                                               \
    const Matrix_t *,                                                 \
    const MatrixFree<dim, double> *);

  DYNAMIC_CONTACT_INSTANTIATE(2)
  DYNAMIC_CONTACT_INSTANTIATE(3)
#undef DYNAMIC_CONTACT_INSTANTIATE
} // namespace DynamicContact
