#pragma once
// The plant description (experiment-format.md "The plant description": the sidecar without
// `name`) <-> PlantDescription message. The plant daemon describes each source's header; the
// identifier, FRF and diagnostics daemons and `ambid record` turn the message back into the
// header their windows get.
//
// description_id: 16 hex digits of the 64-bit FNV-1a hash of a canonical serialisation of the
// message (every field but plant_id and the id itself, in IDL order, doubles as exact hex
// floats, strings length-prefixed). Equal content gives equal ids on every machine and vendor;
// a receiver recomputes it and refuses a description whose id does not match its content.
#include <string>

#include "core/experiment.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// The description of `header` (its samples are ignored) for `plant_id`, id filled in. Keeps
// controller.output_limits / state_limits from the header's extra keys. Throws Error when the
// header fails validate_metadata().
bus::PlantDescription describe(const Experiment& header, const std::string& plant_id);

// The content hash described above.
std::string description_id(const bus::PlantDescription& description);

// The header (no samples; name "PLANT_ID description ID") a description stands for. Throws Error
// naming what is wrong: an id that does not match the content, a repeated parameter or
// operating-point name, a limit matrix that is not n x 2, or anything validate_metadata()
// refuses (controller dimensions, names, sample time).
Experiment experiment_header(const bus::PlantDescription& description);

// Plant family and controller kind as an operator reads them ("amb1dof_voltage", "state_space
// 5 states" or "none").
std::string controller_summary(const bus::PlantDescription& description);

}  // namespace ambid::convert
