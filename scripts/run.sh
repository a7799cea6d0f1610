#!/usr/bin/env bash
# Sets up, builds, and runs the main job: the nominal simulated bearing in closed loop.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default --target ambid
mkdir -p runs
build/services/ambid sim --plant amb1dof_voltage --duration 2 --seed 7 --out runs/nominal
