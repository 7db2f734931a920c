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
  namespace
  {
    /** DataOut with the names of its fields and its patches in reach. */
    template <int dim>
    class FieldsOut : public DataOut<dim>
    {
    public:
      using DataOut<dim>::get_dataset_names;
      using DataOut<dim>::get_nonscalar_data_ranges;
      using DataOut<dim>::get_patches;
    };


    /**
     * The piece of a process that has no patch (no cell, or no face of
     * Gamma_3): a valid empty VTU with the time and step and the arrays of
     * the fields. (deal.II writes such a piece without points, cell arrays
     * and time, which readers such as meshio refuse.)
     */
    template <class Out>
    std::string
    empty_piece(const Out &out, const DataOutBase::VtkFlags &flags)
    {
      const auto         names = out.get_dataset_names();
      std::vector<bool>  in_range(names.size(), false);
      std::ostringstream s;
      s << std::setprecision(9)
        << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<FieldData>\n"
           "<DataArray type=\"Float32\" Name=\"TIME\" NumberOfTuples=\"1\" "
           "format=\"ascii\">"
        << flags.time << "</DataArray>\n";
      if (flags.cycle != 0)
        s << "<DataArray type=\"Float32\" Name=\"CYCLE\" "
             "NumberOfTuples=\"1\" format=\"ascii\">"
          << flags.cycle << "</DataArray>\n";
      s << "</FieldData>\n<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">\n"
           "<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" "
           "format=\"ascii\"> </DataArray>\n</Points>\n<Cells>\n";
      for (const char *cells : {"Int32\" Name=\"connectivity",
                                "Int32\" Name=\"offsets",
                                "UInt8\" Name=\"types"})
        s << "<DataArray type=\"" << cells
          << "\" format=\"ascii\"> </DataArray>\n";
      s << "</Cells>\n<PointData>\n";
      const auto array = [&](const std::string &name, const unsigned int n) {
        s << "<DataArray type=\"Float32\" Name=\"" << name << '"';
        if (n > 1)
          s << " NumberOfComponents=\"" << n << '"';
        s << " format=\"ascii\"> </DataArray>\n";
      };
      // Vectors with 3 components, tensors with 9, as deal.II writes them.
      for (const auto &range : out.get_nonscalar_data_ranges())
        {
          const unsigned int first = std::get<0>(range),
                             last  = std::get<1>(range);
          for (unsigned int i = first; i <= last; ++i)
            in_range[i] = true;
          const bool tensor =
            std::get<3>(range) ==
            DataComponentInterpretation::component_is_part_of_tensor;
          array(std::get<2>(range).empty() ? names[first] : std::get<2>(range),
                tensor ? 9 : 3);
        }
      for (unsigned int i = 0; i < names.size(); ++i)
        if (!in_range[i])
          array(names[i], 1);
      s << "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
      return s.str();
    }


    /**
     * DataOutFaces restricted to the faces of Gamma_3 (the boundary faces
     * with one of the contact boundary ids) of the locally owned cells.
     */
    template <int dim>
    class ContactFaces : public DataOutFaces<dim>
    {
    public:
      using FaceDescriptor = typename DataOutFaces<dim>::FaceDescriptor;
      using DataOutFaces<dim>::get_dataset_names;
      using DataOutFaces<dim>::get_nonscalar_data_ranges;
      using DataOutFaces<dim>::get_patches;

      explicit ContactFaces(const std::vector<types::boundary_id> &ids)
        : DataOutFaces<dim>(true)
        , ids(ids.begin(), ids.end())
      {}

      FaceDescriptor
      first_face() override
      {
        return search(this->triangulation->begin_active(), 0);
      }

      FaceDescriptor
      next_face(const FaceDescriptor &face) override
      {
        return search(face.first, face.second + 1);
      }

    private:
      std::set<types::boundary_id> ids;

      /** The first face of Gamma_3 at or after face @p f of @p cell. */
      FaceDescriptor
      search(const typename Triangulation<dim>::cell_iterator &start,
             unsigned int                                      f)
      {
        const auto end = this->triangulation->end();
        for (typename Triangulation<dim>::active_cell_iterator cell = start;
             cell != end;
             ++cell, f = 0)
          if (cell->is_locally_owned())
            for (; f < GeometryInfo<dim>::faces_per_cell; ++f)
              if (cell->face(f)->at_boundary() &&
                  ids.count(cell->face(f)->boundary_id()) == 1)
                return FaceDescriptor(cell, f);
        return FaceDescriptor(end, 0);
      }
    };


    /** The physical units of the fields (VTU attribute "unit"). */
    const std::map<std::string, std::string> &
    field_units()
    {
      static const std::map<std::string, std::string> units = {
        {"displacement", "m"},
        {"velocity", "m/s"},
        {"stress", "Pa"},
        {"von_mises_stress", "Pa"},
        {"stress_zz", "Pa"},
        {"contact_traction", "Pa"},
        {"contact_pressure", "Pa"},
        {"normal_pressure", "Pa"},
        {"penetration", "m"},
        {"friction_traction", "Pa"},
        {"slip_velocity", "m/s"},
        {"slip_rate", "m/s"}};
      return units;
    }

    // Nodal fields of Gamma_3 (the enums index them).
    enum Vectorial
    {
      v_traction,
      v_friction,
      v_slip,
      n_vectorial
    };
    enum Scalar
    {
      s_pressure,
      s_penetration,
      s_mu,
      s_state,
      s_slip_rate,
      n_scalar
    };

    // Nodal fields of Gamma_3, zero elsewhere: in the vector space (the
    // traction, the friction traction, the slip velocity) and in the scalar
    // space (pressure, penetration, friction data). Set by the owner of
    // each node; a hanging point of Gamma_3 (adaptive meshes) gets the
    // interpolation of its neighbours, as the finite element fields there.
    template <int dim>
    void
    contact_fields(const Discretization<dim>                &d,
                   const ContactBoundary<dim>               &boundary,
                   const std::vector<ContactNodeState<dim>> &states,
                   std::array<Vector_t, n_vectorial>        &vectorial,
                   std::array<TrilinosWrappers::MPI::Vector, n_scalar> &scalar)
    {
      std::array<Vector_t, n_vectorial>                   owned_v;
      std::array<TrilinosWrappers::MPI::Vector, n_scalar> owned_s;
      for (auto &v : owned_v)
        d.reinit_owned(v);
      for (auto &v : owned_s)
        v.reinit(d.scalar_locally_owned, d.comm);

      const auto                                  &nodes = boundary.nodes();
      std::vector<types::global_dof_index>         vi, si;
      std::array<std::vector<double>, n_vectorial> vv;
      std::array<std::vector<double>, n_scalar>    sv;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const auto          &s = states[i];
          const Tensor<1, dim> friction_traction =
            -s.friction_force / nodes[i].weight;
          const Tensor<1, dim> traction =
            -s.normal.pressure * nodes[i].normal + friction_traction;
          for (unsigned int c = 0; c < dim; ++c)
            {
              vi.push_back(nodes[i].dofs[c]);
              vv[v_traction].push_back(traction[c]);
              vv[v_friction].push_back(friction_traction[c]);
              vv[v_slip].push_back(s.slip_velocity[c]);
            }
          si.push_back(nodes[i].scalar_dof);
          sv[s_pressure].push_back(s.normal.pressure);
          sv[s_penetration].push_back(s.normal.u_nu);
          sv[s_mu].push_back(s.mu);
          sv[s_state].push_back(contact_state_code(s));
          sv[s_slip_rate].push_back(s.slip_rate);
        }

      AffineConstraints<double> scalar_hanging;
      scalar_hanging.reinit(d.scalar_locally_relevant);
      DoFTools::make_hanging_node_constraints(d.scalar_dof_handler,
                                              scalar_hanging);
      scalar_hanging.close();
      for (unsigned int f = 0; f < n_vectorial; ++f)
        {
          owned_v[f].set(vi, vv[f]);
          owned_v[f].compress(VectorOperation::insert);
          d.hanging_node_constraints.distribute(owned_v[f]);
          d.reinit_ghosted(vectorial[f]);
          vectorial[f] = owned_v[f];
        }
      for (unsigned int f = 0; f < n_scalar; ++f)
        {
          owned_s[f].set(si, sv[f]);
          owned_s[f].compress(VectorOperation::insert);
          scalar_hanging.distribute(owned_s[f]);
          scalar[f].reinit(d.scalar_locally_owned,
                           d.scalar_locally_relevant,
                           d.comm);
          scalar[f] = owned_s[f];
        }
    }

    // Stress: the cell averages of sigma = E eps(u) + C eps(w), as a
    // piecewise constant (DG0) tensor field, and the von Mises stress (and
    // in 2D sigma_zz) as cell data.
    // (stress_dofs: the DG0 tensor space, distributed by the caller).
    template <int dim>
    void
    cell_stress(const Discretization<dim>      &d,
                const KelvinVoigtMaterial<dim> &material,
                const Vector_t                 &u_ghosted,
                const Vector_t                 &w_ghosted,
                const DoFHandler<dim>          &stress_dofs,
                TrilinosWrappers::MPI::Vector  &stress,
                Vector<float>                  &von_mises,
                Vector<float>                  &stress_zz,
                Vector<float>                  &subdomain)
    {
      const FiniteElement<dim>     &stress_fe = stress_dofs.get_fe();
      TrilinosWrappers::MPI::Vector stress_owned;
      stress_owned.reinit(stress_dofs.locally_owned_dofs(), d.comm);
      const unsigned int n_cells = d.triangulation.n_active_cells();
      von_mises.reinit(n_cells);
      stress_zz.reinit(n_cells);
      subdomain.reinit(n_cells);
      {
        const QGauss<dim>                    quadrature(d.fe.degree + 1);
        FEValues<dim>                        fe_values =
          d.cell_values(quadrature, update_gradients | update_JxW_values);
        const FEValuesExtractors::Vector     displacement(0);
        std::vector<SymmetricTensor<2, dim>> eps_u(quadrature.size()),
          eps_w(quadrature.size());
        std::vector<types::global_dof_index> stress_indices(
          stress_fe.n_dofs_per_cell());
        for (const auto &cell : d.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              fe_values[displacement].get_function_symmetric_gradients(
                u_ghosted, eps_u);
              fe_values[displacement].get_function_symmetric_gradients(
                w_ghosted, eps_w);
              SymmetricTensor<2, dim> sigma;
              double                  sigma_zz = 0, volume = 0;
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                {
                  sigma +=
                    material.stress(eps_u[q], eps_w[q]) * fe_values.JxW(q);
                  sigma_zz += material.out_of_plane_stress(eps_u[q], eps_w[q]) *
                              fe_values.JxW(q);
                  volume += fe_values.JxW(q);
                }
              sigma /= volume;
              sigma_zz /= volume;
              const unsigned int index = cell->active_cell_index();
              von_mises(index)         = von_mises_stress(sigma, sigma_zz);
              stress_zz(index)         = sigma_zz;
              subdomain(index)         = cell->subdomain_id();

              typename DoFHandler<dim>::active_cell_iterator stress_cell(
                &d.triangulation, cell->level(), cell->index(), &stress_dofs);
              stress_cell->get_dof_indices(stress_indices);
              for (unsigned int i = 0; i < stress_indices.size(); ++i)
                {
                  const unsigned int c =
                    stress_fe.system_to_component_index(i).first;
                  stress_owned(stress_indices[i]) = sigma[c / dim][c % dim];
                }
            }
        stress_owned.compress(VectorOperation::insert);
        IndexSet stress_relevant;
        DoFTools::extract_locally_relevant_dofs(stress_dofs, stress_relevant);
        stress.reinit(stress_dofs.locally_owned_dofs(),
                      stress_relevant,
                      d.comm);
        stress = stress_owned;
      }
    }
  } // namespace


  template <int dim>
  VtuWriter<dim>::VtuWriter(OutputDirectory                       &directory,
                            const MPI_Comm                         comm,
                            const std::vector<types::boundary_id> &contact_ids,
                            const unsigned int                     subdivisions)
    : directory(directory)
    , comm(comm)
    , contact_ids(contact_ids)
    , subdivisions(subdivisions)
  {}


  template <int dim>
  std::vector<std::string>
  VtuWriter<dim>::file_names(const std::string &base,
                             const unsigned int step,
                             const unsigned int n_processes)
  {
    char number[32];
    std::snprintf(number, sizeof(number), "_%05u", step);
    const std::string        stem  = base + number;
    std::vector<std::string> names = {stem + ".pvtu"};
    for (unsigned int p = 0; p < n_processes; ++p)
      names.push_back(stem + "." + std::to_string(p) + ".vtu");
    return names;
  }


  template <int dim>
  void
  VtuWriter<dim>::write_index()
  {
    collectively_on_rank_zero(comm, [&]() {
      if (records.empty())
        {
          directory.remove({"solution.pvd", "contact_surface.pvd"});
          return;
        }
      // The surface has a record at every time the fields have one:
      // contact_surface_NNNNN.pvtu beside solution_NNNNN.pvtu.
      std::vector<std::pair<double, std::string>> surface;
      for (const auto &[t, file] : records)
        surface.emplace_back(t,
                             "contact_surface" +
                               file.substr(std::string("solution").size()));
      for (const auto &[name, list] :
           {std::make_pair(std::string("solution.pvd"), &records),
            std::make_pair(std::string("contact_surface.pvd"), &surface)})
        {
          std::ostringstream pvd;
          DataOutBase::write_pvd_record(pvd, *list);
          directory.claim(name);
          replace_file(directory.file(name), pvd.str());
        }
    });
  }


  namespace
  {
    /**
     * The nodal fields of the volume and of the surface Gamma_3: the
     * ghosted solution and the contact fields, added by name to the volume
     * or surface output.
     */
    template <int dim>
    struct NodalFields
    {
      const Discretization<dim>                                 &d;
      const Vector_t                                            &u_ghosted;
      const Vector_t                                            &w_ghosted;
      const std::array<Vector_t, n_vectorial>                   &vectorial;
      const std::array<TrilinosWrappers::MPI::Vector, n_scalar> &scalar;

      /** Add the nodal vector field @p v (dim components, one name). */
      template <typename Output>
      void
      add_vector(Output &out, const Vector_t &v, const std::string &name) const
      {
        out.add_data_vector(
          d.dof_handler,
          v,
          std::vector<std::string>(dim, name),
          std::vector<DataComponentInterpretation::DataComponentInterpretation>(
            dim, DataComponentInterpretation::component_is_part_of_vector));
      }

      /** Add the contact field scalar[@p index]. */
      template <typename Output>
      void
      add_scalar(Output &out, const Scalar index, const std::string &name) const
      {
        out.add_data_vector(d.scalar_dof_handler, scalar[index], name);
      }

      /** The fields of the surface (contact_surface files). */
      void
      add_to_surface(ContactFaces<dim> &faces) const
      {
        add_vector(faces, u_ghosted, "displacement");
        add_scalar(faces, s_pressure, "normal_pressure");
        add_scalar(faces, s_penetration, "penetration");
        add_vector(faces, vectorial[v_friction], "friction_traction");
        add_vector(faces, vectorial[v_slip], "slip_velocity");
        add_scalar(faces, s_mu, "friction_coefficient");
        add_scalar(faces, s_state, "contact_state");
      }

      /**
       * The fields of the volume (solution files): displacement, velocity,
       * the contact fields, and with @p friction the friction coefficient
       * and slip rate.
       */
      void
      add_to_volume(FieldsOut<dim> &data_out, const bool friction) const
      {
        add_vector(data_out, u_ghosted, "displacement");
        add_vector(data_out, w_ghosted, "velocity");
        add_vector(data_out, vectorial[v_traction], "contact_traction");
        add_scalar(data_out, s_pressure, "contact_pressure");
        add_scalar(data_out, s_state, "contact_state");
        if (friction)
          {
            add_scalar(data_out, s_mu, "friction_coefficient");
            add_scalar(data_out, s_slip_rate, "slip_rate");
          }
      }
    };


    /**
     * The stress fields of the volume: the cellwise stress tensor, the von
     * Mises stress, in 2D the out-of-plane stress_zz, and the subdomain.
     */
    template <int dim>
    void
    add_stress_fields(FieldsOut<dim>                      &data_out,
                      const DoFHandler<dim>               &stress_dofs,
                      const TrilinosWrappers::MPI::Vector &stress,
                      const Vector<float>                 &von_mises,
                      const Vector<float>                 &stress_zz,
                      const Vector<float>                 &subdomain)
    {
      data_out.add_data_vector(
        stress_dofs,
        stress,
        std::vector<std::string>(dim * dim, "stress"),
        std::vector<DataComponentInterpretation::DataComponentInterpretation>(
          dim * dim, DataComponentInterpretation::component_is_part_of_tensor));
      data_out.add_data_vector(von_mises,
                               "von_mises_stress",
                               DataOut<dim>::type_cell_data);
      if (dim == 2)
        data_out.add_data_vector(stress_zz,
                                 "stress_zz",
                                 DataOut<dim>::type_cell_data);
      data_out.add_data_vector(subdomain,
                               "subdomain",
                               DataOut<dim>::type_cell_data);
    }


    /**
     * Collective: the pieces of each process and the records of rank 0 (the
     * names of DataOut::write_vtu_with_pvtu_record) of the volume and the
     * surface output of @p step, each write checked; returns the name of
     * the volume's record.
     */
    template <int dim>
    std::string
    write_pieces(OutputDirectory             &directory,
                 const MPI_Comm               comm,
                 const unsigned int           step,
                 const FieldsOut<dim>        &data_out,
                 const ContactFaces<dim>     &faces,
                 const DataOutBase::VtkFlags &flags)
    {
      const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
      const unsigned int n    = Utilities::MPI::n_mpi_processes(comm);
      const auto         solution_names =
        VtuWriter<dim>::file_names("solution", step, n);
      const auto surface_names =
        VtuWriter<dim>::file_names("contact_surface", step, n);
      collectively(comm, [&]() {
        directory.claim(solution_names);
        directory.claim(surface_names);
      });
      collectively(comm, [&]() {
        // TIME is written as text (in the precision of the stream): enough
        // digits that it reads back as the float it is declared to be.
        const auto piece = [&](const auto &out) {
          if (out.get_patches().empty())
            return empty_piece(out, flags);
          std::ostringstream s;
          s << std::setprecision(9);
          out.write_vtu(s);
          return s.str();
        };
        write_file(directory.file(solution_names[1 + rank]), piece(data_out));
        write_file(directory.file(surface_names[1 + rank]), piece(faces));
        // The record names[0] of the pieces names[1], names[2], ...
        const auto record = [&](const auto &out, const auto &names) {
          std::ostringstream s;
          out.write_pvtu_record(s,
                                std::vector<std::string>(names.begin() + 1,
                                                         names.end()));
          write_file(directory.file(names[0]), s.str());
        };
        if (rank == 0)
          {
            record(data_out, solution_names);
            record(faces, surface_names);
          }
      });
      return solution_names[0];
    }
  } // namespace


  template <int dim>
  void
  VtuWriter<dim>::write(const unsigned int                        step,
                        const double                              time,
                        const Discretization<dim>                &d,
                        const KelvinVoigtMaterial<dim>           &material,
                        const ContactBoundary<dim>               &boundary,
                        const std::vector<ContactNodeState<dim>> &states,
                        const Vector_t                           &u,
                        const Vector_t                           &w,
                        const bool                                friction)
  {
    const Vector_t u_ghosted = d.expanded(u), w_ghosted = d.expanded(w);

    std::array<Vector_t, n_vectorial>                   vectorial;
    std::array<TrilinosWrappers::MPI::Vector, n_scalar> scalar;
    contact_fields(d, boundary, states, vectorial, scalar);

    const FESystem<dim> stress_fe(FE_DGQ<dim>(0), dim * dim);
    DoFHandler<dim>     stress_dofs(d.triangulation);
    stress_dofs.distribute_dofs(stress_fe);
    TrilinosWrappers::MPI::Vector stress;
    Vector<float>                 von_mises, stress_zz, subdomain;
    cell_stress(d,
                material,
                u_ghosted,
                w_ghosted,
                stress_dofs,
                stress,
                von_mises,
                stress_zz,
                subdomain);

    // The time and step go into every file (VTK's TimeValue field, read by
    // ParaView when a single file is opened); no date, so that equal runs
    // write equal files.
    DataOutBase::VtkFlags flags(time,
                                step,
                                false,
                                DataOutBase::VtkFlags::best_speed,
                                false,
                                field_units());

    FieldsOut<dim> data_out;
    data_out.set_flags(flags);
    data_out.attach_triangulation(d.triangulation);
    const NodalFields<dim> nodal{d, u_ghosted, w_ghosted, vectorial, scalar};
    nodal.add_to_volume(data_out, friction);
    add_stress_fields(
      data_out, stress_dofs, stress, von_mises, stress_zz, subdomain);
    const unsigned int n_subdivisions =
      subdivisions > 0 ? subdivisions : d.fe.degree;
    data_out.build_patches(d.mapping, n_subdivisions);

    // The surface Gamma_3: the same nodal fields on its faces (the faces of
    // the locally owned cells on each process).
    ContactFaces<dim> faces(contact_ids);
    faces.set_flags(flags);
    faces.attach_triangulation(d.triangulation);
    nodal.add_to_surface(faces);
    faces.build_patches(d.mapping, n_subdivisions);

    const std::string record =
      write_pieces(directory, comm, step, data_out, faces, flags);
    records.emplace_back(time, record);
    write_index();
  }


  template class VtuWriter<2>;
  template class VtuWriter<3>;
} // namespace DynamicContact
