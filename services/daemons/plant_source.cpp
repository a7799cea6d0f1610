#include "services/daemons/plant_source.hpp"

#include <utility>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "services/daemons/rig_source.hpp"
#include "services/daemons/scenario_json.hpp"

namespace ambid::daemons {
namespace {

class SimSource : public PlantSource {
 public:
  // The first record is simulated here, so a scenario whose loop diverges (the rotor touches
  // down) is refused before the swap instead of failing after it was announced.
  explicit SimSource(const std::string& file)
      : PlantSource(bus::SourceKind::sim, file), options_(read_scenario_file(file)), first_(simulate()) {}

  std::optional<SourceRows> next_rows(std::chrono::milliseconds) override {
    if (first_) return SourceRows{*std::exchange(first_, std::nullopt), true};
    return SourceRows{simulate(), true};
  }

  void excite(const ExcitationRequest& r) override {
    sim::ScenarioOptions o = options_;
    o.excitation = r.kind;
    o.amplitude = r.amplitude;
    if (r.f_max > 0) {
      o.f_min = r.f_min;
      o.f_max = r.f_max;
    }
    sim::build_scenario(o);  // refuses what the simulation cannot run
    options_ = o;
  }

 private:
  Experiment simulate() {
    sim::ScenarioOptions o = options_;
    o.seed = options_.seed + records_++;
    return sim::simulate_scenario(o);
  }

  sim::ScenarioOptions options_;
  std::uint64_t records_ = 0;
  std::optional<Experiment> first_;
};

class ReplaySource : public PlantSource {
 public:
  explicit ReplaySource(const std::string& file)
      : PlantSource(bus::SourceKind::replay, file), record_(read_experiment(file).experiment) {}
  std::optional<SourceRows> next_rows(std::chrono::milliseconds) override { return SourceRows{record_, true}; }
  void excite(const ExcitationRequest&) override { throw Error("a replayed experiment cannot be excited"); }

 private:
  Experiment record_;
};

}  // namespace

std::unique_ptr<PlantSource> make_plant_source(bus::SourceKind kind, const std::string& target,
                                               const SourceContext& context) {
  switch (kind) {
    case bus::SourceKind::sim:
      return std::make_unique<SimSource>(target);
    case bus::SourceKind::replay:
      return std::make_unique<ReplaySource>(target);
    case bus::SourceKind::rig:
      return make_rig_source(target, context);
  }
  // A foreign peer's enum value out of range was taken for a rig address (a 3 s HELLO wait).
  throw Error("unknown source kind " + std::to_string(static_cast<int>(kind)));
}

}  // namespace ambid::daemons
