#ifndef dynamic_contact_error_messages_h
#define dynamic_contact_error_messages_h

#include <exception>
#include <string>

namespace DynamicContact
{
  /**
   * The message of an exception as a user should read it: for deal.II's
   * exceptions only their specific information (not the file, line and
   * function of the library that threw), trimmed to one paragraph.
   */
  std::string
  error_message(const std::exception &e);
} // namespace DynamicContact

#endif
