#include "support/maglev_records.hpp"

#include "core/error.hpp"

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
  result.experiment.validate();  // with the PID and r of attach_rig_controller
  return std::move(result.experiment);
}

}  // namespace ambid::test_support
