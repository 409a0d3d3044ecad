#!/usr/bin/env bash
# Cross-check of the DEM against LAMMPS on the paper-000 damper (see docs/dem.md).
# Usage: validation/lammps/compare.sh [build-dir]   (default: build/dem)
# Builds the slow DEM test, then runs the comparison: it writes the random fill as a LAMMPS
# data file, runs `lmp -in in.damper` with the same law and time step, computes LAMMPS's
# dissipated power from the momentum balance and compares it with ShakerBench's energy ledger
# (tolerance 10 %). Needs `lmp` (Debian: apt-get install -y lammps). Takes about 25 s.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${1:-$root/build/dem}"
command -v lmp > /dev/null || { echo "lmp not found: apt-get install -y lammps"; exit 77; }
cmake --build "$build" --target dem_slow_test -j2
"$build/tests/dem/dem_slow_test" --gtest_filter='LammpsComparison.*'
