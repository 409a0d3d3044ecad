#!/usr/bin/env bash
# LAMMPS throughput on problem (a) of docs/performance.md (paper-000 damper, same law and dt as
# the comparison). Needs the fill written by the comparison test (compare.sh) in
# ${TMPDIR:-/tmp}/sb_dem_lammps/damper.data. Usage: bench_lammps.sh [steps=200000]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="${TMPDIR:-/tmp}/sb_dem_lammps"
steps="${1:-200000}"
cd "$dir"
k=2e5; m=$(awk 'BEGIN{print 7800*3.141592653589793/6*27e-9}')
# zeta for e = 0.9 with no tensile force (dem::linear_zeta_from_restitution)
zeta=0.034265
etapp=$(awk -v z=$zeta -v k=$k -v m=$m 'BEGIN{print 2*z*sqrt(k*m/2)}')
etapw=$(awk -v z=$zeta -v k=$k -v m=$m 'BEGIN{print 2*z*sqrt(k*m)}')
w=$(awk 'BEGIN{print 2*3.141592653589793*6.3}')
amp=$(awk -v w=$w 'BEGIN{print 3*9.80665/(w*w)}')
lmp -log none -in "$here/in.damper" -var data damper.data -var out bench_series.txt \
    -var dt 2e-6 -var steps "$steps" -var kn $k -var kt $(awk -v k=$k 'BEGIN{print 2*k/7}') \
    -var etapp "$etapp" -var etapw "$etapw" -var amp "$amp" -var omega "$w" -var every 100000 \
    | awk -v n="$steps" '/^Loop time/ {print; printf "LAMMPS: %.4g particle-steps/s (wall)\n", 120*n/$4} /CPU use/ {print}'
