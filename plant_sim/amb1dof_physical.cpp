#include "plant_sim/amb1dof_physical.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

double at(const std::map<std::string, double>& v, const char* key) {
  const auto it = v.find(key);
  if (it == v.end()) throw Error(std::string("amb1dof_voltage structure parameter '") + key + "' is missing");
  return it->second;
}

void require_positive(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    std::ostringstream msg;
    msg << "amb1dof_voltage: " << name << " must be positive and finite, got " << value;
    throw Error(msg.str());
  }
}

}  // namespace

std::map<std::string, double> amb1dof_structure_parameters(const Amb1dofParameters& p) {
  const double x0sq = p.x0 * p.x0;
  const double ks1 = p.K1 * p.i0 * p.i0 / (2.0 * x0sq * p.x0);
  const double ks2 = p.K2 * p.i0 * p.i0 / (2.0 * x0sq * p.x0);
  const double kr1 = p.K1 * p.i0 / (2.0 * x0sq);
  const double kr2 = p.K2 * p.i0 / (2.0 * x0sq);
  const double L1 = p.L1(), L2 = p.L2();
  return {{"v1", (ks1 + ks2) / p.m}, {"v2", kr1 / p.m}, {"v3", kr2 / p.m},  {"v4", kr1 / L1},  {"v5", p.R1 / L1},
          {"v6", kr2 / L2},          {"v7", p.R2 / L2}, {"v8", p.kw1 / L1}, {"v9", p.kw2 / L2}};
}

ContinuousSystem amb1dof_structure_system(const std::map<std::string, double>& v) {
  ContinuousSystem sys;
  sys.A = Eigen::MatrixXd::Zero(4, 4);
  sys.A(0, 1) = 1.0;
  sys.A(1, 0) = at(v, "v1");
  sys.A(1, 2) = at(v, "v2");
  sys.A(1, 3) = -at(v, "v3");
  sys.A(2, 1) = -at(v, "v4");
  sys.A(2, 2) = -at(v, "v5");
  sys.A(3, 1) = at(v, "v6");
  sys.A(3, 3) = -at(v, "v7");
  sys.B = Eigen::MatrixXd::Zero(4, 2);
  sys.B(2, 0) = at(v, "v8");
  sys.B(3, 1) = at(v, "v9");
  sys.C = Eigen::MatrixXd::Zero(3, 4);
  sys.C(0, 0) = 1.0;
  sys.C(1, 2) = 1.0;
  sys.C(2, 3) = 1.0;
  sys.D = Eigen::MatrixXd::Zero(3, 2);
  return sys;
}

std::map<std::string, double> amb1dof_structure_parameters(const ContinuousSystem& sys) {
  if (sys.A.rows() != 4 || sys.A.cols() != 4 || sys.B.rows() != 4 || sys.B.cols() != 2) {
    std::ostringstream msg;
    msg << "amb1dof_voltage structure needs A 4x4 and B 4x2, got A " << sys.A.rows() << "x" << sys.A.cols() << " and B "
        << sys.B.rows() << "x" << sys.B.cols();
    throw Error(msg.str());
  }
  return {{"v1", sys.A(1, 0)}, {"v2", sys.A(1, 2)},  {"v3", -sys.A(1, 3)}, {"v4", -sys.A(2, 1)}, {"v5", -sys.A(2, 2)},
          {"v6", sys.A(3, 1)}, {"v7", -sys.A(3, 3)}, {"v8", sys.B(2, 0)},  {"v9", sys.B(3, 1)}};
}

std::map<std::string, double> Amb1dofPhysical::to_map() const {
  return {{"R1", R1},   {"R2", R2}, {"kw1", kw1},         {"kw2", kw2},        {"kr1", kr1},
          {"kr2", kr2}, {"ks", ks}, {"kr1_emf", kr1_emf}, {"kr2_emf", kr2_emf}};
}

Amb1dofPhysical amb1dof_physical_from_structure(const std::map<std::string, double>& v, double L1, double L2,
                                                double m) {
  require_positive(L1, "inductance L1");
  require_positive(L2, "inductance L2");
  require_positive(m, "mass m");
  Amb1dofPhysical out;
  out.ks = at(v, "v1") * m;
  out.kr1 = at(v, "v2") * m;
  out.kr2 = at(v, "v3") * m;
  out.kr1_emf = at(v, "v4") * L1;
  out.R1 = at(v, "v5") * L1;
  out.kr2_emf = at(v, "v6") * L2;
  out.R2 = at(v, "v7") * L2;
  out.kw1 = at(v, "v8") * L1;
  out.kw2 = at(v, "v9") * L2;
  return out;
}

Amb1dofPhysical amb1dof_physical_from_structure(const std::map<std::string, double>& v,
                                                const Amb1dofParameters& nominal) {
  return amb1dof_physical_from_structure(v, nominal.L1(), nominal.L2(), nominal.m);
}

}  // namespace ambid::sim
