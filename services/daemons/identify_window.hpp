#pragma once
// The identifier daemon's one computation: a window of closed-loop samples of the
// amb1dof_voltage bearing -> its physical model, by one of the time-domain methods of
// identifier/identify_experiment.hpp with the known controller, as an IdentifiedModel message.
// Default `closed-loop` (Lee ch. 2): unbiased off nominal (R1 +20 % reads +20 %), but it
// reports no sigmas, so the diagnostics learn the scatter from the baseline windows;
// `deadbeat` reports sigmas but is biased when the controller's observer model is wrong.
//
// The controller's integrator state at the first sample of a window is not on the bus; the
// window is identified with it taken as zero. closed-loop fits r -> y with the controller's
// transfer function only (no initial state). deadbeat: the error is a constant shift of the
// reconstructed velocity, which the offset term of the realisation absorbs exactly:
// x[k+1] = A x + B u + c holds for x + d with c' = c + d - A d.
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "identifier/identify_experiment.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

inline constexpr const char* kDefaultWindowMethod = "closed-loop";

// How a window is identified: `method` (one of ident::identification_methods()), every
// sample of the window in the fit (no validation part), `skip_samples` leading samples
// dropped. Throws Error naming the known methods for an unknown one, and for skip < 0.
ident::IdentifyOptions window_identify_options(const std::string& method, Eigen::Index skip_samples = 0);

// Throws Error (InsufficientData for unexciting data) naming what the window lacks. Sigmas
// the method does not report are 0.
bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::IdentifyOptions& options = window_identify_options(kDefaultWindowMethod));

}  // namespace ambid::daemons
