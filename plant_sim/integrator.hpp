#pragma once
// Fixed-step classical Runge-Kutta (RK4) over one sample of a Plant, with the input u and the
// disturbance w held constant over the sample (zero-order hold).
#include <Eigen/Core>

#include "plant_sim/plant.hpp"

namespace ambid::sim {

// RK4 steps per sample the closed-loop runner uses by default. At 1e-4 s on amb1dof_voltage
// one step keeps the relative error below 1e-7 open loop up to half the air gap
// (tests/plant_sim/integrator_test.cpp) and in the default closed-loop scenario, where it is
// ~1e-7 of the sensor noise (tests/plant_sim/closed_loop_accuracy_test.cpp). Each further
// step costs as much again of the simulation time.
inline constexpr int kDefaultSubsteps = 1;

// The state one sample_time later, from x, with `substeps` equal RK4 steps.
// Error on non-positive sample_time or substeps, or wrongly sized x, u, w; errors of the
// plant (e.g. the rotor touching the bearing) propagate.
Eigen::VectorXd integrate_sample(const Plant& plant, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& w, double sample_time, int substeps = kDefaultSubsteps);

// The same with its work vectors allocated once, for loops over many samples: advances x in
// place. Only Plant::derivative's result vectors are allocated per evaluation. Keeps a
// reference to the plant, which must outlive it.
class Rk4Integrator {
 public:
  explicit Rk4Integrator(const Plant& plant);
  void integrate_sample(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
                        int substeps = kDefaultSubsteps);

 private:
  const Plant& plant_;
  Eigen::Index inputs_, disturbances_;
  Eigen::VectorXd k1_, k2_, k3_, k4_, xt_;
};

}  // namespace ambid::sim
