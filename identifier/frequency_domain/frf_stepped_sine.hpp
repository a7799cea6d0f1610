#pragma once
// FRF from a stepped-sine experiment: one sine per step, a settling time, then a measurement
// window holding a whole number of cycles, so that one DFT line of the window is exactly the
// step's frequency (no leakage, no window). Per step the phasors of r, u and y give
// T_yr = Y / R and T_ur = U / R, and the plant the indirect estimate G = T_yr / T_ur; the
// open-loop formula Y / U (biased under feedback with noise) is kept for comparison.
//
// One step excites one direction, so this estimator needs exactly one reference and one plant
// input (several inputs need as many independent directions at each frequency).
// No variance: a single window per frequency has no spread to estimate it from.
#include <vector>

#include <Eigen/Core>

#include "identifier/frf_types.hpp"

namespace ambid::ident {

struct SteppedSineStep {
  Eigen::Index measure_start = 0;    // first sample of the measurement window
  Eigen::Index measure_samples = 0;  // M, the window length
  Eigen::Index cycles = 0;           // whole cycles of the sine in the window: f = cycles / (M T)
};

struct SteppedSineFrfOptions {
  double sample_time = 0.0;
  std::vector<SteppedSineStep> steps;
  double f_min = 0.0, f_max = 0.0;  // keep steps with f_min <= f <= f_max (0: no upper limit)
};

struct SteppedSineFrf {
  Frf plant;                  // G = T_yr / T_ur (indirect)
  Frf plant_direct;           // Y / U
  Frf output_from_reference;  // T_yr
  Frf input_from_reference;   // T_ur
};

// r, u, y: samples x signals, deviations. Throws Error for inconsistent sizes, a window outside
// the record, cycles outside (0, M/2), two steps at one frequency or a non-positive sample time;
// InsufficientData for other than one reference and one plant input, no step in the band, or a
// step whose reference or T_ur phasor vanishes (names the step).
SteppedSineFrf estimate_stepped_sine_frf(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                                         const SteppedSineFrfOptions& options);

}  // namespace ambid::ident
