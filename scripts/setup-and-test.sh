#!/usr/bin/env bash
# Installs what is missing, builds with warnings as errors and runs every test; then builds
# with clang, AddressSanitizer + UndefinedBehaviorSanitizer, runs the unit tests again and
# every libFuzzer target for a short while (SB_FUZZ_SECONDS, default 20 s each).
set -euo pipefail
cd "$(dirname "$0")/.."
# Each phase's heading carries the minutes and seconds since the start (docs/development.md
# keeps CI under 30 minutes; these say where the time goes).
phase() { printf '== [%d:%02d] %s\n' $((SECONDS / 60)) $((SECONDS % 60)) "$*"; }

scripts/install-deps.sh --test
jobs="$(nproc)"

phase "architecture: leaf modules do not include each other"
scripts/check-architecture.sh

phase "format"
mapfile -t sources < <(git ls-files '*.cpp' '*.hpp' 2>/dev/null || find . -name '*.[ch]pp' -not -path './build/*')
if ((${#sources[@]} > 0)); then
    clang-format --dry-run -Werror "${sources[@]}"
fi

phase "release build with MPI (benchmarks compiled, not run)"
cmake --preset ci >/dev/null
cmake --build --preset ci -j "$jobs"
phase "release tests (mpirun -np 2 included)"
ctest --preset ci -j "$jobs"

phase "clang build with AddressSanitizer + UndefinedBehaviorSanitizer: unit tests, then the libFuzzer targets"
echo "   ${SB_FUZZ_SECONDS:-20} s each (docs/development.md)"
# One build for both: the libraries carry the sanitizers and libFuzzer's coverage, the unit
# suites and the fuzz targets link them.
cmake --preset ci-sanitize >/dev/null
cmake --build --preset ci-sanitize -j "$jobs"
phase "sanitizer unit tests"
ctest --preset ci-sanitize -j "$jobs"
phase "libFuzzer targets"
# One target per core at a time; each one's output goes to build/ci-sanitize/logs/TARGET.log and is
# shown when the target finds an input that crashes, hangs or runs out of memory.
mkdir -p build/ci-sanitize/logs
printf '%s\n' config recording uff58 matrix_market checkpoint |
    SB_FUZZ_NO_BUILD=1 SB_FUZZ_BUILD_DIR=build/ci-sanitize xargs -P "$jobs" -I{} bash -c \
        'log=build/ci-sanitize/logs/{}.log
         if ! scripts/fuzz.sh {} "${SB_FUZZ_SECONDS:-20}" >"$log" 2>&1; then
             tail -n 80 "$log"; echo "fuzz {}: FAILED ($log)"
             exit 255
         fi
         echo "fuzz {}: $(grep -a -m1 DONE "$log")"'
phase "all passed"
