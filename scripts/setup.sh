#!/usr/bin/env bash
# Installs every Debian bookworm package ambid needs. Idempotent, asks no questions.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  lld  # the linker (CMakeLists.txt: several times faster than ld.bfd)
  libeigen3-dev libceres-dev
  nlohmann-json3-dev libcli11-dev libspdlog-dev libsqlite3-dev
  libmatio-dev  # MAT v5 files of `ambid import` (via pkg-config)
  libgtest-dev libgmock-dev libbenchmark-dev
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools cyclonedds-dev cyclonedds-tools
  libsystemd-dev prometheus-cpp-dev
  iproute2 procps libxml2-utils
  clang-format  # the style check (scripts/check-format.sh)
  chromium  # headless rendering test of the HTML audit report
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "setup: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -q
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
