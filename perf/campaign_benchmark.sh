#!/usr/bin/env bash
# Campaign benchmark: runs `shakerbench run` on a config under /usr/bin/time -v and reports
# simulated periods per point (median and worst, over all points and over the points after
# the first frequency of each sweep), wall time per point and peak memory.
#
#   perf/campaign_benchmark.sh SHAKERBENCH CONFIG OUT_DIR [THREADS]
#
# The run starts from an empty OUT_DIR (no checkpoint is reused). Figures go to standard
# output and to OUT_DIR/benchmark.txt. Targets (docs/performance.md): median <= 12 periods
# per point after the first frequency of a sweep; peak memory < 1 GiB.
set -euo pipefail

if [[ $# -lt 3 ]]; then
    echo "usage: $0 SHAKERBENCH CONFIG OUT_DIR [THREADS]" >&2
    exit 2
fi
shakerbench=$1
config=$2
out=$3
threads=${4:-2}

rm -rf "$out"
mkdir -p "$(dirname "$out")"
timing=$(mktemp)
trap 'rm -f "$timing"' EXIT

/usr/bin/time -v "$shakerbench" run "$config" --out "$out" --threads "$threads" -q \
    2>"$timing" >/dev/null || {
    echo "shakerbench run failed:" >&2
    tail -n 30 "$timing" >&2
    exit 1
}

wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$timing")
peak_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$timing")
user_s=$(awk -F': ' '/User time/ {print $2}' "$timing")

# control.csv: arrangement,level_g,frequency_hz,status,periods,... one row per point in sweep
# order; the first row of each (arrangement, level) is the sweep's first frequency.
awk -F',' -v wall="$wall" -v peak_kb="$peak_kb" -v user_s="$user_s" -v threads="$threads" '
function median(a, n,    i, j, t) {
    for (i = 2; i <= n; ++i) { t = a[i]; for (j = i - 1; j >= 1 && a[j] > t; --j) a[j + 1] = a[j]; a[j + 1] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
}
NR == 1 { next }
{
    key = $1 "|" $2
    n_all++; all[n_all] = $5; total += $5
    if ($5 > worst_all) worst_all = $5
    status[$4]++
    if (key in seen) {
        n_warm++; warm[n_warm] = $5
        if ($5 > worst_warm) worst_warm = $5
        if ($4 == "converged" || $4 == "limit-cycle-2") { n_conv++; conv[n_conv] = $5 }
    } else {
        seen[key] = 1; sweeps++
    }
}
END {
    split(wall, parts, ":")
    seconds = 0
    for (i = 1; i in parts; ++i) seconds = seconds * 60 + parts[i]
    printf "points                        %d in %d sweeps (%d converged, %d limit-cycle-2, %d closest)\n", n_all, sweeps, status["converged"], status["limit-cycle-2"], status["closest"]
    printf "periods per point, all        median %g, worst %d, total %d\n", median(all, n_all), worst_all, total
    if (n_warm > 0)
        printf "periods per point, after the first frequency of a sweep: median %g, worst %d (%d points)\n", median(warm, n_warm), worst_warm, n_warm
    if (n_conv > 0)
        printf "  of those converged or limit-cycle-2: median %g\n", median(conv, n_conv)
    printf "wall time                     %s (%.1f s), %.2f s per point, %d threads, user %s s\n", wall, seconds, seconds / n_all, threads, user_s
    printf "peak memory (max RSS)         %.1f MiB\n", peak_kb / 1024
}' "$out/control.csv" | tee "$out/benchmark.txt"
