#pragma once
// `ambid daemon identifier`: collects the plant's samples into windows (services/convert/plant_samples.hpp) and
// publishes the identified model of each (identify_window.hpp). Each window is read with the
// plant description its samples name (PlantDescription on the bus, described_windows.hpp):
// model, nominal parameters, signals, operating point and controller come with the data.
//
// One process serves every plant id of its "plants" (served_plants.hpp), each with its own
// windows, failure rule and model numbers; Health per plant on node PLANT/identifier (the
// failing-windows WARN there), and, serving a list or "all", the process's own node
// identifier@HOST:PID. A plant whose models another identifier also publishes
// (foreign_models.hpp) is logged, counted (ambid_foreign_models_total) and put in Health WARN.
//
// Config (JSON, every key optional):
//   {"plants": ["bearing-1", ...] | "all" (default: the --plant-id),
//    "method": "rpem" (kDefaultDaemonMethod, identify_window.hpp; any of identifier/methods.hpp,
//    listed by `ambid daemon identifier --help`; an unknown name is refused at start),
//    "window": 0.25 (s of samples per identification),
//    "settle": 0.25 (s dropped at the start of every record: the transient from the nominal
//    operating point to the plant's own), "transient_samples": 0 (samples skipped at the start of every window),
//    "publish_rate": 1 / window (Hz), "forgetting": 0.9999, "carry": 0.1 (method "rpem" only:
//    one recursive estimator per plant runs on every sample and publishes at publish_rate, the
//    information carried from one published estimate to the next scaled by carry;
//    continuous_estimator.hpp),
//    "failing_consecutive": 4, "failing_recent": 20, "failing_fraction": 0.5 (when windows keep
//    failing: window_failures.hpp)}
// A window the method cannot identify is skipped and counted by reason
// (ambid_windows_unidentified_total{reason}); while windows keep failing Health is WARN
// "windows not identified: ..." naming the last reason, and OK "windows identified again" after.
// The diagnostics daemon marks the parameters STALE on that WARN.
// Samples that never arrived (a jump in the plant's clock or the batch numbers:
// sample_gaps.hpp) are logged, counted (ambid_samples_missed_total), set Health WARN and raise
// a WARN alert history_gap (parameter "samples"): the hole in the history is visible. So are
// samples dropped because their plant description never arrived (described_windows.hpp).
#include "services/daemons/daemon_options.hpp"

namespace ambid::daemons {

int run_identifier_daemon(const DaemonOptions& options);

}  // namespace ambid::daemons
