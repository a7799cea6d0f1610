#include "identifier/amb1dof_structure.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {

const std::vector<std::string>& amb1dof_structure_names() {
  static const std::vector<std::string> names = {"v1", "v2", "v3", "v4", "v5", "v6", "v7", "v8", "v9"};
  return names;
}

const std::vector<std::string>& amb1dof_physical_names() {
  static const std::vector<std::string> names = {"ks", "kr1", "kr2", "kr1_emf", "R1", "kr2_emf", "R2", "kw1", "kw2"};
  return names;
}

Eigen::Matrix<double, 9, 1> amb1dof_structure_vector(const ContinuousSystem& c) {
  Eigen::Matrix<double, 9, 1> v;
  v << c.A(1, 0), c.A(1, 2), -c.A(1, 3), -c.A(2, 1), -c.A(2, 2), c.A(3, 1), -c.A(3, 3), c.B(2, 0), c.B(3, 1);
  return v;
}

double amb1dof_structure_deviation(const ContinuousSystem& c) {
  return std::max({std::abs(c.A(0, 0)), std::abs(c.A(0, 1) - 1.0), std::abs(c.A(0, 2)), std::abs(c.A(0, 3)),
                   std::abs(c.A(1, 1)), std::abs(c.A(2, 0)), std::abs(c.A(2, 3)), std::abs(c.A(3, 0)),
                   std::abs(c.A(3, 2)), c.B.topRows(2).cwiseAbs().maxCoeff(), std::abs(c.B(2, 1)),
                   std::abs(c.B(3, 0))}) /
         std::abs(c.A(1, 0));
}

Eigen::Matrix<double, 9, 1> amb1dof_physical_scale(double L1, double L2, double m) {
  Eigen::Matrix<double, 9, 1> scale;
  scale << m, m, m, L1, L1, L2, L2, L1, L2;
  return scale;
}

namespace {

double nominal_parameter(const Experiment& e, const std::string& name, const std::string& who) {
  const auto it = e.plant.parameters.find(name);
  if (it == e.plant.parameters.end()) throw Error(who + ": plant.parameters." + name + " is missing");
  return it->second;
}

}  // namespace

Amb1dofNominal amb1dof_nominal(const Experiment& e, const std::string& who) {
  auto parameter = [&](const std::string& name) { return nominal_parameter(e, name, who); };
  const double x0 = parameter("x0");
  return {parameter("Ls1") + parameter("K1") / (2.0 * x0), parameter("Ls2") + parameter("K2") / (2.0 * x0),
          parameter("m")};
}

Eigen::Matrix<double, 9, 1> amb1dof_nominal_structure(const Experiment& e, const std::string& who) {
  auto parameter = [&](const std::string& name) { return nominal_parameter(e, name, who); };
  const Amb1dofNominal n = amb1dof_nominal(e, who);
  const double x0 = parameter("x0"), i0 = parameter("i0");
  // Force slopes of each coil at the operating point: ks_j = K_j i0^2 / (2 x0^3), kr_j = K_j i0 / (2 x0^2).
  const double ks = (parameter("K1") + parameter("K2")) * i0 * i0 / (2.0 * x0 * x0 * x0);
  const double kr1 = parameter("K1") * i0 / (2.0 * x0 * x0), kr2 = parameter("K2") * i0 / (2.0 * x0 * x0);
  Eigen::Matrix<double, 9, 1> v;
  v << ks / n.m, kr1 / n.m, kr2 / n.m, kr1 / n.L1, parameter("R1") / n.L1, kr2 / n.L2, parameter("R2") / n.L2,
      parameter("kw1") / n.L1, parameter("kw2") / n.L2;
  return v;
}

namespace {

// T = [C_x; C_x Ac; C_i1; C_i2] maps a realisation's state to the physical one (x, x', i1, i2).
Eigen::Matrix4d physical_transform(const ContinuousSystem& c) {
  Eigen::Matrix4d T;
  T.row(0) = c.C.row(0);
  T.row(1) = c.C.row(0) * c.A;
  T.row(2) = c.C.row(1);
  T.row(3) = c.C.row(2);
  return T;
}

Eigen::Matrix4d checked_inverse(const Eigen::Matrix4d& T) {
  const std::optional<Eigen::MatrixXd> inverse = linalg::regular_inverse(T);
  const double rcond = inverse ? 1.0 / (T.norm() * inverse->norm()) : 0.0;
  if (!inverse || !(rcond > 1e-12))
    throw Error("amb1dof physical coordinates: [C_x; C_x Ac; C_i1; C_i2] is singular (reciprocal condition " +
                std::to_string(rcond) + "): the outputs and the rate of x do not determine the state");
  return *inverse;
}

void check_shape(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C) {
  if (A.rows() != 4 || B.cols() != 2 || C.rows() != 3)
    throw Error("amb1dof physical coordinates: need a realisation with 4 states, 2 inputs and 3 outputs, got " +
                std::to_string(A.rows()) + ", " + std::to_string(B.cols()) + ", " + std::to_string(C.rows()));
}

}  // namespace

ContinuousSystem amb1dof_physical_coordinates(const ContinuousSystem& c) {
  check_shape(c.A, c.B, c.C);
  const Eigen::Matrix4d T = physical_transform(c);
  const Eigen::Matrix4d Ti = checked_inverse(T);
  return {T * c.A * Ti, T * c.B, c.C * Ti, c.D};
}

Amb1dofPhysicalModel amb1dof_physical_model(const DiscreteSystem& r) {
  r.validate();
  check_shape(r.A, r.B, r.C);
  if (r.D.cwiseAbs().maxCoeff() != 0.0)
    throw Error("amb1dof physical coordinates: the plant must be strictly proper (D = 0)");
  const ContinuousSystem c = d2c_zoh(r);
  const Eigen::Matrix4d T = physical_transform(c);
  const Eigen::Matrix4d Ti = checked_inverse(T);
  Amb1dofPhysicalModel out;
  out.discrete = {T * r.A * Ti, T * r.B, r.C * Ti, r.D, r.sample_time};
  out.continuous = {T * c.A * Ti, T * c.B, c.C * Ti, c.D};
  return out;
}

}  // namespace ambid::ident
