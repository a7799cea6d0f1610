#pragma once
// Prometheus metrics of one daemon, served at http://127.0.0.1:PORT/metrics (loopback only;
// port 0: counted but not served). Every daemon has the message counters, labelled by role:
//   ambid_messages_received_total   batches, models or commands taken from the bus
//   ambid_messages_published_total  messages written
//   ambid_messages_rejected_total   malformed or refused input, failed computations (dropped)
// and adds its own (identification time, alerts by level).
#include <memory>
#include <string>

#include <prometheus/counter.h>
#include <prometheus/exposer.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

namespace ambid::daemons {

class Metrics {
 public:
  Metrics(const std::string& role, int port);

  prometheus::Histogram& histogram(const std::string& name, const std::string& help,
                                   const prometheus::Histogram::BucketBoundaries& buckets);
  prometheus::Counter& counter(const std::string& name, const std::string& help, const prometheus::Labels& labels);

 private:
  std::string role_;
  std::shared_ptr<prometheus::Registry> registry_ = std::make_shared<prometheus::Registry>();
  std::unique_ptr<prometheus::Exposer> exposer_;

 public:
  prometheus::Counter& received;
  prometheus::Counter& published;
  prometheus::Counter& rejected;
};

}  // namespace ambid::daemons
