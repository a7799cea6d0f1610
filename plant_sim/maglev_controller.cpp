#include "plant_sim/maglev_controller.hpp"

#include <cmath>

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

}  // namespace ambid::sim
