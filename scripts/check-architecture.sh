#!/usr/bin/env bash
# Checks the include rules of ../shared/design/architecture.md on the source tree:
#  1. a library's public headers are the .hpp files at its root; headers in its subfolders are
#     internal and may be included only by the library itself, its tests (tests/LIB/) and bench/;
#  2. arrows point one way: core <- plant_sim, identifier <- diagnostics <- services;
#  3. no DDS header outside services/;
#  4. the test programs' files are safe in a unity batch (tests/CMakeLists.txt): no anonymous
#     namespace, file-local names in a namespace named after the file (every *_test.cpp opens
#     one; none opens another file's), and every #define is #undef'd in the same file;
#  5. Eigen's decompositions are compiled once, in core/linalg.cpp: library code (core, plant_sim,
#     identifier, diagnostics, services, bench, examples) includes no Eigen module but
#     <Eigen/Core> (and <unsupported/Eigen/FFT>) and names no decomposition class or method; it
#     calls core/linalg.hpp instead. Tests are exempt (they may compute an independent truth with
#     Eigen itself), though core/linalg serves them too and compiles faster.
# Prints every violation as file:line and exits 1 when there is one. Run by ctest (architecture).
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

sources() { find "$@" -name '*.cpp' -o -name '*.hpp' -o -name '*.h'; }
status=0
fail() { echo "$1"; status=1; }

# 1. Internal headers: LIB/SUB/x.hpp included from outside LIB, tests/LIB and bench.
for lib in core plant_sim identifier diagnostics services/bus; do
  outside=$(sources core plant_sim identifier diagnostics services tests bench examples 2>/dev/null |
            grep -v -e "^$lib/" -e "^tests/$lib/" -e "^bench/" || true)
  [ -n "$outside" ] || continue
  while IFS= read -r hit; do
    fail "internal header of $lib included from outside it: $hit"
  done < <(echo "$outside" | xargs grep -nE "#include \"$lib/[a-z0-9_]+/" || true)
done

# 2. Dependency direction: LIB may not include the folders listed after it.
forbid() {
  local lib=$1; shift
  for other in "$@"; do
    while IFS= read -r hit; do
      fail "$lib must not depend on $other: $hit"
    done < <(sources "$lib" | xargs grep -nE "#include \"$other/" || true)
  done
}
forbid core plant_sim identifier diagnostics services
forbid plant_sim identifier diagnostics services
forbid identifier plant_sim diagnostics services
forbid diagnostics services

# 3. DDS headers (vendor APIs and generated types) only in services/.
while IFS= read -r hit; do
  fail "DDS header outside services/: $hit"
done < <(sources core plant_sim identifier diagnostics | xargs grep -nE '#include [<"](fastdds|fastrtps|fastcdr|dds/|idl/)' || true)

# 4. Unity-safe test files: a batch compiles several .cpp files as one translation unit.
test_sources=$(find tests -name '*.cpp' | sort)
stems=$(echo "$test_sources" | xargs -n1 basename | sed 's/\.cpp$//')
for file in $test_sources; do
  stem=$(basename "$file" .cpp)
  while IFS= read -r hit; do
    fail "anonymous namespace in a test file (unity batches): $file:$hit: use namespace $stem"
  done < <(grep -nE '^namespace \{' "$file" || true)
  case $file in
    *_test.cpp) grep -qE "^namespace $stem \{" "$file" || fail "$file: no namespace $stem for its file-local names" ;;
  esac
  while IFS=: read -r line name; do
    [ "$name" = "$stem" ] || ! grep -qx "$name" <<<"$stems" ||
      fail "$file:$line: namespace $name is another file's (copied?): use namespace $stem"
  done < <(grep -noE '^namespace [a-z0-9_]+ \{' "$file" | sed -E 's/namespace ([a-z0-9_]+) \{/\1/' || true)
  while IFS=: read -r line macro; do
    grep -qE "^#undef $macro\b" "$file" || fail "$file:$line: #define $macro without #undef (it would leak into the next file of a unity batch)"
  done < <(grep -noE '^#define [A-Za-z0-9_]+' "$file" | sed -E 's/#define //' || true)
done

# 5. Decompositions only in core/linalg.cpp (whole-line comments are not code).
library_sources=$(sources core plant_sim identifier diagnostics services bench examples 2>/dev/null |
                  grep -vx core/linalg.cpp || true)
decomposition='#include <(Eigen/[A-Za-z]+|unsupported/Eigen/[A-Za-z]+)>|'\
'\b(SelfAdjointEigenSolver|ComplexEigenSolver|GeneralizedEigenSolver|EigenSolver|RealSchur|ComplexSchur|'\
'JacobiSVD|BDCSVD|HouseholderQR|ColPivHouseholderQR|FullPivHouseholderQR|CompleteOrthogonalDecomposition|'\
'FullPivLU|PartialPivLU|LLT|LDLT|MatrixExponential|MatrixLogarithm)\b|'\
'\.(householderQr|colPivHouseholderQr|fullPivHouseholderQr|completeOrthogonalDecomposition|fullPivLu|'\
'partialPivLu|lu|llt|ldlt|jacobiSvd|bdcSvd|eigenvalues|operatorNorm|determinant)\('
while IFS= read -r hit; do
  fail "Eigen decomposition outside core/linalg.cpp (call core/linalg.hpp): $hit"
done < <(echo "$library_sources" | xargs grep -nE "$decomposition" |
         grep -vE '^[^:]+:[0-9]+:[[:space:]]*//' |
         grep -vE '#include <(Eigen/Core|unsupported/Eigen/FFT)>' || true)

[ $status -eq 0 ] && echo "architecture: include rules, unity-safe test files and linalg-only decompositions hold"
exit $status
