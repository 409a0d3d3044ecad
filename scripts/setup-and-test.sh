#!/usr/bin/env bash
# Installs what is missing, builds with warnings as errors and runs every test; then runs the
# unit tests again under AddressSanitizer + UndefinedBehaviorSanitizer; then runs every
# libFuzzer target for a short while (SB_FUZZ_SECONDS, default 20 s each).
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

echo "== libFuzzer targets, ${SB_FUZZ_SECONDS:-20} s each (clang, ASan + UBSan; docs/development.md)"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$jobs"
# One target per core at a time; each one's output goes to build/fuzz/logs/TARGET.log and is
# shown when the target finds an input that crashes, hangs or runs out of memory.
mkdir -p build/fuzz/logs
printf '%s\n' config recording uff58 matrix_market checkpoint |
    SB_FUZZ_NO_BUILD=1 xargs -P "$jobs" -I{} bash -c \
        'if ! scripts/fuzz.sh {} "${SB_FUZZ_SECONDS:-20}" >build/fuzz/logs/{}.log 2>&1; then
             tail -n 80 build/fuzz/logs/{}.log; echo "fuzz {}: FAILED (build/fuzz/logs/{}.log)"
             exit 255
         fi
         echo "fuzz {}: $(grep -a -m1 DONE build/fuzz/logs/{}.log)"'
