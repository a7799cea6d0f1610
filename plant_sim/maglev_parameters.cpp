#include "plant_sim/maglev_parameters.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

// The one table tying the contract names to the members.
struct MaglevField {
  const char* name;
  double MaglevParameters::*member;
};
constexpr MaglevField kMaglevFields[] = {
    {"m", &MaglevParameters::m},         {"g", &MaglevParameters::g},         {"R", &MaglevParameters::R},
    {"L", &MaglevParameters::L},         {"Km", &MaglevParameters::Km},       {"Ke", &MaglevParameters::Ke},
    {"kw", &MaglevParameters::kw},       {"n_i", &MaglevParameters::n_i},     {"n_x", &MaglevParameters::n_x},
    {"x_min", &MaglevParameters::x_min}, {"x_max", &MaglevParameters::x_max},
};

std::string valid_maglev_names() {
  std::string out;
  for (const auto& f : kMaglevFields) out += (out.empty() ? "" : ", ") + std::string(f.name);
  return out;
}

}  // namespace

MaglevParameters MaglevParameters::nominal() {
  MaglevParameters p;
  p.m = 7.4e-4;
  p.g = 9.81;
  p.R = 210.0;
  p.L = 0.3;
  p.Km = p.Ke = 1.5e-8;
  p.kw = 1.0;
  p.n_i = 1.0;
  p.n_x = 4.0;
  p.x_min = 0.012;
  p.x_max = 0.017;
  return p;
}

std::map<std::string, double> MaglevParameters::to_map() const {
  std::map<std::string, double> out;
  for (const auto& f : kMaglevFields) out[f.name] = this->*f.member;
  return out;
}

MaglevParameters MaglevParameters::from_map(const std::map<std::string, double>& values) {
  MaglevParameters p;
  for (const auto& f : kMaglevFields) {
    const auto it = values.find(f.name);
    if (it == values.end()) throw Error(std::string("maglev1coil_voltage parameter '") + f.name + "' is missing");
    p.*f.member = it->second;
  }
  p.validate();
  return p;
}

void MaglevParameters::set(const std::string& name, double value) {
  for (const auto& f : kMaglevFields)
    if (name == f.name) {
      this->*f.member = value;
      return;
    }
  throw Error("unknown maglev1coil_voltage parameter '" + name + "'; valid names: " + valid_maglev_names());
}

void MaglevParameters::validate() const {
  for (const auto& f : kMaglevFields) {
    const double v = this->*f.member;
    if (!std::isfinite(v) || !(v > 0.0)) {
      std::ostringstream msg;
      msg << "maglev1coil_voltage parameter '" << f.name << "' must be positive and finite, got " << v;
      throw Error(msg.str());
    }
  }
  if (!(x_min < x_max)) {
    std::ostringstream msg;
    msg << "maglev1coil_voltage: the top stop x_min = " << x_min << " m must lie above the ground x_max = " << x_max
        << " m";
    throw Error(msg.str());
  }
}

const std::vector<std::string>& MaglevParameters::names() {
  static const std::vector<std::string> out = [] {
    std::vector<std::string> n;
    for (const auto& f : kMaglevFields) n.emplace_back(f.name);
    return n;
  }();
  return out;
}

double MaglevParameters::force(double current, double gap) const {
  return std::copysign(Km * std::pow(std::abs(current), n_i), current) / std::pow(gap, n_x);
}

double MaglevParameters::equilibrium_current(double gap) const {
  return std::pow(m * g * std::pow(gap, n_x) / Km, 1.0 / n_i);
}

}  // namespace ambid::sim
