#ifndef dynamic_contact_plugins_h
#define dynamic_contact_plugins_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace DynamicContact
{
  using namespace dealii;

  /**
   * Enter a subsection of a ParameterHandler for the lifetime of the
   * object (left again when an error is thrown inside).
   */
  class ScopedSubsection
  {
  public:
    ScopedSubsection(ParameterHandler &prm, const std::string &name)
      : prm(prm)
    {
      prm.enter_subsection(name);
    }
    ~ScopedSubsection()
    {
      prm.leave_subsection();
    }
    ScopedSubsection(const ScopedSubsection &) = delete;
    ScopedSubsection &
    operator=(const ScopedSubsection &) = delete;

  private:
    ParameterHandler &prm;
  };


  /**
   * The implementations of one interface that a parameter file can choose
   * by name, in the way of ASPECT's plugins (doc/extending.md): each
   * implementation declares and parses the entries of its own subsection,
   * named after it with a capital first letter ('exponential' ->
   * 'Exponential'), and registers itself with
   * DYNAMIC_CONTACT_REGISTER(Interface, Class, "name", "description").
   *
   * An implementation Class of @p Interface provides
   *   static void declare_parameters(ParameterHandler &prm);
   *   void parse_parameters(ParameterHandler &prm);   // may throw ExcMessage
   * and a default constructor; both functions are called inside the
   * implementation's subsection. A Class without declare_parameters() has
   * no entries and no subsection (a time scheme without parameters).
   *
   * @p Role tells apart two registries of one interface (e.g. the
   * compliance and the damped response of the foundation).
   */
  template <class Interface, class Role = Interface>
  class PluginRegistry
  {
  public:
    struct Plugin
    {
      std::string                                                   description;
      std::function<void(ParameterHandler &)>                       declare;
      std::function<std::unique_ptr<Interface>(ParameterHandler &)> create;
    };

    static PluginRegistry &
    instance()
    {
      static PluginRegistry registry;
      return registry;
    }

    /** Register @p plugin as @p name (a name given twice is a bug). */
    void
    add(const std::string &name, Plugin plugin)
    {
      AssertThrow(plugins.find(name) == plugins.end(),
                  ExcMessage("Two plugins are registered as '" + name + "'."));
      plugins.emplace(name, std::move(plugin));
    }

    /** The names of the implementations, in alphabetical order. */
    std::vector<std::string>
    registered() const
    {
      std::vector<std::string> list;
      for (const auto &[name, plugin] : plugins)
        list.push_back(name);
      return list;
    }

    /** "a|b|c", the pattern of the entry that chooses one. */
    std::string
    names(const std::string &separator = "|") const
    {
      std::string s;
      for (const std::string &name : registered())
        s += (s.empty() ? "" : separator) + name;
      return s;
    }

    /** "'a': description of a. 'b': ..." for the choosing entry. */
    std::string
    documentation() const
    {
      std::string s;
      for (const auto &[name, plugin] : plugins)
        s += (s.empty() ? "" : " ") + ("'" + name + "': ") + plugin.description;
      return s;
    }

    /** The subsection of the implementation @p name. */
    static std::string
    subsection(const std::string &name)
    {
      std::string s = name;
      if (!s.empty() && s[0] >= 'a' && s[0] <= 'z')
        s[0] = static_cast<char>(s[0] - 'a' + 'A');
      return s;
    }

    /**
     * Declare, in the current subsection of @p prm, the entry @p entry
     * choosing one implementation (default @p default_name, @p intro
     * heading the list of names and descriptions) and the subsection of
     * every implementation.
     */
    void
    declare_parameters(ParameterHandler  &prm,
                       const std::string &entry,
                       const std::string &default_name,
                       const std::string &intro) const
    {
      prm.declare_entry(entry,
                        default_name,
                        Patterns::Selection(names()),
                        intro + " " + documentation());
      declare_subsections(prm);
    }

    /**
     * The same with 'auto' (the default) as a further choice before the
     * names: @p intro says what auto chooses.
     */
    void
    declare_parameters_with_auto(ParameterHandler  &prm,
                                 const std::string &entry,
                                 const std::string &intro) const
    {
      prm.declare_entry(entry,
                        "auto",
                        Patterns::Selection("auto|" + names()),
                        intro + " " + documentation());
      declare_subsections(prm);
    }

    /** Declare the subsection of every implementation. */
    void
    declare_subsections(ParameterHandler &prm) const
    {
      for (const auto &[name, plugin] : plugins)
        if (plugin.declare)
          {
            const ScopedSubsection section(prm, subsection(name));
            plugin.declare(prm);
          }
    }

    /**
     * The implementation @p name with the parameters of its subsection
     * (of the current subsection of @p prm).
     */
    std::unique_ptr<Interface>
    create(const std::string &name, ParameterHandler &prm) const
    {
      const auto found = plugins.find(name);
      AssertThrow(found != plugins.end(),
                  ExcMessage("'" + name + "' is not one of " + names(", ") +
                             "."));
      if (!found->second.declare) // no subsection of its own
        return found->second.create(prm);
      const ScopedSubsection section(prm, subsection(name));
      return found->second.create(prm);
    }

  private:
    std::map<std::string, Plugin> plugins;
  };


  /**
   * Registers Class as @p name in PluginRegistry<Interface, Role> when the
   * program starts (a static object of the translation unit that defines
   * Class).
   */
  template <class Interface, class Class, class Role = Interface>
  struct RegisterPlugin
  {
    RegisterPlugin(const std::string &name, const std::string &description)
    {
      typename PluginRegistry<Interface, Role>::Plugin plugin;
      plugin.description = description;
      plugin.create = [](ParameterHandler &prm) -> std::unique_ptr<Interface> {
        auto object = std::make_unique<Class>();
        if constexpr (has_parameters)
          object->parse_parameters(prm);
        return object;
      };
      if constexpr (has_parameters)
        plugin.declare = [](ParameterHandler &prm) {
          Class::declare_parameters(prm);
        };
      PluginRegistry<Interface, Role>::instance().add(name, std::move(plugin));
    }

  private:
    /** Whether Class has entries of its own (declare_parameters()). */
    template <class C, class = void>
    struct Declares : std::false_type
    {};
    template <class C>
    struct Declares<C,
                    std::void_t<decltype(C::declare_parameters(
                      std::declval<ParameterHandler &>()))>> : std::true_type
    {};
    static constexpr bool has_parameters = Declares<Class>::value;
  };
} // namespace DynamicContact

#define DYNAMIC_CONTACT_PLUGIN_CONCAT2(a, b) a##b
#define DYNAMIC_CONTACT_PLUGIN_CONCAT(a, b) DYNAMIC_CONTACT_PLUGIN_CONCAT2(a, b)

/**
 * Register @p classname as the implementation @p name (a string) of
 * @p interface, described by @p description (a string for the entry's
 * documentation). Use at namespace scope in the file that defines the class.
 */
#define DYNAMIC_CONTACT_REGISTER(interface, classname, name, description) \
  static const ::DynamicContact::RegisterPlugin<interface, classname>     \
  DYNAMIC_CONTACT_PLUGIN_CONCAT(dynamic_contact_plugin_,                  \
                                __COUNTER__)(name, description)

/** The same for a registry with a role (PluginRegistry<interface, role>). */
#define DYNAMIC_CONTACT_REGISTER_ROLE(                                      \
  interface, role, classname, name, description)                            \
  static const ::DynamicContact::RegisterPlugin<interface, classname, role> \
  DYNAMIC_CONTACT_PLUGIN_CONCAT(dynamic_contact_plugin_,                    \
                                __COUNTER__)(name, description)

#endif
