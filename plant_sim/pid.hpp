#pragma once
// Decentralised discrete controllers in the contract's StateSpaceController form: a list of
// single-measurement loops, each driving one or more plant inputs with its own gain (a sign
// for a differential drive: x -> u1 with +1, u2 with -1).
//
// Every loop acts on the control error e[k] = -y[k] (y the deviation of its measured signal;
// the set-point is the operating point), and its output c[k] is added to uf of each driven
// input times that drive's gain.
#include <string>
#include <vector>

#include "core/experiment.hpp"

namespace ambid::sim {

struct LoopDrive {
  std::string input;  // plant input name
  double gain = 1.0;  // usually +1 or -1
};

// PID with filtered derivative, C(s) = kp + ki/s + kd s / (tau s + 1), discretised as
//   integral:   I[k+1] = I[k] + T e[k]                 (forward Euler; term ki I[k])
//   derivative: d[k] = a d[k-1] + b (e[k] - e[k-1]),   a = tau/(tau+T), b = kd/(tau+T)
//               (backward Euler)
//   c[k] = kp e[k] + ki I[k] + d[k].
// A loop with ki = 0 has no integrator state, one with kd = 0 no derivative state.
struct PidLoop {
  std::string measured;
  std::vector<LoopDrive> drives;
  double kp = 0.0, ki = 0.0, kd = 0.0;
  double derivative_time_constant = 0.0;  // tau, > 0 when kd != 0
};

// C(s) = gain * prod_i (lead_i s + 1) / (lag_i s + 1) + ki / s: the cascade discretised by
// Tustin (bilinear), the integral as the PID's (forward Euler, term ki I[k]; no state when
// ki = 0).
struct LeadLagSection {
  double lead_time_constant = 0.0;  // >= 0
  double lag_time_constant = 0.0;   // > 0
};
struct LeadLagLoop {
  std::string measured;
  std::vector<LoopDrive> drives;
  double gain = 0.0;
  std::vector<LeadLagSection> sections;
  double ki = 0.0;
};

// Controller inputs: the measured signals in order of first appearance; outputs:
// plant_inputs (all of them; inputs no loop drives get zero rows). Throws Error for a drive
// naming an unknown input, a non-positive sample time or time constant, or a non-finite gain.
StateSpaceController pid_controller(const std::vector<PidLoop>& loops, double sample_time,
                                    const std::vector<std::string>& plant_inputs);
StateSpaceController lead_lag_controller(const std::vector<LeadLagLoop>& loops, double sample_time,
                                         const std::vector<std::string>& plant_inputs);

}  // namespace ambid::sim
