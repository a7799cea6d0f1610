#include "services/daemons/daemon_options.hpp"

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

}  // namespace ambid::daemons
