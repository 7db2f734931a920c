#ifndef dynamic_contact_command_line_h
#define dynamic_contact_command_line_h

#include <string>
#include <vector>

namespace DynamicContact
{
  /** What the command line asks for. */
  struct CommandLine
  {
    bool help             = false;
    bool print_parameters = false;
    /** --print-parameters=FORMAT: prm (the default), json, xml, markdown. */
    std::string print_format = "prm";
    /** --validate: check the scene as a run would, without running it. */
    bool validate = false;
    bool resume   = false;
    /** --resume=auto: resume if Output/Directory has a checkpoint, else
     *  start a new run (a chain of batch jobs). */
    bool                     resume_auto = false;
    bool                     version     = false;
    std::string              parameter_file;
    std::vector<std::string> overrides; // "Section/Entry=value"
    std::string              error;     // non-empty: a usage error

    static CommandLine
    parse(const int argc, const char *const *argv);

    static std::string
    usage();

    /** "dynamic-contact X.Y.Z (git H), deal.II A.B.C" */
    static std::string
    version_text();
  };
} // namespace DynamicContact

#endif
