#include "plant_sim/maglev_rig.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

struct RigField {
  const char* name;
  double MaglevRig::*member;
};
constexpr RigField kRigFields[] = {
    {"Kp", &MaglevRig::Kp},
    {"Ti", &MaglevRig::Ti},
    {"Td", &MaglevRig::Td},
    {"integral_min", &MaglevRig::integral_min},
    {"integral_max", &MaglevRig::integral_max},
    {"pid_min", &MaglevRig::pid_min},
    {"pid_max", &MaglevRig::pid_max},
    {"v_ref", &MaglevRig::v_ref},
    {"dac_step", &MaglevRig::dac_step},
    {"sensor_gain", &MaglevRig::sensor_gain},
    {"sensor_offset", &MaglevRig::sensor_offset},
    {"sensor_exponent", &MaglevRig::sensor_exponent},
    {"sensor_reference", &MaglevRig::sensor_reference},
    {"sensor_coupling", &MaglevRig::sensor_coupling},
    {"sensor_delay", &MaglevRig::sensor_delay},
    {"log_x", &MaglevRig::log_x},
    {"log_u", &MaglevRig::log_u},
    {"log_i", &MaglevRig::log_i},
};

[[noreturn]] void fail_rig(const std::string& what, double value) {
  std::ostringstream msg;
  msg << "maglev rig: " << what << ", got " << value;
  throw Error(msg.str());
}

}  // namespace

std::map<std::string, double> MaglevRig::to_map() const {
  std::map<std::string, double> out;
  for (const auto& f : kRigFields) out[f.name] = this->*f.member;
  return out;
}

void MaglevRig::set(const std::string& name, double value) {
  for (const auto& f : kRigFields)
    if (name == f.name) {
      this->*f.member = value;
      return;
    }
  std::string valid;
  for (const auto& f : kRigFields) valid += (valid.empty() ? "" : ", ") + std::string(f.name);
  throw Error("maglev rig: unknown setting '" + name + "'; valid names: " + valid);
}

void MaglevRig::validate() const {
  for (const auto& f : kRigFields) {
    const double v = this->*f.member;
    if (!std::isfinite(v)) fail_rig(std::string(f.name) + " must be finite", v);
  }
  if (!(Kp > 0.0)) fail_rig("Kp must be positive", Kp);
  if (!(Ti > 0.0)) fail_rig("Ti must be positive", Ti);
  if (!(Td >= 0.0)) fail_rig("Td must be >= 0", Td);
  if (!(integral_min <= integral_max)) fail_rig("integral_min must not exceed integral_max", integral_min);
  if (!(pid_min <= pid_max)) fail_rig("pid_min must not exceed pid_max", pid_min);
  if (!(v_ref > 0.0)) fail_rig("v_ref must be positive", v_ref);
  if (!(dac_step >= 0.0)) fail_rig("dac_step must be >= 0", dac_step);
  if (!(sensor_gain > 0.0)) fail_rig("sensor_gain must be positive", sensor_gain);
  if (!(sensor_exponent > 0.0)) fail_rig("sensor_exponent must be positive", sensor_exponent);
  if (!(sensor_reference > 0.0)) fail_rig("sensor_reference must be positive", sensor_reference);
  if (!(sensor_delay >= 0.0) || sensor_delay != std::floor(sensor_delay))
    fail_rig("sensor_delay must be a whole number of samples >= 0", sensor_delay);
  for (const double r : {log_x, log_u, log_i})
    if (!(r >= 0.0)) fail_rig("log resolutions must be >= 0", r);
}

const std::vector<std::string>& MaglevRig::names() {
  static const std::vector<std::string> out = [] {
    std::vector<std::string> n;
    for (const auto& f : kRigFields) n.emplace_back(f.name);
    return n;
  }();
  return out;
}

double MaglevRig::sense(double x, double i) const {
  return sensor_offset + sensor_gain * sensor_reference * std::pow(x / sensor_reference, sensor_exponent) +
         sensor_coupling * i;
}

double MaglevRig::dac(double u) const { return round_to(u, dac_step); }

double round_to(double v, double resolution) {
  return resolution > 0.0 ? resolution * std::nearbyint(v / resolution) : v;
}

}  // namespace ambid::sim
