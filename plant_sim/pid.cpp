#include "plant_sim/pid.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::sim {
namespace {

using Names = std::vector<std::string>;

// One loop as a discrete system from its error e = -y to its output c.
struct LoopSystem {
  Eigen::MatrixXd A, B, C, D;  // B is states x 1, C is 1 x states, D is 1 x 1
};

Eigen::Index index_in(const Names& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<Eigen::Index>(it - names.begin());
}

[[noreturn]] void fail_pid(const std::string& where, const std::string& what, double value) {
  std::ostringstream msg;
  msg << where << ": " << what << ", got " << value;
  throw Error(msg.str());
}

void require_sample_time(double T, const char* where) {
  if (!(T > 0.0) || !std::isfinite(T)) fail_pid(where, "sample time must be positive and finite", T);
}

void require_finite(double v, const std::string& where, const char* name) {
  if (!std::isfinite(v)) fail_pid(where, std::string(name) + " must be finite", v);
}

LoopSystem pid_loop(const PidLoop& loop, double T, const std::string& where) {
  require_finite(loop.kp, where, "kp");
  require_finite(loop.ki, where, "ki");
  require_finite(loop.kd, where, "kd");
  const bool integral = loop.ki != 0.0, derivative = loop.kd != 0.0;
  if (derivative && !(loop.derivative_time_constant > 0.0 && std::isfinite(loop.derivative_time_constant)))
    fail_pid(where, "derivative_time_constant must be positive when kd != 0", loop.derivative_time_constant);
  const Eigen::Index n = (integral ? 1 : 0) + (derivative ? 1 : 0);
  LoopSystem s{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, 1), Eigen::MatrixXd::Zero(1, n),
               Eigen::MatrixXd::Constant(1, 1, loop.kp)};
  Eigen::Index k = 0;
  if (integral) {  // I[k+1] = I[k] + T e[k]; term ki I[k]
    s.A(k, k) = 1.0;
    s.B(k, 0) = T;
    s.C(0, k) = loop.ki;
    ++k;
  }
  if (derivative) {
    // d[k] = a d[k-1] + b (e[k] - e[k-1]) realised with w[k] = d[k] - b e[k]:
    // w[k+1] = a w[k] + b (a - 1) e[k],  d[k] = w[k] + b e[k].
    const double tau = loop.derivative_time_constant;
    const double a = tau / (tau + T), b = loop.kd / (tau + T);
    s.A(k, k) = a;
    s.B(k, 0) = b * (a - 1.0);
    s.C(0, k) = 1.0;
    s.D(0, 0) += b;
  }
  return s;
}

LoopSystem lead_lag_loop(const LeadLagLoop& loop, double T, const std::string& where) {
  require_finite(loop.gain, where, "gain");
  // Continuous cascade of (lead s + 1)/(lag s + 1) = lead/lag + (1 - lead/lag)/(lag s + 1).
  Eigen::MatrixXd A(0, 0), B(0, 1), C(1, 0), D = Eigen::MatrixXd::Constant(1, 1, loop.gain);
  for (const LeadLagSection& sec : loop.sections) {
    if (!(sec.lag_time_constant > 0.0 && std::isfinite(sec.lag_time_constant)))
      fail_pid(where, "lag_time_constant must be positive", sec.lag_time_constant);
    if (!(sec.lead_time_constant >= 0.0 && std::isfinite(sec.lead_time_constant)))
      fail_pid(where, "lead_time_constant must be non-negative", sec.lead_time_constant);
    const double a = -1.0 / sec.lag_time_constant, b = 1.0 / sec.lag_time_constant;
    const double c = 1.0 - sec.lead_time_constant / sec.lag_time_constant;
    const double d = sec.lead_time_constant / sec.lag_time_constant;
    // Series: previous (A, B, C, D) then this section.
    const Eigen::Index n = A.rows();
    Eigen::MatrixXd An = Eigen::MatrixXd::Zero(n + 1, n + 1), Bn(n + 1, 1), Cn(1, n + 1);
    An.topLeftCorner(n, n) = A;
    An.bottomLeftCorner(1, n) = b * C;
    An(n, n) = a;
    Bn << B, b * D;
    Cn << d * C, c;
    A = An;
    B = Bn;
    C = Cn;
    D = (d * D).eval();
  }
  // Tustin: Ad = M (I + A T/2), Bd = M B T, Cd = C M, Dd = D + C M B T/2, M = (I - A T/2)^-1.
  const Eigen::Index n = A.rows();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd M = linalg::inverse(I - A * (T / 2));
  LoopSystem s{M * (I + A * (T / 2)), M * B * T, C * M, D + C * M * B * (T / 2)};
  require_finite(loop.ki, where, "ki");
  if (loop.ki == 0.0) return s;
  // Integral in parallel: I[k+1] = I[k] + T e[k]; term ki I[k].
  LoopSystem with{Eigen::MatrixXd::Zero(n + 1, n + 1), Eigen::MatrixXd::Zero(n + 1, 1), Eigen::MatrixXd::Zero(1, n + 1),
                  s.D};
  with.A.topLeftCorner(n, n) = s.A;
  with.A(n, n) = 1.0;
  with.B.topRows(n) = s.B;
  with.B(n, 0) = T;
  with.C.leftCols(n) = s.C;
  with.C(0, n) = loop.ki;
  return with;
}

template <class Loop, class Discretise>
StateSpaceController assemble(const std::vector<Loop>& loops, double T, const Names& plant_inputs, const char* kind,
                              Discretise discretise) {
  require_sample_time(T, kind);
  if (plant_inputs.empty()) throw Error(std::string(kind) + ": no plant inputs named");
  if (loops.empty()) throw Error(std::string(kind) + ": no loops given");
  StateSpaceController c;
  c.sample_time = T;
  c.outputs = plant_inputs;
  std::vector<LoopSystem> systems;
  Eigen::Index states = 0;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const std::string where = std::string(kind) + " loop " + std::to_string(i) + " ('" + loops[i].measured + "')";
    if (loops[i].measured.empty()) throw Error(where + ": measured signal name is empty");
    if (index_in(plant_inputs, loops[i].measured) >= 0) throw Error(where + ": measured signal is a plant input");
    if (loops[i].drives.empty()) throw Error(where + ": drives no plant input");
    for (const LoopDrive& drive : loops[i].drives) {
      if (index_in(plant_inputs, drive.input) < 0)
        throw Error(where + ": drives '" + drive.input + "', which is not a plant input");
      require_finite(drive.gain, where, "drive gain");
    }
    if (index_in(c.inputs, loops[i].measured) < 0) c.inputs.push_back(loops[i].measured);
    systems.push_back(discretise(loops[i], T, where));
    states += systems.back().A.rows();
  }
  const auto m = static_cast<Eigen::Index>(plant_inputs.size());
  const auto p = static_cast<Eigen::Index>(c.inputs.size());
  c.A = Eigen::MatrixXd::Zero(states, states);
  c.B = Eigen::MatrixXd::Zero(states, p);
  c.C = Eigen::MatrixXd::Zero(m, states);
  c.D = Eigen::MatrixXd::Zero(m, p);
  Eigen::Index offset = 0;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const LoopSystem& s = systems[i];
    const Eigen::Index n = s.A.rows(), col = index_in(c.inputs, loops[i].measured);
    c.A.block(offset, offset, n, n) = s.A;
    c.B.block(offset, col, n, 1) = -s.B;  // e = -y
    for (const LoopDrive& drive : loops[i].drives) {
      const Eigen::Index row = index_in(plant_inputs, drive.input);
      c.C.block(row, offset, 1, n) += drive.gain * s.C;
      c.D(row, col) -= drive.gain * s.D(0, 0);
    }
    offset += n;
  }
  return c;
}

}  // namespace

StateSpaceController pid_controller(const std::vector<PidLoop>& loops, double sample_time, const Names& plant_inputs) {
  return assemble(loops, sample_time, plant_inputs, "PID controller", pid_loop);
}

StateSpaceController lead_lag_controller(const std::vector<LeadLagLoop>& loops, double sample_time,
                                         const Names& plant_inputs) {
  return assemble(loops, sample_time, plant_inputs, "lead-lag controller", lead_lag_loop);
}

}  // namespace ambid::sim
