#pragma once
// The closed-loop signature of each fault of amb1dof_voltage: how the identified physical
// parameters (R1 R2 kw1 kw2 kr1 kr2 ks, read from v1..v9 with the nominal m and L) move per
// relative change of one physical parameter of the true plant.
//
// A fault moves more than its own parameter. In the loop the controller's integral action
// holds x at 0, but the bias currents settle where the fault puts them (R1 +20 %: i1 = i2 =
// 0.478 A instead of 0.5), and the linearised ks (~ i^2) and kr (~ i) of that operating point
// move with them; K and x0 also change the inductance L = Ls + K/(2 x0), which the
// identification reads R and kw through. So each signature comes from the model:
//   1. the nonlinear plant with the fault, in closed loop with the recorded controller,
//      noise-free and unexcited, run until it settles (settled_parameters);
//   2. linearised by central differences at the settled state and input, brought to the
//      measured coordinates (x, x', i1, i2 as the sensors see them), v1..v9 read off and
//      mapped to the physical parameters with the nominal m and L, as the identifier does;
//   3. the signature is the central difference of the relative change of each identified
//      parameter over +-step of the fault parameter.
// Fault parameters: R1, R2 (coil_resistance), kw1, kw2 (amplifier_gain), K1, K2 (force_factor:
// shorted turns lower the force constant of one coil), x0 (air_gap), m (rotor_mass) and the
// position sensor gain (sensor_gain: the controller and the identifier see g x).
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "diagnostics/monitored_parameter.hpp"

namespace ambid::diag {

// The monitored parameters of amb1dof_voltage (R1 R2 kw1 kw2 kr1 kr2 ks) with their roles, in
// the order an estimate window carries them (fault_isolation.hpp: why these).
std::span<const MonitoredParameter> amb1dof_monitored_parameters();

// One way the monitored parameters can move together: d log(identified p) per unit relative
// change of the fault parameter, for every monitored parameter.
struct FaultHypothesis {
  std::string fault;           // vocabulary name (fault_isolation.hpp)
  std::optional<int> channel;  // empty: both channels or none
  std::string subject;         // "coil 1 resistance"
  // The monitored parameters that stand for the fault (R1 for coil 1 resistance, ks for the
  // air gap): preferred when several faults explain the same change (fault_isolation.hpp).
  std::vector<std::string> own;
  std::map<std::string, double> signature;
};

struct SignatureOptions {
  double relative_step = 0.05;  // +- this relative change of each fault parameter
  double settle_time = 1.5;     // s of closed loop per evaluation
  // Settled means: x, i1, i2 and u moved less than this (relative to x0, i0, u0) over the
  // last tenth of settle_time. Error otherwise (the loop does not settle, or too slowly).
  double settle_tolerance = 1e-7;
  void validate() const;  // step in (0, 0.5), settle_time >= 10 samples, tolerance > 0
};

// The identified physical parameters (R1 R2 kw1 kw2 kr1 kr2 ks) of the closed loop of
// `header` (plant amb1dof_voltage with its nominal parameters, and its controller) whose true
// plant has `true_parameters` overriding the nominal ones and a position sensor of gain
// `sensor_gain`, settled and linearised as above. Throws Error when the header has no
// controller or another plant, for an unknown parameter name, or when the loop does not settle.
std::map<std::string, double> settled_parameters(const Experiment& header,
                                                 const std::map<std::string, double>& true_parameters,
                                                 double sensor_gain = 1.0, const SignatureOptions& options = {});

// Every fault of the vocabulary the monitored parameters can show, with its signature, for the
// loop of `header`: coil_resistance and amplifier_gain per channel and both alike (the sum of
// the two columns), force_factor per channel, air_gap, sensor_gain, rotor_mass.
std::vector<FaultHypothesis> closed_loop_fault_hypotheses(const Experiment& header,
                                                          const SignatureOptions& options = {});

// The same for the loop `ambid sim` runs (amb1dof_voltage nominal, lqr controller, 1e-4 s),
// computed once on first use (19 closed-loop runs of settle_time each: ~30 ms).
const std::vector<FaultHypothesis>& default_fault_hypotheses();

}  // namespace ambid::diag
