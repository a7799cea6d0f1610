#include "support/maglev_records.hpp"

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "plant_sim/maglev_controller.hpp"

namespace ambid::test_support {

sim::MaglevRunOptions maglev_run_options(double sample_time, Eigen::Index samples, std::uint64_t seed) {
  sim::MaglevRunOptions o;
  o.sample_time = sample_time;
  o.samples = samples;
  o.step_period = 1.5;
  o.noise_amplitude = 0.5;
  o.position_noise = 5e-6;
  o.current_noise = 1e-5;
  o.seed = seed;
  return o;
}

Experiment maglev_record(const sim::MaglevParameters& truth, const sim::MaglevRig& rig,
                         const sim::MaglevRunOptions& run) {
  sim::MaglevRun result = sim::run_maglev_rig(truth, sim::MaglevParameters::nominal(), rig, run);
  if (!result.ended.empty()) throw Error(result.ended);
  Experiment e = std::move(result.experiment);
  e.controller = sim::maglev_rig_controller(rig, e.sample_time);
  const ControllerReplay replay = replay_controller(e);
  e.r_names = {"r"};
  e.r = e.u_deviation() - replay.output;  // operating value of r: 0
  e.validate();
  return e;
}

}  // namespace ambid::test_support
