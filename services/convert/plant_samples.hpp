#pragma once
// PlantSamples batches <-> experiment rows. The plant daemon cuts an experiment into batches;
// the identifier and `ambid record` collect batches back into windows of consecutive samples.
//
// Batch numbering (the contract of the plant_samples topic): `seq` counts the batches of one
// continuous record from 0; a batch with seq 0 starts a new record (a new simulated record, a
// replay from its start, a swapped source), so a window never spans two records. A missing seq
// (a batch lost or dropped) also starts the window again.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// Rows [begin, begin + count) of `e` as one message; times shifted by `time_offset`.
bus::PlantSamples sample_batch(const Experiment& e, Eigen::Index begin, Eigen::Index count, const std::string& plant_id,
                               std::uint64_t seq, double time_offset);

class SampleWindow {
 public:
  enum class Outcome { added, restarted, rejected };
  struct Result {
    Outcome outcome;
    std::string reason;  // why rejected or restarted
  };

  // `header`: the names, sample time, plant and controller every window gets; `samples`: the
  // window length (>= 2); `settle`: samples dropped after the start of every record (a new
  // record starts at the nominal operating point: its first samples are a transient).
  SampleWindow(Experiment header, Eigen::Index samples, Eigen::Index settle = 0);

  // Refuses (nothing kept) a batch whose names or sample time differ from the header's, whose
  // value arrays do not hold count rows, or with a non-finite value.
  Result add(const bus::PlantSamples& batch);
  bool full() const { return Eigen::Index(t_.size()) >= samples_; }
  Eigen::Index buffered() const { return Eigen::Index(t_.size()); }
  // The first `samples` buffered rows as an experiment (call only when full()); the rest stay
  // for the next window.
  Experiment take();
  void clear();

 private:
  std::string check(const bus::PlantSamples& batch) const;

  Experiment header_;
  Eigen::Index samples_, settle_;
  Eigen::Index to_drop_ = 0;
  std::vector<double> t_, y_, u_, r_;  // row-major
  std::uint64_t next_seq_ = 0;
  double next_t_ = 0.0;
  bool started_ = false;
};

}  // namespace ambid::convert
