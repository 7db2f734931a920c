#ifndef dynamic_contact_mpi_startup_h
#define dynamic_contact_mpi_startup_h

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace DynamicContact
{
  /**
   * Open MPI's settings for a cheap start of one process started without a
   * launcher (README, "Running a scene").
   *
   * Started without mpirun, an Open MPI 4 process is a "singleton": in
   * MPI_Init it starts a supporting daemon (orted) and probes the
   * high-speed networks' message layers (the 'cm' PML: PSM2, OFI), which
   * is a noticeable part of a short run's wall time. A one-process run
   * needs neither: it never spawns processes and sends no message to
   * another. So, for such a process only, the program sets before
   * MPI_Init:
   *
   * - OMPI_MCA_pml=ob1: the PML whose transports are shared memory and
   *   TCP (no network probing);
   * - OMPI_MCA_ess_singleton_isolated=1: no orted;
   * - OMPI_MCA_io_romio321_priority=100, with the previous one: MPI-IO
   *   (the checkpoints of a parallel::distributed mesh) through ROMIO.
   *   Open MPI's own MPI-IO (OMPIO) opens a shared-file-pointer file in
   *   the session directory that only orted creates: without orted it
   *   fails ("mca_sharedfp_sm_file_open: Error"); ROMIO writes and reads
   *   the same bytes without it. The priority (ROMIO 10, OMPIO 30 by
   *   default) rather than OMPI_MCA_io=romio321: an Open MPI built without
   *   ROMIO keeps OMPIO instead of having no MPI-IO at all.
   *
   * Each is set only if the environment does not have it already: a value
   * the user set always wins (also OMPI_MCA_ess_singleton_isolated=0, which
   * brings back the daemon, and with it OMPIO). A user who chose the MPI-IO
   * component (OMPI_MCA_io) keeps the daemon, which that component may
   * need. Open MPI's parameter files (openmpi-mca-params.conf) rank below
   * the environment: their pml, io priority or isolated setting is
   * overridden for such a process; set the variable in the environment to
   * keep one.
   *
   * Nothing is set for a process started by a launcher or inside a batch
   * job (any of launch_variables() in the environment): mpirun's processes
   * (OMPI_COMM_WORLD_SIZE, ...), PMIx or PMI launchers such as srun
   * (PMIX_RANK, PMI_RANK, ...), and a process in a Slurm, PBS, LSF, Flux,
   * ALPS or PALS job, which Open MPI may treat as launched by it.
   */
  std::vector<std::pair<std::string, std::string>>
  open_mpi_singleton_settings(
    const std::map<std::string, std::string> &environment);

  /**
   * The environment variables whose presence says that a launcher started
   * the process, or that it runs inside a batch job.
   */
  const std::vector<std::string> &
  launch_variables();

  /**
   * Before MPI_Init: if the program is linked with Open MPI 4 (whose
   * parameter names these are; nothing otherwise), set in the process's
   * environment the settings of open_mpi_singleton_settings() for the
   * current environment (setenv without overwriting). Returns what it set.
   */
  std::vector<std::pair<std::string, std::string>>
  set_open_mpi_singleton_defaults();
} // namespace DynamicContact

#endif
