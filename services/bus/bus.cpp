#include "services/bus/bus.hpp"

#include <utility>

namespace ambid::bus {

Bus::Bus(std::string vendor, int domain) : vendor_(std::move(vendor)), domain_(domain) {}

bool Bus::wait(std::chrono::milliseconds timeout) {
  const std::uint64_t now = activity_->wait(seen_, timeout);
  const bool changed = now != seen_;
  seen_ = now;
  return changed;
}

}  // namespace ambid::bus
