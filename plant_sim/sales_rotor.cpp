#include "plant_sim/sales_rotor.hpp"

namespace ambid::sim {

NamedSystem sales_rotor() {
  NamedSystem out;
  out.model = "sales_rotor";
  ContinuousSystem& s = out.system;
  s.A = (Eigen::MatrixXd(2, 2) << 0.0, 1.0, 2.8e3, 0.0).finished();
  s.B = (Eigen::MatrixXd(2, 1) << 0.0, 4.2).finished();
  s.C = (Eigen::MatrixXd(1, 2) << 0.2e3, 0.0).finished();
  s.D = Eigen::MatrixXd::Zero(1, 1);
  out.state_names = {"x", "x_dot"};
  out.input_names = {"u"};
  out.output_names = {"y"};
  return out;
}

}  // namespace ambid::sim
