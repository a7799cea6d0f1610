#pragma once
// `ambid daemon frf`: runs an excitation experiment through the plant daemon (an
// ExcitationCommand), records the next whole record of samples the plant starts under it,
// analyses it (identifier/frf_analysis.hpp) and publishes the FrequencyResponse with the
// input-sensitivity peaks and ISO 14839-3 zone; then asks the plant for its usual excitation
// again. Repeats every `interval` seconds (0: once).
//
// Config (JSON, every key optional):
//   {"duration": 1.0 (s analysed: the plant's record length; the samples are read with the plant
//    description they name, as by the identifier; the analysis keeps f_min..f_max),
//    "excitation": "multisine", "amplitude": 0.05, "f_min": 1, "f_max": 1000,
//    "interval": 0,
//    "restore_excitation": "prbs", "restore_amplitude": 0.05}
#include "services/daemons/daemon_options.hpp"

namespace ambid::daemons {

int run_frf_daemon(const DaemonOptions& options);

}  // namespace ambid::daemons
