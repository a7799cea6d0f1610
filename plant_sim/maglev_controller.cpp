#include "plant_sim/maglev_controller.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/controller_replay.hpp"
#include "core/error.hpp"

namespace ambid::sim {

StateSpaceController maglev_rig_controller(const MaglevRig& rig, double sample_time) {
  rig.validate();
  if (!(sample_time > 0.0) || !std::isfinite(sample_time))
    throw Error("maglev rig controller: sample time must be positive, got " + std::to_string(sample_time));
  constexpr double mm_per_m = 1e3;
  const double q = rig.Kp * sample_time / rig.Ti, kd = rig.Kp * rig.Td / sample_time;
  StateSpaceController c;
  c.sample_time = sample_time;
  c.inputs = {"x"};
  c.outputs = {"u"};
  c.A = Eigen::Matrix2d{{1.0, 0.0}, {0.0, 0.0}};
  c.B = Eigen::Vector2d(q * mm_per_m, 1.0);
  c.C = Eigen::RowVector2d(1.0, -kd * mm_per_m);
  c.D = Eigen::MatrixXd::Constant(1, 1, (rig.Kp + q + kd) * mm_per_m);
  c.output_limits = {Limit{0.0, rig.v_ref}};
  return c;
}

void attach_rig_controller(Experiment& record, const MaglevRig& rig) {
  if (record.y_names != std::vector<std::string>{"x", "i"} || record.u_names != std::vector<std::string>{"u"} ||
      !record.operating_point.count("x"))
    throw Error("maglev rig controller: the record needs y = [x, i], u = [u] and operating_point.x");
  record.controller = maglev_rig_controller(rig, record.sample_time);
  record.r_names.clear();
  record.r.resize(record.samples(), 0);
  const ControllerReplay replay = replay_controller(record);
  record.r_names = {"r"};
  record.r = record.u_deviation() - replay.output;  // operating value of r: 0
  nlohmann::json& extra = record.extra.json();
  extra["rig"]["not_in_controller"] = {
      "the integral's clamp [integral_min, integral_max] and the PID's clamp [pid_min, pid_max]: a sample where "
      "one acted is not exogenous and the form cannot see it",
      "the reference levels: their proportional, derivative and integral parts of the command are in r",
      "the excitation w added to the command: in r"};
}

}  // namespace ambid::sim
