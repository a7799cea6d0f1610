#pragma once
// The identifier daemon's computation with a window method (every method but rpem, which
// continuous_estimator.hpp runs): a window of closed-loop samples of the amb1dof_voltage
// bearing -> its model and estimates (identifier/identify_window.hpp, the same function
// `ambid diagnose` calls) -> an IdentifiedModel message.
//
// The controller's integrator state at the first sample of a window is not on the bus; the
// window is identified with it taken as zero. closed-loop fits r -> y with the controller's
// transfer function only (no initial state). deadbeat: the error is a constant shift of the
// reconstructed velocity, which the offset term of the realisation absorbs exactly:
// x[k+1] = A x + B u + c holds for x + d with c' = c + d - A d.
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "identifier/identify_window.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

using ident::window_identify_options;

// The identifier daemon's default method: rpem, one recursive estimator per plant on every
// sample (continuous_estimator.hpp), ~3 % of a core per bearing at 10 kHz where pem on each
// window needs more than a core (bench/recursive_identification_bench.cpp). `ambid diagnose`
// keeps ident::kDefaultWindowMethod (pem: each window on its own).
inline constexpr const char* kDefaultDaemonMethod = "rpem";

// Throws Error (InsufficientData for unexciting data) naming what the window lacks. Sigmas
// the method does not report are 0.
bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::IdentifyOptions& options);

}  // namespace ambid::daemons
