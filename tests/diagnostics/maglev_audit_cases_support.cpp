#include "maglev_audit_cases.hpp"

#include <cmath>

#include "core/error.hpp"
#include "plant_sim/maglev_effects.hpp"
#include "support/maglev_records.hpp"

namespace ambid::diag::testing {

sim::MaglevParameters maglev_truth(double n_i, double n_x) {
  sim::MaglevParameters p = sim::MaglevParameters::nominal();
  p.n_i = n_i;
  p.n_x = n_x;
  p.Km = p.m * p.g * std::pow(0.014, n_x) / std::pow(0.019, n_i);
  p.Ke = p.Km;
  return p;
}

namespace maglev_audit_cases_support {

// `p` with its mass scaled by `factor` and the force and back-EMF constants with it (the same
// gravity balance).
sim::MaglevParameters with_mass(sim::MaglevParameters p, double factor) {
  p.m *= factor;
  p.Km *= factor;
  p.Ke = p.Km;
  return p;
}

}  // namespace maglev_audit_cases_support
using namespace maglev_audit_cases_support;

MaglevCase maglev_case(const std::string& effect) {
  MaglevCase c{effect, maglev_truth(1.0, 4.0), {}};
  if (effect == "sensor_nonlinearity")
    c.rig.sensor_exponent = 1.2;
  else if (effect == "force_law")
    c.truth = maglev_truth(1.3, 3.4);
  else if (effect == "actuator_quantisation")
    c.rig.dac_step = 0.35;
  else if (effect == "sensor_delay")
    c.rig.sensor_delay = 1;
  else if (effect == "coil_resistance")
    c.truth.R = 235.0;
  else if (effect == "sensor_offset")
    c.rig.sensor_offset = 3e-4;
  else if (effect == "sensor_gain")
    c.rig.sensor_gain = 1.04;
  else if (effect == "amplifier_gain")
    c.truth.kw = 1.1;
  else if (effect == "rotor_mass")  // the force constant still holds the body at 14 mm with 19 mA
    c = {effect, with_mass(maglev_truth(1.0, 4.0), 1.5), {}};
  else if (effect == "harmonic_disturbance") {
    c.harmonic_force = 1e-3;  // 14 % of the body's weight
    c.harmonic_frequency = 50.0;
  } else if (effect != "none")
    throw Error("no maglev audit case for '" + effect + "'");
  return c;
}

std::vector<std::string> maglev_case_effects() {
  std::vector<std::string> names;
  for (const auto& spec : sim::maglev_effect_catalogue()) names.push_back(spec.name);
  return names;
}

Experiment maglev_case_record(const MaglevCase& c, sim::MaglevRunOptions run) {
  run.harmonic_force = c.harmonic_force;
  run.harmonic_frequency = c.harmonic_frequency;
  return test_support::maglev_record(c.truth, c.rig, run);
}

}  // namespace ambid::diag::testing
