#!/usr/bin/env bash
# Periods per point of a campaign directory: from control.csv when the campaign finished,
# else from its checkpoints (a campaign still running or interrupted).
#
#   perf/campaign_point_stats.sh OUT_DIR
#
# Prints the number of points by status, and the median and worst periods per point, over
# all points and over the points after the first frequency of each sweep; then where the
# periods above the controller's floor went (the fewest a point can take: transient_periods
# + average_periods x window_periods of the resolved config): first points, second points,
# later points that changed their amplitude, and the first points' final drive over the
# warm start's.
set -euo pipefail
out=${1:?usage: $0 OUT_DIR}
controller_value() {  # KEY: its value in the [controller] table of config.resolved.toml
    awk -F' = ' -v key="$1" '/^\[/ { inside = ($0 == "[controller]") }
                             inside && $1 == key { print $2; exit }' "$out/config.resolved.toml"
}
floor=0
if [[ -f "$out/config.resolved.toml" ]]; then
    floor=$(($(controller_value transient_periods) +
             $(controller_value average_periods) * $(controller_value window_periods)))
fi

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

rows | awk -F',' -v floor="$floor" '
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
    above = $5 > floor ? $5 - floor : 0
    index_in_sweep = seen[key]++
    if (index_in_sweep > 0) {
        n_warm++; warm[n_warm] = $5
        if ($5 > worst_warm) worst_warm = $5
        if ($4 == "converged" || $4 == "limit-cycle-2") { n_conv++; conv[n_conv] = $5 }
        if (index_in_sweep == 1) above_second += above
        else if ($6 > 0 || $4 == "closest") { above_later += above; n_later++ }
        else above_rest += above
    } else {
        sweeps++; above_first += above
        # amplitudes_tried: the warm start first, the final amplitude last
        n_tried = split($9, tried, ";")
        if (n_tried > 0 && tried[1] > 0) { n_ratio++; ratio[n_ratio] = tried[n_tried] / tried[1] }
    }
}
END {
    printf "points                        %d in %d sweeps (%d converged, %d limit-cycle-2, %d closest)\n", n_all, sweeps, status["converged"], status["limit-cycle-2"], status["closest"]
    printf "periods per point, all        median %s, worst %d, total %d\n", median(all, n_all), worst_all, total
    printf "periods per point, after the first frequency of a sweep: median %s, worst %d (%d points)\n", median(warm, n_warm), worst_warm, n_warm
    printf "  of those converged or limit-cycle-2: median %s\n", median(conv, n_conv)
    if (floor > 0) {
        printf "periods above the floor of %d per point: %d of %d (%.0f %%): first points %d, second points %d, later points that changed amplitude or ran to closest %d (%d points), other later points %d\n", floor, above_first + above_second + above_later + above_rest, total, 100 * (above_first + above_second + above_later + above_rest) / total, above_first, above_second, above_later, n_later, above_rest
    }
    printf "first points: final drive / warm start, median %s (%d sweeps)\n", median(ratio, n_ratio), n_ratio
}'
