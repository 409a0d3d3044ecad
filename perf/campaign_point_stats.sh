#!/usr/bin/env bash
# Periods per point of a campaign directory: from control.csv when the campaign finished,
# else from its checkpoints (a campaign still running or interrupted).
#
#   perf/campaign_point_stats.sh OUT_DIR
#
# Prints the number of points by status, and the median and worst periods per point, over
# all points and over the points after the first frequency of each sweep.
set -euo pipefail
out=${1:?usage: $0 OUT_DIR}

rows() {
    if [[ -f "$out/control.csv" ]]; then
        tail -n +2 "$out/control.csv"
    else
        # Checkpoint lines "l<TAB><control.csv row>", one file per sweep, in point order.
        for f in "$out"/checkpoints/*.txt; do
            [[ -f "$f" ]] && grep '^l	' "$f" | cut -f2
        done
    fi
}

rows | awk -F',' '
function median(a, n,    i, j, t) {
    if (n == 0) return "-"
    for (i = 2; i <= n; ++i) { t = a[i]; for (j = i - 1; j >= 1 && a[j] > t; --j) a[j + 1] = a[j]; a[j + 1] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
}
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
    printf "points                        %d in %d sweeps (%d converged, %d limit-cycle-2, %d closest)\n", n_all, sweeps, status["converged"], status["limit-cycle-2"], status["closest"]
    printf "periods per point, all        median %s, worst %d, total %d\n", median(all, n_all), worst_all, total
    printf "periods per point, after the first frequency of a sweep: median %s, worst %d (%d points)\n", median(warm, n_warm), worst_warm, n_warm
    printf "  of those converged or limit-cycle-2: median %s\n", median(conv, n_conv)
}'
