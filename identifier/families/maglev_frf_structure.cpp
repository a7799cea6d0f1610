#include "identifier/families/maglev_frf_structure.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

double value_of(const std::map<std::string, double>& values, const std::string& name, const char* where) {
  const auto it = values.find(name);
  if (it == values.end()) throw Error(std::string("maglev FRF structure: ") + where + "." + name + " is missing");
  return it->second;
}

Eigen::VectorXd start(const Experiment& h) {
  const auto p = [&](const char* name) { return value_of(h.plant.parameters, name, "plant.parameters"); };
  const double x0 = value_of(h.operating_point, "x", "operating_point"),
               i0 = value_of(h.operating_point, "i", "operating_point");
  const double g = p("g"), n_i = p("n_i"), n_x = p("n_x"), L = p("L");
  const double rho = p("Km") * std::pow(i0, n_i) / (p("m") * g * std::pow(x0, n_x));
  const double emf = n_i * p("Ke") / rho * std::pow(i0, n_i - 1.0) / (std::pow(x0, n_x) * L);
  Eigen::VectorXd theta(5);
  theta << n_x * g / x0, n_i * g / i0, p("R") / L, p("kw") / L, emf;
  return theta;
}

Eigen::VectorXd unstable_pole(const Eigen::VectorXd& theta) {
  const Eigen::VectorXcd poles = linalg::eigenvalues(maglev_structure_model(theta).A);
  double pole = 0.0;
  for (Eigen::Index k = 0; k < poles.size(); ++k) pole = std::max(pole, poles(k).real());
  return Eigen::VectorXd::Constant(1, pole);
}

// Gravity balance at both points: a x = n_x g, b i = n_i g and emf i = n_i (Ke / Km) m g / L
// hold at every level, R / L and kw / L do not depend on it.
Eigen::VectorXd maglev_level_transport(const Eigen::VectorXd& theta, const std::map<std::string, double>& from,
                                       const std::map<std::string, double>& to) {
  const double x_ratio = value_of(from, "x", "level") / value_of(to, "x", "operating_point"),
               i_ratio = value_of(from, "i", "level") / value_of(to, "i", "operating_point");
  Eigen::VectorXd out = theta;
  out(0) *= x_ratio;
  out(1) *= i_ratio;
  out(4) *= i_ratio;
  return out;
}

}  // namespace

ContinuousSystem maglev_structure_model(const Eigen::VectorXd& theta) {
  if (theta.size() != 5) throw Error("maglev structure: theta needs 5 entries, got " + std::to_string(theta.size()));
  ContinuousSystem c;
  c.A = Eigen::MatrixXd::Zero(3, 3);
  c.A(0, 1) = 1.0;
  c.A(1, 0) = theta(0);
  c.A(1, 2) = -theta(1);
  c.A(2, 1) = theta(4);
  c.A(2, 2) = -theta(2);
  c.B = Eigen::Vector3d(0.0, 0.0, theta(3));
  c.C = Eigen::MatrixXd::Zero(2, 3);
  c.C(0, 0) = 1.0;
  c.C(1, 2) = 1.0;
  c.D = Eigen::MatrixXd::Zero(2, 1);
  return c;
}

const FrfStructure& maglev_frf_structure() {
  static const FrfStructure s{{"a", "b", "R_over_L", "kw_over_L", "emf"},
                              {"unstable_pole"},
                              start,
                              maglev_structure_model,
                              unstable_pole,
                              "x",
                              maglev_level_transport};
  return s;
}

}  // namespace ambid::ident
