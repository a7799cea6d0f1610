#pragma once
// The plant daemon's sources of samples, one record at a time:
//   sim     the closed loop of a scenario file (scenario_json.hpp), record after record, each
//           with the next seed
//   replay  an experiment file (core/experiment_io.hpp), over and over
//   rig     not built yet: refused with a clear error
#include <cstdint>
#include <memory>
#include <string>

#include "core/experiment.hpp"
#include "plant_sim/scenario.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

// A requested excitation for the next sim records (ExcitationCommand, already checked).
struct ExcitationRequest {
  std::string kind;
  double amplitude = 0.0;
  double f_min = 0.0, f_max = 0.0;
};

class PlantSource {
 public:
  virtual ~PlantSource() = default;
  virtual Experiment next_record() = 0;
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

// Reads and checks the target now (file missing, bad scenario, ...): Error naming it.
std::unique_ptr<PlantSource> make_plant_source(bus::SourceKind kind, const std::string& target);

}  // namespace ambid::daemons
