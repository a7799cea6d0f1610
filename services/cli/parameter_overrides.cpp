#include "services/cli/parameter_overrides.hpp"

#include <charconv>
#include <cmath>

#include "core/error.hpp"

namespace ambid::cli {

std::map<std::string, double> parse_parameter_overrides(const std::vector<std::string>& items) {
  std::map<std::string, double> values;
  for (const auto& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw Error("--set expects NAME=VALUE, got '" + item + "'");
    const std::string name = item.substr(0, eq), text = item.substr(eq + 1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
      throw Error("--set " + name + ": '" + text + "' is not a finite number");
    if (!values.emplace(name, value).second) throw Error("--set " + name + " given twice");
  }
  return values;
}

}  // namespace ambid::cli
