#include "core/controller_replay.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace ambid {
namespace {

// Index of `name` in `names`, or -1.
Eigen::Index find(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : Eigen::Index(it - names.begin());
}

}  // namespace

ControllerReplay replay_controller(const Experiment& e) {
  if (!e.controller) throw Error("experiment '" + e.name + "' has no controller to replay");
  const StateSpaceController& k = *e.controller;
  const Eigen::Index n = e.samples();
  const Eigen::MatrixXd y = e.y_deviation(), u = e.u_deviation();
  const Eigen::MatrixXd r = e.has_excitation() ? e.r_deviation() : Eigen::MatrixXd();
  // v[k] stacks columns of y, u or r: (group, column) per controller input.
  std::vector<std::pair<const Eigen::MatrixXd*, Eigen::Index>> inputs;
  for (const auto& name : k.inputs) {
    if (const Eigen::Index j = find(e.y_names, name); j >= 0)
      inputs.emplace_back(&y, j);
    else if (const Eigen::Index j2 = find(e.u_names, name); j2 >= 0)
      inputs.emplace_back(&u, j2);
    else if (const Eigen::Index j3 = find(e.r_names, name); j3 >= 0)
      inputs.emplace_back(&r, j3);
    else
      throw Error("controller.inputs names '" + name + "', which experiment '" + e.name + "' does not record");
  }
  std::vector<Eigen::Index> column_of_output;  // u column of each controller output
  for (const auto& name : k.outputs) column_of_output.push_back(find(e.u_names, name));

  ControllerReplay out;
  out.output = Eigen::MatrixXd::Zero(n, Eigen::Index(e.u_names.size()));
  out.clamped.assign(std::size_t(n), false);
  out.states.resize(n, k.states());
  Eigen::VectorXd xc = k.initial_state.size() ? k.initial_state : Eigen::VectorXd::Zero(k.states());
  Eigen::VectorXd v(Eigen::Index(inputs.size())), next(k.states());
  for (Eigen::Index s = 0; s < n; ++s) {
    out.states.row(s) = xc.transpose();
    for (std::size_t i = 0; i < inputs.size(); ++i) v(Eigen::Index(i)) = (*inputs[i].first)(s, inputs[i].second);
    const Eigen::VectorXd uf = k.C * xc + k.D * v;
    bool clamped = false;
    for (std::size_t o = 0; o < column_of_output.size(); ++o) {
      const Eigen::Index j = column_of_output[o];
      out.output(s, j) = uf(Eigen::Index(o));
      if (!k.output_limits.empty() && k.output_limits[o].acts_on(e.u(s, j))) clamped = true;
    }
    next = k.A * xc + k.B * v;
    for (std::size_t i = 0; i < k.state_limits.size(); ++i) {
      const Limit& l = k.state_limits[i];
      const double x = next(Eigen::Index(i));
      if (x < l.lo || x > l.hi) {
        next(Eigen::Index(i)) = std::clamp(x, l.lo, l.hi);
        clamped = true;
      }
    }
    xc = next;
    out.clamped[std::size_t(s)] = clamped;
    if (clamped) ++out.clamped_samples;
  }
  return out;
}

ControllerReplay clamped_samples(const Experiment& e) {
  if (!e.controller || (e.controller->output_limits.empty() && e.controller->state_limits.empty())) {
    ControllerReplay none;
    none.clamped.assign(std::size_t(e.samples()), false);
    return none;
  }
  return replay_controller(e);
}

}  // namespace ambid
