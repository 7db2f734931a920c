#ifndef dynamic_contact_number_or_auto_h
#define dynamic_contact_number_or_auto_h

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>

namespace DynamicContact
{
  /**
   * The number that the whole of @p text is (read by @p read, e.g.
   * std::stol or std::stod), or std::nullopt for 'auto'; an ExcMessage
   * with @p error where it is neither or fails @p valid (an entry that is
   * a number or 'auto': its Pattern is Anything).
   */
  template <typename Number, typename Read>
  std::optional<Number>
  number_or_auto(const std::string                 &text,
                 const Read                        &read,
                 const std::function<bool(Number)> &valid,
                 const std::string                 &error)
  {
    if (text == "auto")
      return std::nullopt;
    std::size_t end   = 0;
    Number      value = 0;
    bool        read_ = false;
    try
      {
        value = read(text, &end);
        read_ = true;
      }
    catch (...)
      {}
    AssertThrow(read_ && end == text.size() && valid(value),
                dealii::ExcMessage(error));
    return value;
  }

  /** A finite number > 0, or std::nullopt for 'auto' (number_or_auto()). */
  inline std::optional<double>
  positive_or_auto(const std::string &text, const std::string &error)
  {
    return number_or_auto<double>(
      text,
      [](const std::string &t, std::size_t *end) { return std::stod(t, end); },
      [](const double v) { return std::isfinite(v) && v > 0; },
      error);
  }

  /**
   * An integer >= 0 that an unsigned int holds, or std::nullopt for 'auto'
   * (number_or_auto()).
   */
  inline std::optional<unsigned int>
  count_or_auto(const std::string &text, const std::string &error)
  {
    const std::optional<long> value = number_or_auto<long>(
      text,
      [](const std::string &t, std::size_t *end) { return std::stol(t, end); },
      [](const long v) {
        return v >= 0 && v <= std::numeric_limits<unsigned int>::max();
      },
      error);
    if (!value)
      return std::nullopt;
    return static_cast<unsigned int>(*value);
  }
} // namespace DynamicContact

#endif
