#pragma once
// `--set NAME=VALUE` options: parsed strictly (the whole value must be a finite number).
#include <map>
#include <string>
#include <vector>

namespace ambid::cli {

// Throws ambid::Error naming the malformed item.
std::map<std::string, double> parse_parameter_overrides(const std::vector<std::string>& items);

}  // namespace ambid::cli
