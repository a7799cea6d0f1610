#pragma once
// `ambid daemon diagnostics`: identified models -> diagnostics engine (trend store in SQLite)
// -> Alert messages (transient-local: a late subscriber gets the latest). When the models stop
// (the identifier's writer loses liveliness or goes away, or none came for `silence` seconds
// of wall time) every parameter of the plant is marked STALE at the last model time plus the
// stale timeout; the next model brings it back to OK. When the identifier's Health says its
// windows keep failing (window_failures.hpp) every parameter is marked STALE at once, naming
// the reason; again the next model brings it back.
// A hole in the history is logged and raised as a WARN alert history_gap (parameter "all"):
// a jump in the model numbers (this daemon fell behind or was stopped; model_gaps.hpp) or a
// restarted identifier (numbers from 0 again) whose first model comes more than 4 windows of
// plant time after the last one. Its value is the plant seconds the hole spans.
//
// One process serves every plant id of its "plants" (served_plants.hpp): each has its own
// engine (baselines, trend state, loop and fault signatures), clock and model numbering; the
// trend store is shared (keyed by plant id). Health per plant on node PLANT/diagnostics, and,
// serving a list or "all", the process's own node diagnostics@PID. The identifier's
// failing-windows WARN is read per plant (node PLANT/identifier).
//
// Config (JSON, every key optional):
//   {"plants": ["bearing-1", ...] | "all" (default: the --plant-id), "store": "ambid-trend.sqlite",
//    "learning_windows": 50, "persist_windows": 100,
//    "unconverged_sigma_ratio": 2 (an estimate whose sigma is over this many times the
//    baseline's has not converged: stored, not judged, logged "P: R1 not judged: sigma ..."
//    and "P: R1 judged again ..."; diag::MonitorConfig),
//    "confirm_windows": 3 (a WARN or ERROR, or a new cause of one, is raised once this many
//    judged windows in a row agree on it; diag::AlertPolicy, "Confirmation"),
//    "error_fraction": 0.10, "warn_fraction": 0.005 (smaller changes are not alerted),
//    "stale_timeout": 30 (s of plant time), "silence": 3 (s wall),
//    retention of the trend store (diag::RetentionPolicy): "keep_windows_days": 7 (per-window
//    estimates, then aggregated), "aggregate_bucket": 3600 (s per aggregate), "keep_days": 365,
//    "retention_period": 600 (s of plant time between two passes; the first pass runs at the
//    first model)}
#include "services/daemons/daemon_options.hpp"

namespace ambid::daemons {

int run_diagnostics_daemon(const DaemonOptions& options);

}  // namespace ambid::daemons
