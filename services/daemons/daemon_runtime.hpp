#pragma once
// What every daemon's main loop shares: the stop signals, systemd notification (READY=1 once
// the bus is up, WATCHDOG=1 every loop turn; no-ops when not started by systemd), and its
// Health message once a second with the counters an operator and the metrics look at.
// A daemon serving several plants also publishes one Health per plant (node PLANT/ROLE), with
// that plant's level and message and the process's counters.
#include <chrono>
#include <cstdint>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "services/bus/bus.hpp"
#include "services/daemons/metrics.hpp"

namespace ambid::daemons {

class DaemonRuntime {
 public:
  // Installs the stop handlers and creates the Health writer; role: "plant", "identifier", ...
  // metrics_port: 0 for none (metrics.hpp).
  DaemonRuntime(bus::Bus& bus, std::string role, std::string node, int metrics_port);

  // After the daemon's endpoints exist: tells systemd it is ready and logs one line.
  void ready(const std::string& what);
  // True until SIGINT/SIGTERM. Pets the watchdog and publishes Health when a second has passed.
  bool running();
  // Level and message of the next Health messages (e.g. WARN "refused excitation ...").
  void set_health(bus::AlertLevel level, std::string message);
  // The same for another node (one plant of the daemon); added on first use, published from then on.
  void set_health(const std::string& node, bus::AlertLevel level, std::string message);
  void add_node(const std::string& node);
  // One line on stderr, prefixed with the role (daemons log; libraries never print).
  void log(const std::string& line) const;

  Metrics metrics;  // its message counters also go into Health

 private:
  void publish_health();

  struct NodeHealth {
    bus::AlertLevel level = bus::AlertLevel::ok;
    std::string message = "running";
  };

  std::string role_, node_;
  std::unique_ptr<bus::Writer<bus::Health>> health_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_health_{};
  std::map<std::string, NodeHealth> nodes_;  // node_ and the plants' nodes
};

// Seconds since the daemon's runtime started (the clock of Health.time).
double seconds_since(std::chrono::steady_clock::time_point start);

}  // namespace ambid::daemons
