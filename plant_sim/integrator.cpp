#include "plant_sim/integrator.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

void require_state_size(const Eigen::VectorXd& v, Eigen::Index n, const char* what) {
  if (v.size() != n) {
    std::ostringstream msg;
    msg << "integrate_sample: " << what << " must have " << n << " entries, got " << v.size();
    throw Error(msg.str());
  }
}

void check_arguments(const Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, Eigen::Index states,
                     Eigen::Index inputs, Eigen::Index disturbances, double sample_time, int substeps) {
  if (!(sample_time > 0.0) || !std::isfinite(sample_time)) {
    std::ostringstream msg;
    msg << "integrate_sample: sample time must be positive and finite, got " << sample_time;
    throw Error(msg.str());
  }
  if (substeps < 1) throw Error("integrate_sample: substeps must be at least 1, got " + std::to_string(substeps));
  require_state_size(x, states, "state");
  require_state_size(u, inputs, "input");
  require_state_size(w, disturbances, "disturbance");
}

}  // namespace

Rk4Integrator::Rk4Integrator(const Plant& plant)
    : plant_(plant),
      inputs_(static_cast<Eigen::Index>(plant.input_names().size())),
      disturbances_(static_cast<Eigen::Index>(plant.disturbance_names().size())) {
  const auto n = static_cast<Eigen::Index>(plant.state_names().size());
  k1_.resize(n);
  k2_.resize(n);
  k3_.resize(n);
  k4_.resize(n);
  xt_.resize(n);
}

void Rk4Integrator::integrate_sample(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                     double sample_time, int substeps) {
  check_arguments(x, u, w, xt_.size(), inputs_, disturbances_, sample_time, substeps);

  const double h = sample_time / substeps;
  auto eval = [&](Eigen::VectorXd& k, const Eigen::VectorXd& at) {
    k = plant_.derivative(at, u, w);  // move-assigned: no copy
    require_state_size(k, xt_.size(), "plant derivative");
  };
  for (int s = 0; s < substeps; ++s) {
    eval(k1_, x);
    xt_ = x + (0.5 * h) * k1_;
    eval(k2_, xt_);
    xt_ = x + (0.5 * h) * k2_;
    eval(k3_, xt_);
    xt_ = x + h * k3_;
    eval(k4_, xt_);
    x += (h / 6.0) * (k1_ + 2.0 * (k2_ + k3_) + k4_);
  }
}

void Plant::advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
                    int substeps) const {
  Rk4Integrator(*this).integrate_sample(x, u, w, sample_time, substeps);
}

Eigen::VectorXd integrate_sample(const Plant& plant, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& w, double sample_time, int substeps) {
  check_arguments(x, u, w, std::ssize(plant.state_names()), std::ssize(plant.input_names()),
                  std::ssize(plant.disturbance_names()), sample_time, substeps);
  Eigen::VectorXd out = x;
  plant.advance(out, u, w, sample_time, substeps);
  return out;
}

}  // namespace ambid::sim
