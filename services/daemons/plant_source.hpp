#pragma once
// The plant daemon's sources of samples, one record at a time:
//   sim     the closed loop of a scenario file (scenario_json.hpp), record after record, each
//           with the next seed
//   replay  an experiment file (core/experiment_io.hpp), over and over
//   rig     a controller board over the UDP rig protocol (rig_source.hpp), samples as they come
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/experiment.hpp"
#include "plant_sim/scenario.hpp"
#include "services/bus/messages.hpp"
#include "services/daemons/metrics.hpp"

namespace ambid::daemons {

// A requested excitation for the next sim records (ExcitationCommand, already checked).
struct ExcitationRequest {
  std::string kind;
  double amplitude = 0.0;
  double f_min = 0.0, f_max = 0.0;
};

// Consecutive samples of a source; `starts_record`: they begin a new record (seq 0 on the bus).
struct SourceRows {
  Experiment rows;
  bool starts_record = true;
};

// A change of a live source's condition, announced on PlantSourceState (e.g. the rig silent).
struct SourceCondition {
  bool ok = true;
  std::string message;
};

// The rig gateway's settings (plant daemon config keys rig_*).
struct RigSettings {
  double silence = 1.0;        // s without a frame: the rig is announced silent
  double reply_timeout = 0.5;  // s to wait for the ACK/NACK of an excitation command
  bool allow_remote = false;   // a rig address off loopback only when set
};

struct SourceContext {
  Eigen::Index batch_samples = 500;  // rows per SourceRows of a live source
  RigSettings rig;
  Metrics* metrics = nullptr;  // counters of the rig frames; required for rig
  std::function<void(const std::string&)> log;
};

class PlantSource {
 public:
  virtual ~PlantSource() = default;
  // Record sources (sim, replay) return a whole record; a live source (rig) waits at most
  // `wait` and returns nullopt when nothing is ready.
  virtual std::optional<SourceRows> next_rows(std::chrono::milliseconds wait) = 0;
  // True when the source paces itself (the rig); the daemon paces the others at `speed`.
  virtual bool live() const { return false; }
  // Once per change of a live source's condition; nullopt when nothing changed.
  virtual std::optional<SourceCondition> condition_change() { return std::nullopt; }
  // Applies an excitation to the following records; Error when the source cannot excite.
  virtual void excite(const ExcitationRequest& request) = 0;
  bus::SourceKind kind() const { return kind_; }
  const std::string& target() const { return target_; }

 protected:
  PlantSource(bus::SourceKind kind, std::string target) : kind_(kind), target_(std::move(target)) {}

 private:
  bus::SourceKind kind_;
  std::string target_;
};

// Reads and checks the target now (file missing, bad scenario, rig address malformed or not
// answering, ...): Error naming it.
std::unique_ptr<PlantSource> make_plant_source(bus::SourceKind kind, const std::string& target,
                                               const SourceContext& context);

}  // namespace ambid::daemons
