#ifndef dynamic_contact_error_messages_h
#define dynamic_contact_error_messages_h

#include <exception>
#include <iosfwd>
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

  /**
   * While alive, discard what is written to std::cerr (muparser's error
   * dump, which deal.II prints before throwing: the exception carries the
   * same information, and the user gets it once, as our one error line).
   */
  class SilenceStderr
  {
  public:
    SilenceStderr();
    ~SilenceStderr();

  private:
    std::streambuf *saved;
  };

  /** A muparser error as a user reads it (no "Parsing Error at Column"). */
  std::string
  expression_error_message(const std::exception &e);

  /**
   * @p x in scientific notation with @p decimals digits after the point
   * ("%.Ne"): the one format of numbers in messages, progress lines and
   * CSV files (independent of stream state and locale).
   */
  std::string
  scientific(const double x, const unsigned int decimals = 3);

  /**
   * A number as a parameter file would write it (the stream's default
   * format): a parameter's value quoted in an error message.
   */
  std::string
  str(const double x);

  /** Six significant digits: what regression output compares. */
  inline std::string
  sig6(const double x)
  {
    return scientific(x, 5);
  }
} // namespace DynamicContact

#endif
