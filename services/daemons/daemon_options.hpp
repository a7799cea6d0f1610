#pragma once
// What every daemon and every operator command that talks to the bus takes on its command line:
// --dds fastdds|cyclone, --domain N, --profile loopback|FILE, --plant-id ID, --config FILE (JSON).
#include <initializer_list>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>

#include "services/bus/bus.hpp"

namespace ambid::daemons {

struct BusOptions {
  std::string dds = "cyclone";
  int domain = 0;
  std::string profile{bus::loopback_profile};
  std::string plant_id = "bearing-1";

  std::unique_ptr<bus::Bus> connect() const { return bus::make_bus(dds, domain, profile); }
};

struct DaemonOptions : BusOptions {
  std::string config;  // JSON file; empty: defaults only
  int metrics_port = 0;  // Prometheus endpoint on 127.0.0.1; 0: none
};

void add_bus_options(CLI::App& command, BusOptions& options);
void add_daemon_options(CLI::App& command, DaemonOptions& options);

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
