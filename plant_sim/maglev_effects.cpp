#include "plant_sim/maglev_effects.hpp"

namespace ambid::sim {
namespace {

std::vector<EffectSpec> build_catalogue() {
  return {
      {"force_law",
       false,
       {switching_parameter("dn_i", "1", 0.3, -0.9, 5.0, "true current exponent minus the nominal n_i"),
        switching_parameter("dn_x", "1", 0.5, -3.5, 5.0, "true gap exponent minus the nominal n_x")},
       "the force law F = Km i^n_i / x^n_x has other exponents than the nominal (reluctance vs dipole)"},
      {"coil_resistance",
       false,
       {switching_parameter("dR", "ohm", 10.0, -150.0, 1000.0, "true coil resistance minus the nominal R")},
       "the coil resistance differs from the nominal (a warm or damaged coil)"},
      {"amplifier_gain",
       false,
       {switching_parameter("dkw", "V/V", 0.05, -0.9, 10.0, "true actuator gain minus the nominal kw")},
       "the DAC and transistor stage put out another voltage per commanded volt than the nominal"},
      {"sensor_gain",
       false,
       {switching_parameter("dgain", "1", 0.03, -0.5, 1.0, "relative error of the position sensor's scale")},
       "the Hall sensor's distance scale is mis-calibrated"},
      {"sensor_offset",
       false,
       {switching_parameter("dy", "m", 2e-4, -5e-3, 5e-3, "offset of the position reading")},
       "the Hall sensor's distance reading is offset"},
      {"sensor_nonlinearity",
       false,
       {switching_parameter("dp", "1", 0.2, -0.8, 3.0,
                            "exponent of the sensor's power law minus 1 (exact at the operating gap)")},
       "the Hall sensor's field-to-distance map bends away from the operating gap"},
      {"sensor_delay",
       false,
       {switching_parameter("delay", "s", 3e-3, 0.0, 2e-2, "dead time of the position reading")},
       "the position reading arrives late (ADC, filtering, firmware loop)"},
      {"actuator_quantisation",
       false,
       {switching_parameter("step", "V", 0.2, 0.0, 2.0, "the DAC's voltage step near the operating point")},
       "the DAC quantises the coil voltage (an 8-bit board: about 0.35 V steps)"},
      {"rotor_mass",
       false,
       {switching_parameter("dm", "kg", 7e-5, -6e-4, 1e-2, "true levitated mass minus the nominal m")},
       "the levitated body's mass differs from the nominal"},
      {"harmonic_disturbance",
       false,
       {shape_parameter("f", "Hz", 50.0, 0.1, 1000.0, "frequency of the disturbance force"),
        switching_parameter("Fc", "N", 5e-4, -1.0, 1.0, "cosine amplitude of the force"),
        switching_parameter("Fs", "N", 5e-4, -1.0, 1.0, "sine amplitude of the force")},
       "a periodic force acts on the body (a mains-frequency field, a vibrating stand)"},
  };
}

}  // namespace

const std::vector<EffectSpec>& maglev_effect_catalogue() {
  static const std::vector<EffectSpec> catalogue = build_catalogue();
  return catalogue;
}

}  // namespace ambid::sim
