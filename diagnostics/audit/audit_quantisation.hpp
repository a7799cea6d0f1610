#pragma once
// The step of a DAC read from the record (the actuator_quantisation candidate's start): the
// coil current follows the voltage the DAC puts out, so with the right step s the logged
// command rounded to multiples of s explains the next current sample,
//   i[k+1] = a i[k] + b round_s(u[k]) + c,
// far better than with a step that rounds many commands to other levels. Every step of a
// logarithmic grid is scored by the residual of that regression (least squares by QR: the
// columns i[k], 1 orthonormalised once, then the rounded command against them), refined on a
// finer grid about the best, then moved to the middle of the steps that round every command
// alike (the residual is flat there). The cost of a step is rugged (a step 0.5 % off rounds a tenth of
// the commands differently), so a fit from the catalogue's typical step does not find it.
#include <Eigen/Core>

namespace ambid::diag {

struct DacScreen {
  double step = 0.0;       // V: the step of least residual
  double residual = 0.0;   // its residual sum of squares (A^2)
  double unrounded = 0.0;  // the residual sum of squares with the command as logged (no DAC)
};

// `command` and `current` per sample (absolute, as logged), at least 10 samples; steps from
// `smallest` to `largest` (0 < smallest < largest). Error for bad input.
DacScreen screen_dac_step(const Eigen::VectorXd& command, const Eigen::VectorXd& current, double smallest,
                          double largest);

}  // namespace ambid::diag
