#pragma once
// A linear time-invariant plant as a Plant: x' = A x + B u + E w, y = C x, with the
// equilibrium at zero state and zero input (so absolute values are deviations).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/state_space.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

// A continuous system with the names of its variables (used by the test plants).
struct NamedSystem {
  std::string model;
  ContinuousSystem system;
  std::vector<std::string> state_names, input_names, output_names;
};

class LinearPlant : public Plant {
 public:
  // Disturbances enter like the inputs (E = B, names "w_<input name>").
  explicit LinearPlant(NamedSystem named);
  // Disturbances enter through E (states x disturbances), one name per column.
  LinearPlant(NamedSystem named, Eigen::MatrixXd disturbance_matrix, std::vector<std::string> disturbance_names);
  // Both throw Error on inconsistent sizes or name counts, duplicate names, a non-finite
  // entry, or D != 0 (a Plant's output depends on the state only).

  const ContinuousSystem& system() const { return named_.system; }
  const Eigen::MatrixXd& disturbance_matrix() const { return E_; }

  std::string model() const override { return named_.model; }
  std::vector<std::string> state_names() const override { return named_.state_names; }
  std::vector<std::string> input_names() const override { return named_.input_names; }
  std::vector<std::string> output_names() const override { return named_.output_names; }
  std::vector<std::string> disturbance_names() const override { return disturbance_names_; }

  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override;
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override;
  void output_into(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override;
  Eigen::VectorXd equilibrium_state() const override;
  Eigen::VectorXd equilibrium_input() const override;

 private:
  NamedSystem named_;
  Eigen::MatrixXd E_;
  std::vector<std::string> disturbance_names_;
};

}  // namespace ambid::sim
