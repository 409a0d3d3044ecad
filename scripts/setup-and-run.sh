#!/usr/bin/env bash
# Installs what is missing, builds Release and runs the main job on the built-in default
# campaign. Usage: scripts/setup-and-run.sh [OUT_DIR]   (default: out/default)
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

out="${1:-out/default}"
mkdir -p "$out"
# The main job: the built-in paper-000 H-0 campaign (a few minutes on two cores). Run it
# again to resume an interrupted run.
build/release/apps/shakerbench run --out "$out"
