#include <deal.II/base/config.h>
#include <deal.II/base/revision.h>

#include <dynamic_contact/run/command_line.h>
#include <dynamic_contact/run/version.h>

namespace DynamicContact
{
  namespace
  {
    /**
     * --print-parameters=FORMAT (@p arg): print the parameters in FORMAT
     * (md stands for markdown). False, with c.error set, if FORMAT is not
     * known.
     */
    bool
    read_print_format(const std::string &arg, CommandLine &c)
    {
      c.print_parameters = true;
      c.print_format     = arg.substr(19);
      if (c.print_format == "md")
        c.print_format = "markdown";
      if (c.print_format != "prm" && c.print_format != "json" &&
          c.print_format != "xml" && c.print_format != "markdown" &&
          c.print_format != "moved")
        {
          c.error = "--print-parameters: unknown format '" + c.print_format +
                    "' (prm, json, xml, markdown or moved).";
          return false;
        }
      return true;
    }


    /**
     * Check the options read into @p c together: the form of each --set,
     * options that exclude each other, and a parameter file where one is
     * needed. Sets c.error at the first problem.
     */
    void
    check_combination(CommandLine &c)
    {
      for (const auto &o : c.overrides)
        if (o.find('=') == std::string::npos)
          {
            c.error = "--set '" + o + "': expected 'Section/Entry=value'.";
            return;
          }
      if (c.resume && c.resume_auto)
        {
          c.error = "--resume and --resume=auto exclude each other.";
          return;
        }
      if (c.print_parameters &&
          (c.print_format == "markdown" || c.print_format == "moved") &&
          (!c.parameter_file.empty() || !c.overrides.empty()))
        {
          c.error = "--print-parameters=" + c.print_format +
                    " lists the declarations: it takes no parameter file and "
                    "no --set.";
          return;
        }
      if (c.validate && (c.resume || c.resume_auto || c.print_parameters))
        {
          c.error = std::string("--validate and ") +
                    (c.print_parameters ? "--print-parameters" : "--resume") +
                    " exclude each other.";
          return;
        }
      if (!c.help && !c.version && !c.print_parameters &&
          c.parameter_file.empty())
        c.error = "no parameter file given.";
    }
  } // namespace


  CommandLine
  CommandLine::parse(const int argc, const char *const *argv)
  {
    CommandLine c;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "-h" || arg == "--help")
          c.help = true;
        else if (arg == "--print-parameters")
          c.print_parameters = true;
        else if (arg.rfind("--print-parameters=", 0) == 0)
          {
            if (!read_print_format(arg, c))
              return c;
          }
        else if (arg == "--validate")
          c.validate = true;
        else if (arg == "--resume")
          c.resume = true;
        else if (arg == "--resume=auto")
          c.resume_auto = true;
        else if (arg.rfind("--resume=", 0) == 0)
          {
            c.error = "--resume takes no value but 'auto' ('" + arg + "').";
            return c;
          }
        else if (arg == "--version")
          c.version = true;
        else if (arg == "--set" || arg == "-s")
          {
            if (i + 1 >= argc)
              {
                c.error = "--set needs an argument 'Section/Entry=value'.";
                return c;
              }
            c.overrides.emplace_back(argv[++i]);
          }
        else if (arg.rfind("--set=", 0) == 0)
          c.overrides.push_back(arg.substr(6));
        else if (!arg.empty() && arg[0] == '-')
          {
            c.error = "unknown option '" + arg + "'.";
            return c;
          }
        else if (c.parameter_file.empty())
          c.parameter_file = arg;
        else
          {
            c.error = "more than one parameter file ('" + c.parameter_file +
                      "' and '" + arg + "').";
            return c;
          }
      }
    check_combination(c);
    return c;
  }


  std::string
  CommandLine::usage()
  {
    return "Usage: dynamic-contact [options] scene.prm|scene.json|scene.xml\n"
           "       mpirun -np N dynamic-contact [options] scene.prm\n"
           "\n"
           "Simulates a viscoelastic body in dynamic frictional contact with a\n"
           "deformable foundation (Barboteu & Danan 2016) as the parameter\n"
           "file describes; results go to the directory Output/Directory.\n"
           "The parameter file is read as JSON if its name ends in .json,\n"
           "as XML if in .xml (the formats --print-parameters writes), else\n"
           "as deal.II's PRM text. doc/parameters.md lists every parameter.\n"
           "\n"
           "Options:\n"
           "  -h, --help              print this help and exit\n"
           "  --print-parameters[=FORMAT]\n"
           "                          print every parameter with its value,\n"
           "                          default and documentation, and exit\n"
           "                          (the values of scene.prm if given);\n"
           "                          FORMAT: prm (default), json or xml\n"
           "                          (each can be read back as a scene), or\n"
           "                          markdown (doc/parameters.md: the\n"
           "                          declarations, for both dimensions), or\n"
           "                          moved (the entries of older layouts\n"
           "                          and where they are now, read by\n"
           "                          scripts/update-prm)\n"
           "  --validate              check the scene as a run would before\n"
           "                          its first step (parameters, mesh file,\n"
           "                          boundary ids, the functions and the\n"
           "                          friction law evaluated on the mesh,\n"
           "                          resources) without writing anything;\n"
           "                          exit 0 if it would start, else 1 with\n"
           "                          the error\n"
           "  --resume                continue from the newest complete\n"
           "                          checkpoint in Output/Directory\n"
           "                          (see Checkpoint/Every)\n"
           "  --resume=auto           the same if Output/Directory holds a\n"
           "                          checkpoint, else start a new run\n"
           "                          (for a chain of batch jobs)\n"
           "  --version               print the version of dynamic-contact\n"
           "                          and of deal.II, and exit\n"
           "  --set 'Section/Entry=value'\n"
           "                          override one entry of the parameter\n"
           "                          file (repeatable), e.g.\n"
           "                          --set 'Time/Time step=0.001'\n";
  }


  std::string
  CommandLine::version_text()
  {
    return std::string("dynamic-contact ") + DYNAMIC_CONTACT_VERSION +
           " (git " + DYNAMIC_CONTACT_GIT_REVISION + "), deal.II " +
           DEAL_II_PACKAGE_VERSION;
  }
} // namespace DynamicContact
