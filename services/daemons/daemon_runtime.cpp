#include "services/daemons/daemon_runtime.hpp"

#include <systemd/sd-daemon.h>

#include "services/daemons/stop_signal.hpp"

namespace ambid::daemons {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

DaemonRuntime::DaemonRuntime(bus::Bus& bus, std::string role, std::string node, int metrics_port)
    : metrics(role, metrics_port), role_(std::move(role)), node_(std::move(node)), health_(bus.writer<bus::Health>()) {
  install_stop_handlers();
  nodes_[node_];
}

void DaemonRuntime::ready(const std::string& what) {
  sd_notify(0, "READY=1");
  log("ready: " + what);
  publish_health();
}

bool DaemonRuntime::running() {
  if (stop_requested()) {
    sd_notify(0, "STOPPING=1");
    log("stopping");
    return false;
  }
  sd_notify(0, "WATCHDOG=1");
  if (std::chrono::steady_clock::now() - last_health_ >= std::chrono::seconds(1)) publish_health();
  return true;
}

void DaemonRuntime::set_health(bus::AlertLevel level, std::string message) {
  set_health(node_, level, std::move(message));
}

void DaemonRuntime::set_health(const std::string& node, bus::AlertLevel level, std::string message) {
  nodes_[node] = {level, std::move(message)};
}

void DaemonRuntime::add_node(const std::string& node) { nodes_[node]; }

void DaemonRuntime::log(const std::string& line) const { std::cerr << "ambid " << role_ << ": " << line << std::endl; }

void DaemonRuntime::publish_health() {
  last_health_ = std::chrono::steady_clock::now();
  for (const auto& [node, state] : nodes_) {
    bus::Health h;
    h.node = node;
    h.role = role_;
    h.time = seconds_since(start_);
    h.level = state.level;
    h.message = state.message.substr(0, bus::limits::text_length);
    h.received = std::uint64_t(metrics.received.Value());
    h.published = std::uint64_t(metrics.published.Value());
    h.errors = std::uint64_t(metrics.rejected.Value());
    health_->write(h);
  }
}

}  // namespace ambid::daemons
