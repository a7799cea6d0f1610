#include "services/daemons/described_windows.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "services/convert/plant_description.hpp"

namespace ambid::daemons {
namespace {

Eigen::Index samples_of(double seconds, double sample_time) {
  return Eigen::Index(std::llround(seconds / sample_time));
}

}  // namespace

DescribedWindows::DescribedWindows(WindowSettings settings) : settings_(settings) {
  if (!(settings_.window > 0)) throw Error("window must be > 0 s, got " + std::to_string(settings_.window));
  if (!(settings_.settle >= 0)) throw Error("settle must be >= 0 s, got " + std::to_string(settings_.settle));
}

const bus::PlantDescription* DescribedWindows::current() const {
  const auto it = known_.find(current_);
  return it == known_.end() ? nullptr : &it->second.message;
}

std::vector<DescribedWindows::Step> DescribedWindows::describe(const bus::PlantDescription& d) {
  Experiment header = convert::experiment_header(d);
  if (samples_of(settings_.window, header.sample_time) < 2)
    throw Error("plant description " + d.description_id + ": a window of " + std::to_string(settings_.window) +
                " s is shorter than 2 samples of " + std::to_string(header.sample_time) + " s");
  if (!known_.count(d.description_id)) known_order_.push_back(d.description_id);
  known_[d.description_id] = {d, std::move(header)};
  while (known_.size() > settings_.max_descriptions) {
    const auto evict =
        std::find_if(known_order_.begin(), known_order_.end(), [&](const std::string& id) { return id != current_; });
    known_.erase(*evict);
    known_order_.erase(evict);
  }
  std::vector<Step> steps;
  std::deque<bus::PlantSamples> still_waiting;
  for (bus::PlantSamples& b : waiting_) {
    if (b.description_id == d.description_id)
      process(b, steps);
    else
      still_waiting.push_back(std::move(b));
  }
  waiting_ = std::move(still_waiting);
  return steps;
}

std::vector<DescribedWindows::Step> DescribedWindows::add(const bus::PlantSamples& b) {
  std::vector<Step> steps;
  if (known_.count(b.description_id)) {
    process(b, steps);
    return steps;
  }
  waiting_.push_back(b);
  steps.push_back({Event::waiting, "description '" + b.description_id + "' not received yet", 0});
  while (waiting_.size() > settings_.max_waiting_batches) {
    const bus::PlantSamples& oldest = waiting_.front();
    steps.push_back({Event::dropped_no_description,
                     "description '" + oldest.description_id + "' did not arrive in time", oldest.count, oldest.t0,
                     oldest.t0 + double(oldest.count) * oldest.sample_time});
    waiting_.pop_front();
  }
  return steps;
}

void DescribedWindows::process(const bus::PlantSamples& b, std::vector<Step>& steps) {
  if (b.description_id != current_ || !window_) {
    const Known& k = known_.at(b.description_id);
    const std::size_t buffered = window_ ? std::size_t(window_->buffered()) : 0;
    steps.push_back({Event::description_change,
                     current_.empty() ? "description " + b.description_id
                                      : "description " + b.description_id + " replaces " + current_,
                     buffered});
    window_.emplace(k.header, samples_of(settings_.window, k.header.sample_time),
                    samples_of(settings_.settle, k.header.sample_time));
    current_ = b.description_id;
  }
  const Eigen::Index buffered = window_->buffered();
  const convert::SampleWindow::Result r = window_->add(b);
  switch (r.outcome) {
    case convert::SampleWindow::Outcome::added:
      steps.push_back({Event::added, {}, 0});
      break;
    case convert::SampleWindow::Outcome::rejected:
      steps.push_back({Event::rejected, r.reason, b.count});
      break;
    case convert::SampleWindow::Outcome::restarted:
      steps.push_back({b.seq == 0 ? Event::record_end : Event::gap, r.reason, std::size_t(buffered)});
      break;
  }
}

}  // namespace ambid::daemons
