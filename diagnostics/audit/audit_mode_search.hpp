#pragma once
// Where to start the fit of a flexible mode: the mode may sit anywhere up to the Nyquist
// frequency, and a weak one (participation 0.1-0.3 at several hundred Hz under 0.1 um / 1 mA
// noise fed around the loop) raises no peak above the noise in the residual spectrum and
// lowers the estimation cost by a few 0.1 %, less than a broad resonance at a wrong frequency
// gains by fitting noise. So the frequency comes from a matched filter over a fine grid: the
// sensor sees q with q'' + 2 zeta w q' + w^2 q = coupling x'', so the nominal replay's x''
// through that resonance (Tustin, prewarped at w) is the shape the mode adds to the position
// residual (the loop's reaction to q left out: a start, not a fit). The frequency whose shape
// explains most of the residual, on a 0.25 % log grid from 100 Hz to 0.95 of the Nyquist
// frequency at two dampings, then a replay of the closed loop on a 0.5 % grid +-8 % around it
// (and at the residual's spectral peaks), both signs of the coupling, gives the start.
#include <vector>

#include "diagnostics/audit/audit_fit.hpp"

namespace ambid::diag {

struct ModeStart {
  sim::Effect effect;  // flexible_mode at the best replayed point
  double cost = 0.0;   // its estimation cost (estimation_cost), +inf when no point replays
};

// `nominal_y`: the nominal replay's outputs (deviations, at least estimation.end rows);
// `peaks`: frequencies the residual spectrum suggests (Hz), replayed as well.
ModeStart search_mode_start(const Experiment& measured, const Eigen::MatrixXd& measured_y,
                            const Eigen::MatrixXd& nominal_y, const Segment& estimation,
                            const std::vector<double>& peaks);

// The matched-filter frequency alone (Hz), for tests: the grid frequency whose resonance
// shape explains most of the position residual over `estimation`.
double matched_mode_frequency(const Eigen::VectorXd& residual_x, const Eigen::VectorXd& nominal_x, double sample_time,
                              const Segment& estimation);

}  // namespace ambid::diag
