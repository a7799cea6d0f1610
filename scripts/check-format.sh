#!/usr/bin/env bash
# Checks that every C++ file follows .clang-format (clang-format 14, Debian bookworm's).
# Prints the files that do not and exits 1; `scripts/check-format.sh --fix` rewrites them.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=(--dry-run --Werror)
[ "${1:-}" = "--fix" ] && mode=(-i)
git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format "${mode[@]}" --style=file
[ "${1:-}" = "--fix" ] || echo "format: every file follows .clang-format"
