// The ParaView output, read back with a reader that is not the program's
// (meshio, by tests/read_output.py): the small paper scene (32 x 8 Q1
// cells, 33 nodes on Gamma_3, friction) up to t = 0.25 (32 steps of
// 1/128 s) with Output times 0.1 and 0.2 (the steps 13 and 26),
//   serial    1 process, VTU every = 16: VTU at the steps 0, 13, 16, 26, 32
//             (the cadence, the Output times, the first and the last step);
//   parallel  2 processes, VTU every = 0: the steps 0, 13, 26, 32 (the
//             Output times are honoured without a cadence), two pieces per
//             record;
//   block_3d  prm/pressed_block_3d.prm (2 x 2 x 1 cells, no friction) on 2
//             processes, 2 steps of 1 s: the second process has no face of
//             Gamma_3 and writes an empty surface piece (with its time);
//   none      Write VTU = false: no VTU file and no index, the contact CSVs
//             as before.
// For each VTU step the reader checks the time in every piece, the stress
// tensor (symmetric, constant per cell, its von Mises the von_mises_stress
// field), and the contact surface: one distinct point per node of Gamma_3,
// its fields equal to the contact CSV of the step node by node, the state
// codes. Every file of the runs is in the directory's manifest.

#include "program_tools.h"

using namespace program_tools;

namespace
{
  const std::vector<std::string> common = with({"--set",
                                                "Time/End time=0.25",
                                                "--set",
                                                "Output/Output every=0",
                                                "--set",
                                                "Output/Output times=0.1, 0.2"},
                                               quiet);

  std::vector<std::string>
  arguments(const std::string &directory, const std::vector<std::string> &more)
  {
    std::vector<std::string> a = {test_tools::scene(
                                    "barboteu_danan_2016_small.prm"),
                                  "--set",
                                  "Output/Directory=" + directory};
    a.insert(a.end(), common.begin(), common.end());
    a.insert(a.end(), more.begin(), more.end());
    return a;
  }

  const std::vector<std::string> block_3d =
    with({test_tools::scene("pressed_block_3d.prm"),
          "--set",
          "Output/Directory=block_3d",
          "--set",
          "Time/End time=2",
          "--set",
          "Output/Write VTU=true"},
         quiet);

  /** The files of @p directory (not the manifest and the lock). */
  std::set<std::string>
  files_of(const fs::path &directory)
  {
    std::set<std::string> names;
    for (const auto &e : fs::directory_iterator(directory))
      if (e.path().filename().string().rfind(".dynamic-contact", 0) != 0)
        names.insert(e.path().filename().string());
    return names;
  }

  /** Every file of @p directory is listed in its manifest. */
  bool
  all_in_manifest(const fs::path &directory)
  {
    const std::set<std::string> listed = manifest(directory);
    for (const auto &name : files_of(directory))
      if (listed.count(name) == 0)
        return false;
    return true;
  }

  /**
   * Write VTU = false: no VTU at all, whatever VTU every and Output
   * times say; the contact CSVs as before.
   */
  void
  check_without_vtu(Checks &checks)
  {
    const std::string name = "none";
    fs::remove_all(name);
    Launch launch;
    launch.name       = name;
    launch.timeout    = 300;
    const Outcome run = execute(arguments(name,
                                          {"--set",
                                           "Output/Write VTU=false",
                                           "--set",
                                           "Output/VTU every=1"}),
                                launch);
    checks.add(run.succeeded(), "none: the run completes");
    std::string vtu, csv;
    for (const auto &f : files_of(name))
      {
        if (f.find("vtu") != std::string::npos ||
            f.find(".pvd") != std::string::npos)
          vtu += " " + f;
        if (f.rfind("contact_", 0) == 0)
          csv += " " + f;
      }
    test_tools::out() << "none: VTU files and indexes:"
                      << (vtu.empty() ? " none" : vtu)
                      << "; contact CSVs:" << csv << std::endl;
    checks.add(vtu.empty(), "none: no VTU file and no .pvd");
    checks.add(csv == " contact_00000.csv contact_00013.csv contact_00026.csv "
                      "contact_00032.csv",
               "none: the contact CSVs of the steps 0, 13, 26 and 32");
  }
} // namespace

int
main()
{
  auto  &out = test_tools::out();
  Checks checks;

  for (const auto &[name, processes, args] :
       {std::make_tuple(std::string("serial"),
                        0u,
                        arguments("serial",
                                  {"--set",
                                   "Output/Write VTU=true",
                                   "--set",
                                   "Output/VTU every=16"})),
        std::make_tuple(std::string("parallel"),
                        2u,
                        arguments("parallel",
                                  {"--set",
                                   "Output/Write VTU=true",
                                   "--set",
                                   "Output/VTU every=0"})),
        std::make_tuple(std::string("block_3d"), 2u, block_3d)})
    {
      fs::remove_all(name);
      Launch launch;
      launch.name       = name;
      launch.processes  = processes;
      launch.timeout    = 300;
      const Outcome run = execute(args, launch);
      checks.add(run.succeeded(), name + ": the run completes");
      if (!run.succeeded())
        out << run.err;

      Launch reader;
      reader.name    = name + "-read";
      reader.program = "/usr/bin/python3";
      const Outcome read =
        execute({std::string(REPOSITORY_DIR) + "/tests/read_output.py", name},
                reader);
      out << read.out;
      if (!read.err.empty())
        out << "stderr:\n" << read.err;
      checks.add(read.succeeded(),
                 name + ": meshio reads the VTU files and every check of "
                        "tests/read_output.py holds");
      checks.add(all_in_manifest(name),
                 name + ": every file is in the manifest");
    }

  check_without_vtu(checks);
  checks.assert_all();
}
