#include "services/daemons/daemon_options.hpp"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace ambid::daemons {

void add_bus_options(CLI::App& command, BusOptions& o) {
  command.add_option("--dds", o.dds, "DDS vendor: fastdds | cyclone")->capture_default_str();
  command.add_option("--domain", o.domain, "DDS domain id (0..232)")->capture_default_str();
  command.add_option("--profile", o.profile, "network profile: loopback or a vendor XML file (deploy/dds)")
      ->capture_default_str();
  command.add_option("--plant-id", o.plant_id, "plant id (the key of its samples, models and alerts)")
      ->capture_default_str();
}

void add_daemon_options(CLI::App& command, DaemonOptions& o) {
  add_bus_options(command, o);
  command.add_option("--config", o.config, "JSON configuration file (deploy/config/*.json)");
  command.add_option("--metrics-port", o.metrics_port, "serve Prometheus metrics on 127.0.0.1:PORT (0: off)")
      ->capture_default_str();
}

nlohmann::json load_config(const std::string& path) {
  if (path.empty()) return nlohmann::json::object();
  std::ifstream in(path);
  if (!in) throw Error("config " + path + ": cannot open");
  nlohmann::json config;
  try {
    config = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error("config " + path + ": not JSON: " + e.what());
  }
  if (!config.is_object()) throw Error("config " + path + ": expected a JSON object, got " + std::string(config.type_name()));
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
