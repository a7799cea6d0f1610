#pragma once
// The identifier's view of the plant's samples (issue 18): batches are numbered per record
// (services/convert/plant_samples.hpp) and the plant's clock runs on across records and
// sources, so a batch that starts later than the previous one ended, or a jump forward in the
// batch numbers, is samples this consumer never received (it fell behind, was stopped, or the
// bus dropped them): a hole in the history it must report. The numbers go through ModelGaps,
// the diagnostics' rule for the identifier's models. A new record (seq 0) starts again without
// a gap; so does a clock that goes back (a restarted plant daemon), unless its first batch seen
// is not its first (seq > 0): those missed batches are the gap, on the new clock.
#include <cstdint>
#include <optional>
#include <string>

#include "services/bus/messages.hpp"
#include "services/daemons/model_gaps.hpp"

namespace ambid::daemons {

struct SampleGap {
  double from = 0.0, to = 0.0;  // plant time: where the samples should have continued, where they did
  std::uint64_t samples = 0;    // samples missed, from the time jump
  std::uint64_t batches = 0;    // batch numbers skipped within a record
  std::string message() const;  // for the log, Health and the alert
};

class SampleGaps {
 public:
  // The gap before `batch`, if any. A batch without a finite start time or a positive sample
  // time (malformed; refused downstream) is ignored.
  std::optional<SampleGap> check(const bus::PlantSamples& batch);

 private:
  ModelGaps numbers_;
  std::optional<double> next_t_;  // where the next batch should start
};

}  // namespace ambid::daemons
