#pragma once
// The rig board's PID (plant_sim/maglev_rig.hpp) in the contract's controller form
// (experiment-format.md; ../shared/notes/maglev-rig.md): input v = x - x0 (m), output u,
//   xc = [I - u0, v_{k-1}],  A = [[1, 0], [0, 0]],  B = [[q g], [1]],
//   C = [[1, -kd g]],  D = [[(Kp + q + kd) g]],   q = Kp Ts/Ti, kd = Kp Td/Ts, g = 1000 mm/m,
// with output_limits [0, v_ref]. The PID runs on y - reference, this form on y - x0: the
// reference's part of the command (its proportional and derivative terms and its running
// integral) goes into the reconstructed r = u - uf, so a replay with this controller and that
// r follows the levels. For the same reason the integral's clamps have no place here (the
// form's integral is the rig's plus the integral of reference - x0); while the body levitates
// they do not act (the integral holds the command near u0), and where they do the sample is
// clamped and not exogenous anyway.
#include "core/experiment.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::sim {

// Error for a non-positive sample time or bad rig settings (MaglevRig::validate).
StateSpaceController maglev_rig_controller(const MaglevRig& rig, double sample_time);

// Gives a rig record (y = [x, i], u = [u], its operating point set) the board's PID in the
// contract's form and the reference input r = u - the form's output replayed on the logged x and
// u (deviations), as `ambid import --reconstruct-r` does: r carries w and the reference's part
// of the command. What the form does not contain is listed under the sidecar's
// `rig.not_in_controller` (the integral's and the PID's clamps, the reference, w). Error for a
// record of other signals or without an operating point x.
void attach_rig_controller(Experiment& record, const MaglevRig& rig);

}  // namespace ambid::sim
