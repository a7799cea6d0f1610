#pragma once
// The controller board of the single-coil maglev rig (../shared/notes/maglev-rig.md): its PID
// with clamps, the Hall-type position sensor, the DAC-type actuator and the logger's
// resolution. Settings by name so `ambid sim --rig NAME=VALUE` can reach each one.
#include <map>
#include <string>
#include <vector>

namespace ambid::sim {

struct MaglevRig {
  // PID in absolute form on e = y - r in mm, per sample (Ts the sample time):
  //   I_k = clamp(I_{k-1} + Kp Ts/Ti e_k, integral_min, integral_max)
  //   u_pid = clamp(Kp e_k + I_k + Kp Td/Ts (e_k - e_{k-1}), pid_min, pid_max)
  //   u = clamp(u_pid + w_k, 0, v_ref)          (w: the excitation noise, not logged)
  double Kp = 4.0;                                 // V/mm (3 lets the body reach the ground after the step to 16 mm)
  double Ti = 0.3;                                 // s
  double Td = 0.025;                               // s
  double integral_min = 0.0, integral_max = 12.0;  // V
  double pid_min = 0.0, pid_max = 12.0;            // V
  double v_ref = 12.0;                             // V: the DAC's full scale (output clamp [0, v_ref])
  // DAC: the coil gets the command rounded to multiples of dac_step (0: ideal).
  double dac_step = 0.0;  // V
  // Hall sensor: y = sensor_offset + sensor_gain * x_r (x/x_r)^sensor_exponent + sensor_coupling * i,
  // x_r = sensor_reference (the power-law calibration is exact there), read sensor_delay samples late.
  double sensor_gain = 1.0, sensor_offset = 0.0, sensor_exponent = 1.0;
  double sensor_reference = 0.0145;  // m
  double sensor_coupling = 0.0;      // m/A: the coil's own field read as distance
  double sensor_delay = 0.0;         // whole samples
  // Logger resolution of x, u, i (0: full precision): the rig prints 0.01 mm, 0.01 V, 0.01 mA.
  double log_x = 1e-5, log_u = 0.01, log_i = 1e-5;

  std::map<std::string, double> to_map() const;
  // Error listing the valid names for an unknown one; validate() after a batch of changes.
  void set(const std::string& name, double value);
  // Gains, times and resolutions finite and >= 0 (Kp, Ti > 0), clamps ordered, the delay a
  // whole number of samples; Error naming the bad setting.
  void validate() const;
  static const std::vector<std::string>& names();

  // The sensor's reading of gap x with coil current i (before delay).
  double sense(double x, double i) const;
  // The voltage the DAC puts out for command u (u already clamped to [0, v_ref]).
  double dac(double u) const;
};

// Rounds v to a multiple of `resolution` (unchanged when resolution is 0).
double round_to(double v, double resolution);

}  // namespace ambid::sim
