#pragma once
// The closed-loop runner: the true (nonlinear) plant integrated between samples, the recorded
// discrete controller of the experiment sidecar, zero-order hold, measurement and process
// noise, actuator limits. It produces an experiment that any reader can replay: the y columns
// are what the controller received, the u columns what it commanded (experiment-format.md).
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

struct ClosedLoopOptions {
  Eigen::Index samples = 0;
  int substeps = 0;  // integrator sub-steps per sample; 0 means kDefaultSubsteps
  // Excitation r added to the controller output, deviations, samples x controller outputs, in
  // the order of the controller's `outputs`. Empty: no excitation is recorded.
  Eigen::MatrixXd excitation;
  Eigen::VectorXd measurement_noise_std;  // per plant output, absolute units; empty: none
  Eigen::VectorXd process_noise_std;      // per plant disturbance; empty: none
  // Absolute actuator limits; empty: none. The controller's output_limits clamp as well (the
  // tighter bound wins) and its state_limits clamp its state update.
  Eigen::VectorXd input_lower, input_upper;
  std::uint64_t seed = 0;
  // A rounded record to follow: its outputs as logged (absolute, samples x plant outputs) and
  // per output the resolution they were logged at (0: full precision). A controller input
  // from an output of resolution q > 0 reads the logged value while the plant's output lies
  // within q/2 of it (the logger would have printed that value), else the plant's output less
  // q/2 toward the logged value (a dead zone of half a step). A model that agrees with the
  // record thus reproduces the record's rounding, and an excitation reconstructed from the
  // rounded record (r = u - C y_logged) drives it without the controller's answer to the
  // rounding, which the plant never had. Both empty: the plant's output as it is.
  Eigen::MatrixXd followed;
  Eigen::VectorXd followed_resolution;
};

struct ClosedLoopStatistics {
  Eigen::Index saturated_samples = 0;  // samples where an input limit or a controller state clamp acted
};

// Runs `truth` in closed loop with `header.controller` and returns `header` with t, y, u, r
// filled. `header` supplies everything else: name, sample_time, the nominal plant description,
// operating point, and signal names (y = truth outputs, u = truth inputs, r = one excitation
// name per controller output, or empty). The plant starts at the nominal operating point
// (the operating_point values of its states where named, else the truth's equilibrium) and
// the controller at its initial_state (or zero).
// Throws Error on inconsistent names or dimensions, and when the plant leaves its valid
// region (e.g. the rotor touches the bearing), naming the time.
Experiment run_closed_loop(const Plant& truth, const Experiment& header, const ClosedLoopOptions& options,
                           ClosedLoopStatistics* statistics = nullptr);

}  // namespace ambid::sim
