#include "plant_sim/linearize.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

// Step per variable: relative_step * max(|at_j|, scale_j), scale 1 when none is given.
Eigen::VectorXd steps(const Eigen::VectorXd& at, const Eigen::VectorXd& scale, double relative, const char* what) {
  if (scale.size() != 0 && scale.size() != at.size()) {
    std::ostringstream msg;
    msg << "linearize: " << what << " scale must have " << at.size() << " entries, got " << scale.size();
    throw Error(msg.str());
  }
  Eigen::VectorXd h(at.size());
  for (Eigen::Index j = 0; j < at.size(); ++j) {
    const double s = scale.size() == 0 ? 1.0 : scale[j];
    if (!std::isfinite(s) || !(s > 0.0)) {
      std::ostringstream msg;
      msg << "linearize: " << what << " scale " << j << " must be positive and finite, got " << s;
      throw Error(msg.str());
    }
    h[j] = relative * std::max(std::abs(at[j]), s);
  }
  return h;
}

}  // namespace

ContinuousSystem linearize(const Plant& plant, const LinearizeOptions& options) {
  if (!std::isfinite(options.relative_step) || !(options.relative_step > 0.0)) {
    std::ostringstream msg;
    msg << "linearize: relative step must be positive and finite, got " << options.relative_step;
    throw Error(msg.str());
  }
  const Eigen::VectorXd x0 = plant.equilibrium_state();
  const Eigen::VectorXd u0 = plant.equilibrium_input();
  const Eigen::VectorXd w0 = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(plant.disturbance_names().size()));
  const Eigen::VectorXd hx = steps(x0, options.state_scale, options.relative_step, "state");
  const Eigen::VectorXd hu = steps(u0, options.input_scale, options.relative_step, "input");
  const Eigen::Index n = x0.size(), m = u0.size();
  const Eigen::Index q = plant.output(x0).size();

  ContinuousSystem sys;
  sys.A.resize(n, n);
  sys.B.resize(n, m);
  sys.C.resize(q, n);
  sys.D = Eigen::MatrixXd::Zero(q, m);
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd xp = x0, xm = x0;
    xp[j] += hx[j];
    xm[j] -= hx[j];
    const double width = xp[j] - xm[j];  // the step actually taken in floating point
    sys.A.col(j) = (plant.derivative(xp, u0, w0) - plant.derivative(xm, u0, w0)) / width;
    sys.C.col(j) = (plant.output(xp) - plant.output(xm)) / width;
  }
  for (Eigen::Index j = 0; j < m; ++j) {
    Eigen::VectorXd up = u0, um = u0;
    up[j] += hu[j];
    um[j] -= hu[j];
    sys.B.col(j) = (plant.derivative(x0, up, w0) - plant.derivative(x0, um, w0)) / (up[j] - um[j]);
  }
  sys.validate();
  return sys;
}

}  // namespace ambid::sim
