#include "services/daemons/plant_time.hpp"

#include <algorithm>

namespace ambid::daemons {
namespace {

// Twice what a transient-local history can replay (8 models, the state profile in
// services/bus/qos.cpp). No more: a restarted plant's windows end at the same times as the
// old epoch's first ones, which must not look like replays.
constexpr std::size_t kRemembered = 16;

}  // namespace

std::optional<PlantTime::Accepted> PlantTime::accept(double plant_time, double window) {
  bool after_restart = false;
  if (last_ && plant_time + offset_ <= *last_) {
    if (std::find(recent_.begin(), recent_.end(), plant_time) != recent_.end()) return std::nullopt;  // a replay
    offset_ = *last_ + window - plant_time;
    recent_.clear();
    after_restart = true;
  }
  last_ = plant_time + offset_;
  recent_.push_back(plant_time);
  if (recent_.size() > kRemembered) recent_.pop_front();
  return Accepted{*last_, after_restart};
}

}  // namespace ambid::daemons
