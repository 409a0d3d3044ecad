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

points=$(tail -n +2 "$out/control.csv" | wc -l)
seconds=$(awk -v wall="$wall" 'BEGIN { n = split(wall, p, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + p[i]; print s }')
{
    "$(dirname "$0")/campaign_point_stats.sh" "$out"
    awk -v s="$seconds" -v n="$points" -v wall="$wall" -v threads="$threads" -v user_s="$user_s" \
        'BEGIN { printf "wall time                     %s (%.1f s), %.2f s per point, %d threads, user %s s (%.2f s per point)\n", wall, s, s / n, threads, user_s, user_s / n }'
    awk -v kb="$peak_kb" 'BEGIN { printf "peak memory (max RSS)         %.1f MiB\n", kb / 1024 }'
} | tee "$out/benchmark.txt"
