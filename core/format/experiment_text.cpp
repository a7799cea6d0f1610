#include "core/format/experiment_text.hpp"

#include <array>
#include <charconv>

namespace ambid {

std::string number_text(double value) {
  std::array<char, 32> buffer{};  // the longest shortest-form double is 24 characters
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  std::string text(buffer.data(), result.ptr);
  // to_chars pads the exponent to two digits ("1e-04"); "1e-4" reads the same and better.
  if (const auto e = text.find('e'); e != std::string::npos && text[e + 2] == '0') text.erase(e + 2, 1);
  return text;
}

std::optional<double> parse_number(std::string_view text) {
  // from_chars refuses a leading '+', which some writers put on positive numbers.
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value, std::chars_format::general);
  if (result.ec != std::errc() || result.ptr != end) return std::nullopt;
  return value;
}

std::string quote_excerpt(std::string_view text, std::size_t limit) {
  if (text.size() <= limit) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, limit)) + "...'";
}

}  // namespace ambid
