#!/usr/bin/env bash
# Sets up, builds and runs the test suite (everything but the `slow` label).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default
ctest --preset default
