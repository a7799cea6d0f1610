#pragma once
// The lamstf family's scenario (families.hpp): seed 002's LAMSTF model (lamstf.hpp) in the
// closed loop of its sec. 4.4 simulation (Tables 4.1/4.2), run by the generic closed-loop
// runner:
//   - controller: LQR (Q = I, R = I) on the 10 ms model scaled by 1/0.85, so every closed-loop
//     pole lies in |z| < 0.85 (Lee's weights are not given; sec. 2.5 asks for a well-damped
//     band), fed by the steady-state Kalman predictor for the noise below; the contract form
//     reads [u; y] (inputs i1..i5, s1..s5) and drives i1..i5.
//   - excitation r on the five coil currents: gaussian (Lee's r ~ N(0, 1), std `amplitude`),
//     binary (+-amplitude) or none.
//   - "% noise" (undefined in the dissertation) per channel as rms(noise) / rms(signal) of the
//     noise-free loop under the same r: measurement noise std = level * rms(y_j) on output j,
//     process noise std = level * rms(u_j) at plant input j (x' = A x + B (u + w), w held over
//     the sample). A first noise-free run measures those rms values.
//   - `input_limit` > 0: controller.output_limits of +-input_limit A on every coil.
// The family has no parameters (the sidecar's plant.parameters is empty: the model is the
// fixed analytical matrices), no effect catalogue and no physical noise options; those are
// refused by name.
#include "plant_sim/scenario.hpp"

namespace ambid::sim {

Scenario build_lamstf_scenario(const ScenarioOptions& options);
Experiment simulate_lamstf(const ScenarioOptions& options, ClosedLoopStatistics* statistics);
// Seed 002 sec. 4.4: 10 ms, gaussian r of std 1 A, 0.5 % noise; 80 s (8000 samples, so the
// 75 % that `ambid identify` fits are Lee's 6000).
ScenarioOptions lamstf_default_options();

}  // namespace ambid::sim
