#pragma once
// The effect catalogue of `maglev1coil_voltage` (experiment-format.md, effect vocabulary;
// ../shared/notes/maglev-rig.md): what a single-coil rig shows and the nominal model leaves
// out. The effects act in plant_sim/maglev_extended.hpp:
//   force_law             dn_i, dn_x: F = Km' i^(n_i+dn_i) / x^(n_x+dn_x)
//   coil_resistance       dR: R -> R + dR
//   amplifier_gain        dkw: kw -> kw + dkw (DAC and transistor stage)
//   sensor_gain           dgain: y = (1 + dgain) s(x)
//   sensor_offset         dy: y = s(x) + dy
//   sensor_nonlinearity   dp: s(x) = x0 (x/x0)^(1+dp), x0 the operating gap (the Hall sensor's
//                         power-law calibration is exact there)
//   sensor_delay          delay: y read `delay` late (linear between samples)
//   actuator_quantisation step: the coil gets the command rounded to multiples of `step`
//   rotor_mass            dm: m -> m + dm
//   harmonic_disturbance  f, Fc, Fs: a force Fc cos(2 pi f t) + Fs sin(2 pi f t) along +x
// None belongs to a channel (one coil, one amplifier). Scales are those of the rig: 0.74 g,
// 210 ohm, 12-17 mm, 1.3-4 ms samples.
#include <vector>

#include "plant_sim/effects.hpp"

namespace ambid::sim {

const std::vector<EffectSpec>& maglev_effect_catalogue();

}  // namespace ambid::sim
