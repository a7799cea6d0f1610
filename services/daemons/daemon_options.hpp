#pragma once
// What every daemon and every operator command that talks to the bus takes on its command line:
// --dds fastdds|cyclone, --domain N, --profile loopback|FILE, --plant-id ID, --config FILE (JSON,
// config_json.hpp).
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "services/bus/make_bus.hpp"
#include "services/daemons/config_json.hpp"

namespace ambid::daemons {

struct BusOptions {
  std::string dds = "cyclone";
  int domain = 0;
  std::string profile{bus::loopback_profile};
  std::string plant_id = "bearing-1";

  std::unique_ptr<bus::Bus> connect() const { return bus::make_bus(dds, domain, profile); }
};

struct DaemonOptions : BusOptions {
  std::string config;    // JSON file; empty: defaults only
  int metrics_port = 0;  // Prometheus endpoint on 127.0.0.1; 0: none
};

void add_bus_options(CLI::App& command, BusOptions& options);
void add_daemon_options(CLI::App& command, DaemonOptions& options);

}  // namespace ambid::daemons
