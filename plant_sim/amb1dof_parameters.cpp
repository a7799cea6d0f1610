#include "plant_sim/amb1dof_parameters.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

// The one table tying the contract names to the members.
struct Field {
  const char* name;
  double Amb1dofParameters::*member;
};
constexpr Field kFields[] = {
    {"m", &Amb1dofParameters::m},     {"x0", &Amb1dofParameters::x0},   {"i0", &Amb1dofParameters::i0},
    {"R1", &Amb1dofParameters::R1},   {"R2", &Amb1dofParameters::R2},   {"Ls1", &Amb1dofParameters::Ls1},
    {"Ls2", &Amb1dofParameters::Ls2}, {"K1", &Amb1dofParameters::K1},   {"K2", &Amb1dofParameters::K2},
    {"kw1", &Amb1dofParameters::kw1}, {"kw2", &Amb1dofParameters::kw2},
};

std::string valid_names() {
  std::string out;
  for (const auto& f : kFields) out += (out.empty() ? "" : ", ") + std::string(f.name);
  return out;
}

const Field& field(const std::string& name) {
  for (const auto& f : kFields)
    if (name == f.name) return f;
  throw Error("unknown amb1dof_voltage parameter '" + name + "'; valid names: " + valid_names());
}

}  // namespace

Amb1dofParameters Amb1dofParameters::nominal() {
  Amb1dofParameters p;
  p.m = 1.8;
  p.x0 = 3.5e-4;
  p.i0 = 0.5;
  p.R1 = p.R2 = 17.5;
  p.Ls1 = p.Ls2 = 0.086;
  p.K1 = p.K2 = 2.401e-4;
  p.kw1 = p.kw2 = 1.0;
  return p;
}

std::map<std::string, double> Amb1dofParameters::to_map() const {
  std::map<std::string, double> out;
  for (const auto& f : kFields) out[f.name] = this->*f.member;
  return out;
}

Amb1dofParameters Amb1dofParameters::from_map(const std::map<std::string, double>& values) {
  Amb1dofParameters p;
  for (const auto& f : kFields) {
    const auto it = values.find(f.name);
    if (it == values.end()) throw Error(std::string("amb1dof_voltage parameter '") + f.name + "' is missing");
    p.*f.member = it->second;
  }
  p.validate();
  return p;
}

void Amb1dofParameters::set(const std::string& name, double value) { this->*field(name).member = value; }

double Amb1dofParameters::get(const std::string& name) const { return this->*field(name).member; }

void Amb1dofParameters::validate() const {
  for (const auto& f : kFields) {
    const double v = this->*f.member;
    if (!std::isfinite(v) || !(v > 0.0)) {
      std::ostringstream msg;
      msg << "amb1dof_voltage parameter '" << f.name << "' must be positive and finite, got " << v;
      throw Error(msg.str());
    }
  }
}

double Amb1dofParameters::L1() const { return Ls1 + K1 / (2.0 * x0); }
double Amb1dofParameters::L2() const { return Ls2 + K2 / (2.0 * x0); }

const std::vector<std::string>& Amb1dofParameters::names() {
  static const std::vector<std::string> out = [] {
    std::vector<std::string> n;
    for (const auto& f : kFields) n.emplace_back(f.name);
    return n;
  }();
  return out;
}

}  // namespace ambid::sim
