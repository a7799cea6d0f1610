#include "services/daemons/sample_gaps.hpp"

#include <cmath>

namespace ambid::daemons {

std::string SampleGap::message() const {
  std::string text = "missed " + std::to_string(samples) + " samples (plant time " + std::to_string(from) + " to " +
                     std::to_string(to) + " s";
  if (batches > 0) text += ", " + std::to_string(batches) + " batches";
  return text + "): a hole in the identified history";
}

std::optional<SampleGap> SampleGaps::check(const bus::PlantSamples& b) {
  if (!std::isfinite(b.t0) || !(b.sample_time > 0) || !std::isfinite(b.sample_time) || b.count == 0)
    return std::nullopt;
  std::uint64_t batches = numbers_.missed(b.seq);  // a new record (seq 0) is no gap
  std::optional<SampleGap> gap;
  // Half a sample of tolerance: batch start times are sums of sample times.
  const double jump = next_t_ ? b.t0 - *next_t_ : 0.0;
  // The clock went back: a restarted plant, whose first record numbers its batches from 0.
  if (jump < -0.5 * b.sample_time) batches = b.seq;
  if (jump > 0.5 * b.sample_time) {
    gap = SampleGap{*next_t_, b.t0, std::uint64_t(std::llround(jump / b.sample_time)), batches};
  } else if (batches > 0) {
    // The clock went back (a restarted plant): the hole is the batches of its record before
    // this one (batches of a record are of equal size).
    const std::uint64_t samples = batches * b.count;
    gap = SampleGap{b.t0 - double(samples) * b.sample_time, b.t0, samples, batches};
  }
  next_t_ = b.t0 + double(b.count) * b.sample_time;
  return gap;
}

}  // namespace ambid::daemons
