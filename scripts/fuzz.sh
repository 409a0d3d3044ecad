#!/usr/bin/env bash
# Runs one libFuzzer target for a while: scripts/fuzz.sh TARGET SECONDS [LIBFUZZER OPTION...]
# TARGET: config, recording, uff58, matrix_market or checkpoint (fuzz/fuzz_TARGET.cpp).
# Builds the 'fuzz' preset first, in build/fuzz or SB_FUZZ_BUILD_DIR. The committed seeds
# (fuzz/corpus/TARGET) are read, never written; what the fuzzer adds goes to
# BUILD/corpus/TARGET and a crashing input to BUILD/artifacts/TARGET/. Exit status: 0 when no input crashed, hung or ran out of
# memory; non-zero otherwise (the input is named in the output: fix the reader, then add the
# input to fuzz/corpus/TARGET and a unit test in the module's suite).
set -euo pipefail
cd "$(dirname "$0")/.."

targets=(config recording uff58 matrix_market checkpoint)
if [[ $# -lt 2 || ! " ${targets[*]} " =~ " $1 " || ! "$2" =~ ^[0-9]+$ ]]; then
    echo "usage: scripts/fuzz.sh TARGET SECONDS [LIBFUZZER OPTION...]" >&2
    echo "       TARGET: ${targets[*]}" >&2
    exit 2
fi
target=$1
seconds=$2
shift 2

build=${SB_FUZZ_BUILD_DIR:-build/fuzz}
if [[ "${SB_FUZZ_NO_BUILD:-}" != 1 ]]; then
    cmake --preset fuzz -B "$build" >/dev/null
    cmake --build "$build" --target sb_fuzzers -j "$(nproc)" >/dev/null
fi
corpus=$build/corpus/$target
artifacts=$build/artifacts/$target
mkdir -p "$corpus" "$artifacts"
# The readers' temporary files go to a folder of this run, removed at the end.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# -timeout: a reader that takes a second on an input of a few kB hangs for our purposes;
# -rss_limit_mb: a size field believed unchecked shows as running out of memory.
# fuzz/TARGET.dict: the format's words (keys, markers), which mutations rarely spell out.
TMPDIR=$scratch "$build"/fuzz/fuzz_"$target" "$corpus" fuzz/corpus/"$target" \
    -dict=fuzz/"$target".dict -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" "$@"
