#pragma once
// The daemons' JSON configuration files (deploy/config/*.json): loading, typed values with
// defaults, and unknown keys refused.
#include <initializer_list>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace ambid::daemons {

// The JSON object in `path` ({} for an empty path). Throws Error naming the file and what is
// wrong with it (missing, not JSON, not an object).
nlohmann::json load_config(const std::string& path);

// config[key] as T, or `fallback` when the key is absent. Throws Error naming the key and the
// expected type when the value has another type.
template <class T>
T config_value(const nlohmann::json& config, const std::string& key, T fallback);

// Throws Error naming the first key of `config` that is not in `known` (a typo must not be
// silently ignored).
void reject_unknown_keys(const nlohmann::json& config, const std::string& where,
                         std::initializer_list<const char*> known);

}  // namespace ambid::daemons
