#!/usr/bin/env bash
# Installs what is missing, builds with warnings as errors and runs every test; then runs the
# unit tests again under AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh --test
jobs="$(nproc)"

echo "== architecture: leaf modules do not include each other"
scripts/check-architecture.sh

echo "== format"
mapfile -t sources < <(git ls-files '*.cpp' '*.hpp' 2>/dev/null || find . -name '*.[ch]pp' -not -path './build/*')
if ((${#sources[@]} > 0)); then
    clang-format --dry-run -Werror "${sources[@]}"
fi

echo "== release build with MPI (benchmarks compiled, not run), all tests (mpirun -np 2 included)"
cmake --preset ci >/dev/null
cmake --build --preset ci -j "$jobs"
ctest --preset ci -j "$jobs"

echo "== AddressSanitizer + UndefinedBehaviorSanitizer, unit tests"
cmake --preset ci-asan-ubsan >/dev/null
# Only the unit suites run under the sanitizers, so only they (and what they link) are built.
cmake --build --preset ci-asan-ubsan -j "$jobs" --target sb_unit_tests
ctest --preset ci-asan-ubsan -j "$jobs"
