#include <deal.II/base/exceptions.h>

#include <dynamic_contact/base/error_messages.h>

#include <cstdio>
#include <iostream>
#include <regex>
#include <sstream>

namespace DynamicContact
{
  std::string
  error_message(const std::exception &e)
  {
    std::string text;
    if (const auto *deal_ii = dynamic_cast<const dealii::ExceptionBase *>(&e))
      {
        std::ostringstream info;
        deal_ii->print_info(info);
        text = info.str();
        if (text.find_first_not_of(" \n\t") == std::string::npos)
          text = deal_ii->get_exc_name();
      }
    else
      text = e.what();

    // One printable paragraph: collapse line breaks and runs of blanks.
    std::string result;
    bool        blank = false;
    for (const char c : text)
      {
        const bool is_blank = (c == ' ' || c == '\n' || c == '\t' || c == '\r');
        if (is_blank)
          blank = !result.empty();
        else
          {
            if (blank)
              result += ' ';
            // Other control characters (from a binary file quoted in a
            // parser's message) as \xNN: the message stays printable text.
            const unsigned char u = static_cast<unsigned char>(c);
            if (u < 0x20 || u == 0x7f)
              {
                char escaped[8];
                std::snprintf(escaped, sizeof(escaped), "\\x%02x", u);
                result += escaped;
              }
            else
              result += c;
            blank = false;
          }
      }
    return result;
  }


  namespace
  {
    std::ostringstream &
    sink()
    {
      static std::ostringstream s;
      return s;
    }
  } // namespace

  SilenceStderr::SilenceStderr()
    : saved(std::cerr.rdbuf(sink().rdbuf()))
  {}

  SilenceStderr::~SilenceStderr()
  {
    std::cerr.rdbuf(saved);
    sink().str("");
  }


  std::string
  expression_error_message(const std::exception &e)
  {
    // deal.II 9.4 reports muparser's error code as a column.
    return std::regex_replace(error_message(e),
                              std::regex(R"(Parsing Error at Column -?\d+\. )"),
                              "");
  }


  std::string
  str(const double x)
  {
    std::ostringstream s;
    s << x;
    return s.str();
  }


  std::string
  scientific(const double x, const unsigned int decimals)
  {
    char buffer[48];
    std::snprintf(
      buffer, sizeof(buffer), "%.*e", static_cast<int>(decimals), x);
    return buffer;
  }
} // namespace DynamicContact
