#include "maglev_audit_cases.hpp"

#include <cmath>

#include "core/error.hpp"
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
  else if (effect != "none")
    throw Error("no maglev audit case for '" + effect + "'");
  return c;
}

Experiment maglev_case_record(const MaglevCase& c, double sample_time, Eigen::Index samples, std::uint64_t seed) {
  return test_support::maglev_record(c.truth, c.rig, test_support::maglev_run_options(sample_time, samples, seed));
}

}  // namespace ambid::diag::testing
