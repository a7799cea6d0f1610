#pragma once
// A continuous-time plant as the closed-loop runner sees it: absolute states, inputs and
// outputs, a right-hand side, and its nominal operating point. Models with their own
// parameters (amb1dof_voltage, the linear test plants) implement this.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ambid::sim {

class Plant {
 public:
  virtual ~Plant() = default;

  virtual std::string model() const = 0;
  virtual std::vector<std::string> state_names() const = 0;
  virtual std::vector<std::string> input_names() const = 0;
  virtual std::vector<std::string> output_names() const = 0;

  // x' = f(x, u, w): `w` is the process disturbance (one entry per disturbance_names()),
  // held constant over a sample like u.
  virtual Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                     const Eigen::VectorXd& w) const = 0;
  // y = h(x), the noise-free measurement.
  virtual Eigen::VectorXd output(const Eigen::VectorXd& x) const = 0;
  // The same into y (resized if needed). A model on the simulator's hot path overrides it to
  // write into y without allocating.
  virtual void output_into(const Eigen::VectorXd& x, Eigen::VectorXd& y) const { y = output(x); }
  virtual std::vector<std::string> disturbance_names() const = 0;

  // Advances x by one sample with u and w held (zero-order hold) by `substeps` classical RK4
  // steps. The default (integrator.cpp) works for any model; a model on the simulator's hot
  // path overrides it with an allocation-free version of the same scheme.
  virtual void advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
                       int substeps) const;

  // The equilibrium (state and input) the model is linearised and operated at.
  virtual Eigen::VectorXd equilibrium_state() const = 0;
  virtual Eigen::VectorXd equilibrium_input() const = 0;
};

}  // namespace ambid::sim
