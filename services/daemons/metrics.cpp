#include "services/daemons/metrics.hpp"

#include "core/error.hpp"

namespace ambid::daemons {
namespace {

std::unique_ptr<prometheus::Exposer> serve(int port, const std::shared_ptr<prometheus::Registry>& registry) {
  if (port == 0) return nullptr;
  if (port < 0 || port > 65535) throw Error("metrics port must be 0..65535, got " + std::to_string(port));
  try {
    auto exposer = std::make_unique<prometheus::Exposer>("127.0.0.1:" + std::to_string(port));
    exposer->RegisterCollectable(registry);
    return exposer;
  } catch (const std::exception& e) {
    throw Error("metrics on 127.0.0.1:" + std::to_string(port) + ": " + e.what());
  }
}

}  // namespace

Metrics::Metrics(const std::string& role, int port)
    : role_(role),
      exposer_(serve(port, registry_)),
      received(counter("ambid_messages_received_total", "messages taken from the bus", {})),
      published(counter("ambid_messages_published_total", "messages written to the bus", {})),
      rejected(counter("ambid_messages_rejected_total", "malformed or refused input, failed computations", {})) {}

prometheus::Histogram& Metrics::histogram(const std::string& name, const std::string& help,
                                          const prometheus::Histogram::BucketBoundaries& buckets) {
  return prometheus::BuildHistogram().Name(name).Help(help).Register(*registry_).Add({{"role", role_}}, buckets);
}

prometheus::Counter& Metrics::counter(const std::string& name, const std::string& help,
                                      const prometheus::Labels& labels) {
  prometheus::Labels all = labels;
  all["role"] = role_;
  return prometheus::BuildCounter().Name(name).Help(help).Register(*registry_).Add(all);
}

}  // namespace ambid::daemons
