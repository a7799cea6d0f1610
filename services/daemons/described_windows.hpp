#pragma once
// Windows of one plant's samples, each read with the plant description its batches name
// (PlantDescription on the bus; services/convert/plant_description.hpp) instead of a local
// scenario file. The identifier and FRF daemons and `ambid record` keep one per plant.
//
// - A batch whose description has not arrived waits, at most `max_waiting_batches` of them;
//   beyond that the oldest is dropped (reason no_description).
// - A batch naming another description than the window's restarts the window with the new
//   header (the buffered samples are dropped, reason description_change): samples of two
//   loops never share a window.
// - Otherwise the batch goes to a convert::SampleWindow (records, gaps, settling, malformed
//   batches as there).
#include <cstddef>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "services/bus/messages.hpp"
#include "services/convert/plant_samples.hpp"

namespace ambid::daemons {

struct WindowSettings {
  double window = 0.25;  // s per window
  double settle = 0.0;   // s dropped at the start of every record
  std::size_t max_waiting_batches = 64;
  std::size_t max_descriptions = 8;  // kept per plant (the current one is never evicted)
};

class DescribedWindows {
 public:
  // record_end: a new record (seq 0) ended the partial window; gap: a batch did not follow.
  enum class Event { added, rejected, record_end, gap, waiting, dropped_no_description, description_change };
  struct Step {
    Event event;
    std::string reason;
    std::size_t samples = 0;      // samples dropped by this step (all but added and waiting)
    double from = 0.0, to = 0.0;  // dropped_no_description: the plant time the dropped samples span
  };

  // Error for a window shorter than two samples of any description or a negative settle.
  explicit DescribedWindows(WindowSettings settings);

  // A description from the bus, kept for the batches that name it; batches that waited for it
  // are processed now. Throws Error (nothing kept) when it does not hold up
  // (convert::experiment_header) or its window would be shorter than 2 samples.
  std::vector<Step> describe(const bus::PlantDescription& description);
  std::vector<Step> add(const bus::PlantSamples& batch);

  bool full() const { return window_ && window_->full(); }
  Eigen::Index buffered() const { return window_ ? window_->buffered() : 0; }
  Experiment take() { return window_->take(); }
  // The description of the current window; null before the first described batch.
  const bus::PlantDescription* current() const;
  std::size_t waiting() const { return waiting_.size(); }

 private:
  struct Known {
    bus::PlantDescription message;
    Experiment header;
  };
  void process(const bus::PlantSamples& batch, std::vector<Step>& steps);

  WindowSettings settings_;
  std::map<std::string, Known> known_;  // by description id
  std::deque<std::string> known_order_;
  std::deque<bus::PlantSamples> waiting_;
  std::string current_;
  std::optional<convert::SampleWindow> window_;
};

}  // namespace ambid::daemons
