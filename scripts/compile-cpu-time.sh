#!/usr/bin/env bash
# Measures what a clean build costs in CPU time, which a shared machine does not disturb the way
# it does wall time: configures an empty build tree (default preset, no compiler cache), builds
# it with every compile and link run under /usr/bin/time, and prints the CPU-seconds (user +
# system) summed over those processes, the most expensive steps, the build tree's size and the
# `ambid` binary's. On an idle machine with N cores the clean build takes about CPU / N.
#   scripts/compile-cpu-time.sh [BUILD_DIR [JOBS]]   clean build (default build-cpu-time, 2 jobs)
#   scripts/compile-cpu-time.sh --summary BUILD_DIR  the numbers of a build measured earlier
# The per-step log is BUILD_DIR/cpu-time.log ("user system wall output"); a step built again
# (after a fix) counts once, with its last time.
set -euo pipefail

# Launcher mode: CMake runs each compile and link as `compile-cpu-time.sh --record LOG CMD...`.
if [ "${1:-}" = "--record" ]; then
  log=$2
  shift 2
  out=$(printf '%s\n' "$@" | grep -A1 -x -e '-o' | tail -1)
  exec /usr/bin/time -a -o "$log" -f "%U %S %e $out" "$@"
fi

summary() {
  local build=$1
  echo "most expensive steps (CPU s, output):"
  awk '$1 ~ /^[0-9.]+$/ { cpu[$4] = $1 + $2 } END { for (o in cpu) printf "%8.1f  %s\n", cpu[o], o }' "$build/cpu-time.log" |
    sort -rn | head -25
  awk '$1 ~ /^[0-9.]+$/ { cpu[$4] = $1 + $2 }
    END {
      for (o in cpu) { total += cpu[o]; n++; if (o ~ /\.(o|gch)$/) compile += cpu[o] }
      printf "steps: %d; CPU (user + system): %.0f s = %.1f min (compiling %.0f s, linking %.0f s)\n",
        n, total, total / 60, compile, total - compile
      printf "idle estimate: %.1f min on 2 cores (CPU / 2)\n", total / 120
    }' "$build/cpu-time.log"
  echo "build tree: $(du -sh "$build" | cut -f1); ambid: $(stat -c %s "$build/services/ambid") bytes"
}

if [ "${1:-}" = "--summary" ]; then
  summary "$2"
  exit 0
fi

cd "$(dirname "$0")/.."
build=$(realpath -m "${1:-build-cpu-time}")
jobs=${2:-2}
self=$(realpath "$0")
rm -rf "$build"
export CCACHE_DISABLE=1
log=$build/cpu-time.log
launcher="$self;--record;$log"
cmake --preset default -B "$build" -DAMBID_CCACHE=OFF \
  -DCMAKE_C_COMPILER_LAUNCHER="$launcher" -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" \
  -DCMAKE_C_LINKER_LAUNCHER="$launcher" -DCMAKE_CXX_LINKER_LAUNCHER="$launcher" >/dev/null
start=$(date +%s)
nice ninja -C "$build" -j "$jobs" >"$build/ninja.out"
echo "wall on this machine: $(($(date +%s) - start)) s with $jobs jobs"
summary "$build"
