#include "plant_sim/linear_plant.hpp"

#include <set>
#include <sstream>
#include <utility>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

void require_names(const std::vector<std::string>& names, Eigen::Index count, const char* what) {
  if (static_cast<Eigen::Index>(names.size()) != count) {
    std::ostringstream msg;
    msg << "linear plant: " << count << " " << what << " need as many names, got " << names.size();
    throw Error(msg.str());
  }
  std::set<std::string> seen;
  for (const auto& n : names) {
    if (n.empty()) throw Error(std::string("linear plant: empty name among the ") + what);
    if (!seen.insert(n).second) throw Error(std::string("linear plant: duplicate name '") + n + "' among the " + what);
  }
}

void require_plant_size(const Eigen::VectorXd& v, Eigen::Index n, const char* what) {
  if (v.size() != n) {
    std::ostringstream msg;
    msg << "linear plant: " << what << " must have " << n << " entries, got " << v.size();
    throw Error(msg.str());
  }
}

std::vector<std::string> default_disturbance_names(const std::vector<std::string>& inputs) {
  std::vector<std::string> out;
  out.reserve(inputs.size());
  for (const auto& n : inputs) out.push_back("w_" + n);
  return out;
}

}  // namespace

LinearPlant::LinearPlant(NamedSystem named)
    : LinearPlant(named, named.system.B, default_disturbance_names(named.input_names)) {}

LinearPlant::LinearPlant(NamedSystem named, Eigen::MatrixXd disturbance_matrix,
                         std::vector<std::string> disturbance_names)
    : named_(std::move(named)), E_(std::move(disturbance_matrix)), disturbance_names_(std::move(disturbance_names)) {
  const ContinuousSystem& s = named_.system;
  s.validate();
  if (!s.D.isZero(0.0))
    throw Error("linear plant '" + named_.model + "': D must be zero (a plant's output depends on its state only)");
  require_names(named_.state_names, s.states(), "states");
  require_names(named_.input_names, s.inputs(), "inputs");
  require_names(named_.output_names, s.outputs(), "outputs");
  if (E_.rows() != s.states()) {
    std::ostringstream msg;
    msg << "linear plant: disturbance matrix must have " << s.states() << " rows (states), got " << E_.rows();
    throw Error(msg.str());
  }
  require_names(disturbance_names_, E_.cols(), "disturbances");
  if (!E_.allFinite()) throw Error("linear plant: disturbance matrix has a non-finite entry");
}

Eigen::VectorXd LinearPlant::derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                        const Eigen::VectorXd& w) const {
  const ContinuousSystem& s = named_.system;
  require_plant_size(x, s.states(), "state");
  require_plant_size(u, s.inputs(), "input");
  require_plant_size(w, E_.cols(), "disturbance");
  return s.A * x + s.B * u + E_ * w;
}

Eigen::VectorXd LinearPlant::output(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y;
  output_into(x, y);
  return y;
}

void LinearPlant::output_into(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  require_plant_size(x, named_.system.states(), "state");
  y.noalias() = named_.system.C * x;
}

Eigen::VectorXd LinearPlant::equilibrium_state() const { return Eigen::VectorXd::Zero(named_.system.states()); }

Eigen::VectorXd LinearPlant::equilibrium_input() const { return Eigen::VectorXd::Zero(named_.system.inputs()); }

}  // namespace ambid::sim
