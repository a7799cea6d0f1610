#pragma once
// Audit cases on independent truths (tests/support/amb1dof_effect_records.hpp): realistic
// records (PRBS 1.5 V, 1 s, sensor noise 0.1 um on x and 1 mA on the currents, 30 % of its
// variance coloured, process force 0.02 N) with an effect drawn at a multiple of its
// catalogue scale.
#include <cstdint>
#include <string>
#include <vector>

#include "plant_sim/effects.hpp"
#include "support/amb1dof_effect_records.hpp"

namespace ambid::diag::testing {

test_support::EffectRecordOptions realistic_record(const std::string& controller, std::uint64_t seed);

// The catalogue's effects, plus force_factor once the catalogue has it.
std::vector<std::string> independent_effect_names();

// `name` with its switching parameter at `multiple` times its catalogue scale (clamped to its
// range), the sign and the channel drawn; a flexible mode at 300-1500 Hz with zeta
// 0.01-0.02, a harmonic at 20-400 Hz with a drawn phase. force_factor: ratio 1 - 0.1 multiple
// (drawn sign: 1 +- 0.1 multiple).
sim::Effect effect_at(const std::string& name, double multiple, std::uint64_t seed);

// A record with `name` hidden at a moderate size (drawn from `seed`: where a record shows it above
// the noise), under the controller `controller_index` (cycled) of those the effect leaves stable
// (a mode at 450 Hz with coupling 0.3 destabilises the observer loop, eddy currents of 1-2e-4 s
// the lead-lag one); a mode at 600-800 Hz on 2 s at 2 V, the two lags on 2 s. `truth`: the effect.
test_support::EffectRecordOptions hidden_effect_record(const std::string& name, std::uint64_t seed,
                                                       std::uint64_t controller_index, sim::Effect& truth);

// Mismatches outside the catalogue, drawn from `seed` under controller `controller_index`
// (cycled): "coil_inductance" (one coil's Ls 5-10 % off), "sensor_offset" (3-6 um),
// "second_mode" (modes at 600-800 and 1400-1800 Hz, coupling 0.3; 2 s at 2 V), "gain_drift"
// (one amplifier's gain +-10-20 % over 0.3-0.6 s). `what` describes the draw.
const std::vector<std::string>& out_of_catalogue_kinds();
test_support::EffectRecordOptions out_of_catalogue_record(const std::string& kind, std::uint64_t seed,
                                                          std::uint64_t controller_index, std::string& what);

// The size of an effect relative to its catalogue scale (|switching parameter| / scale).
double relative_size(const sim::Effect& effect);

// Effects the audit does not tell apart at 0.1 um / 1 mA on these records (known weaknesses,
// issue 17; measured z of the truth's finding against the other's):
// - the two lags (force behind current, measurement behind position): their fits differ by a
//   cost of ~0.002 (NRMSE^2) at 1.5-2e-4 s, and a larger lag makes every loop unstable. Since
//   the head-to-head test whitens the outputs jointly (diagnostics/audit/audit_rivals.hpp) the
//   confusion table's draws name both right (6 of 6, z 5.5-19.9 over the other); the group
//   stays until a wider sweep confirms it;
// - coil resistance and amplifier gain: both move the steady kw/R and with it every current,
//   which dominates the residual; the electrical pole that tells them apart sits at 6.5 Hz
//   (dkw 0.33 under PID named coil_resistance at z 713). Since the head-to-head choice
//   (diagnostics/audit/audit_rivals.hpp) the confusion table's draws name both right (6 of 6);
//   the group stays until a wider sweep confirms it;
// - a heavier rotor, saturation and the air gap: each rescales the force factor and the
//   negative stiffness (saturation's mechanical part is a mass change), the electrical
//   differences are below the 1 mA noise (dm 0.67 kg named magnetic_saturation at z 5.8 under
//   the observer loop, air_gap at z 7.2 under PID).
// The causes accepted for `name`: its group, or itself.
std::vector<std::string> accepted_causes(const std::string& name);

}  // namespace ambid::diag::testing
