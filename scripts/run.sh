#!/usr/bin/env bash
# Sets up, builds, and runs the main job: the ambid service over DDS (loopback only) on a
# simulated bearing — plant, identifier and diagnostics daemons — then injects a coil fault
# (the plant source swapped to the same bearing with R1 +20 %) and shows the alert.
# Bounded: gives up after 120 s without the baseline's models or 60 s without the alert.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default --target ambid
ambid=build/services/ambid
domain=${AMBID_DOMAIN:-42}
rundir=runs/stack
rm -rf "$rundir"
trap 'deploy/local-stack.sh stop "$domain" "$rundir"' EXIT

echo "== starting the stack on a simulated bearing (DDS domain $domain, loopback, logs in $rundir/)"
deploy/local-stack.sh start "$domain" "$rundir"
# The diagnostics learn 20 windows of 0.5 s (deploy/config/diagnostics.json, identifier.json:
# rpem published every 0.5 s) at real time (plant.json): about 11 s, longer when it falls behind.
# The fault goes in once the identifier has published 22 models (status), at most 120 s.
echo "== learning the baseline of the nominal bearing (20 windows)"
published() {
  $ambid status --domain "$domain" --wait 1 |
    awk '/\(identifier\)/ { for (i = 1; i < NF; i++) if ($i == "published") n = $(i + 1) + 0 } END { print n + 0 }'
}
SECONDS=0
until (($(published) >= 22)); do
  ((SECONDS < 120)) || { echo "the identifier published no 22 models in 120 s" >&2; exit 1; }
done
$ambid status --domain "$domain" --wait 2
echo "== injecting a coil fault: plant source -> deploy/config/coil1-hot.json (R1 17.5 -> 21 ohm, +20 %)"
$ambid source set sim deploy/config/coil1-hot.json --domain "$domain"
echo "== waiting for the ERROR alert about R1"
$ambid alerts --domain "$domain" --until ERROR:R1 --timeout 60
echo "== current alerts"
$ambid alerts --domain "$domain" --wait 2
