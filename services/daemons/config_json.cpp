#include "services/daemons/config_json.hpp"

#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/json_text.hpp"

namespace ambid::daemons {

nlohmann::json load_config(const std::string& path) {
  if (path.empty()) return nlohmann::json::object();
  nlohmann::json config;
  try {
    config = parse_json_text(read_json_file(path));
  } catch (const Error& e) {
    throw Error("config " + path + ": " + e.what());
  }
  if (!config.is_object())
    throw Error("config " + path + ": expected a JSON object, got " + std::string(config.type_name()));
  return config;
}

template <class T>
T config_value(const nlohmann::json& config, const std::string& key, T fallback) {
  const auto it = config.find(key);
  if (it == config.end()) return fallback;
  try {
    return it->get<T>();
  } catch (const nlohmann::json::exception&) {
    throw Error("config key '" + key + "': unexpected value " + it->dump());
  }
}

template double config_value(const nlohmann::json&, const std::string&, double);
template int config_value(const nlohmann::json&, const std::string&, int);
template bool config_value(const nlohmann::json&, const std::string&, bool);
template std::string config_value(const nlohmann::json&, const std::string&, std::string);
template std::uint64_t config_value(const nlohmann::json&, const std::string&, std::uint64_t);
template nlohmann::json config_value(const nlohmann::json&, const std::string&, nlohmann::json);

void reject_unknown_keys(const nlohmann::json& config, const std::string& where,
                         std::initializer_list<const char*> known) {
  for (const auto& [key, value] : config.items()) {
    bool found = false;
    for (const char* k : known) found = found || key == k;
    if (!found) {
      std::string list;
      for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
      throw Error(where + ": unknown key '" + key + "' (known: " + list + ")");
    }
  }
}

}  // namespace ambid::daemons
