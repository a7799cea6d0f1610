#!/usr/bin/env bash
# Sets up, builds and runs the test suite (everything but the `slow` label), then the readers'
# fuzz targets again under AddressSanitizer and UndefinedBehaviorSanitizer (preset `sanitize`,
# which builds only tests/fuzz and the libraries it needs).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default
ctest --preset default
cmake --preset sanitize
cmake --build --preset sanitize
build-sanitize/tests/fuzz_tests
