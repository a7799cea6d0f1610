#!/usr/bin/env bash
# Sets up, builds, and runs the main job: the ambid service over DDS (loopback only) on a
# simulated bearing — plant, identifier and diagnostics daemons — then injects a coil fault
# (the plant source swapped to the same bearing with R1 +20 %) and shows the alert.
# Bounded: gives up after 60 s without the alert (exit 1).
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
echo "== learning the baseline of the nominal bearing (5 s)"
sleep 5
$ambid status --domain "$domain" --wait 2
echo "== injecting a coil fault: plant source -> deploy/config/coil1-hot.json (R1 17.5 -> 21 ohm, +20 %)"
$ambid source set sim deploy/config/coil1-hot.json --domain "$domain"
echo "== waiting for the ERROR alert about R1"
$ambid alerts --domain "$domain" --until ERROR:R1 --timeout 60
echo "== current alerts"
$ambid alerts --domain "$domain" --wait 2
