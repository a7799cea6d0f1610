#include "services/bus/endpoint.hpp"

#include <array>
#include <utility>

namespace ambid::bus {

std::string_view name(StatusKind kind) {
  constexpr std::array<std::string_view, 5> names{"matched", "unmatched", "alive", "liveliness_lost",
                                                  "deadline_missed"};
  return names.at(static_cast<std::size_t>(kind));
}

Endpoint::Endpoint(std::string topic, std::shared_ptr<Activity> activity)
    : topic_(std::move(topic)), activity_(std::move(activity)) {}

std::vector<StatusEvent> Endpoint::events() {
  const std::lock_guard lock(mutex_);
  std::vector<StatusEvent> out(events_.begin(), events_.end());
  events_.clear();
  return out;
}

void Endpoint::matched_changed(int current, int change) {
  matched_.store(current);
  if (change > 0) post({StatusKind::matched, current});
  if (change < 0) post({StatusKind::unmatched, current});
}

void Endpoint::liveliness_changed(int alive, int alive_change, int not_alive_change) {
  if (alive_change > 0) post({StatusKind::alive, alive});
  if (not_alive_change > 0) post({StatusKind::liveliness_lost, alive});
}

void Endpoint::liveliness_lost(int total) { post({StatusKind::liveliness_lost, total}); }

void Endpoint::deadline_missed(int total) { post({StatusKind::deadline_missed, total}); }

void Endpoint::data_available() { activity_->notify(); }

void Endpoint::post(StatusEvent event) {
  {
    const std::lock_guard lock(mutex_);
    if (events_.size() == max_events) events_.pop_front();
    events_.push_back(event);
  }
  activity_->notify();
}

}  // namespace ambid::bus
