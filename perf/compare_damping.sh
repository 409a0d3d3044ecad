#!/usr/bin/env bash
# A predicted campaign against full runs of the same config on several fillings: natural
# frequency and damping per arrangement and level, the runs' mean and standard deviation over
# the fillings beside the prediction (docs/characterisation.md).
#
#   perf/compare_damping.sh PREDICTED_DIR RUN_DIR [RUN_DIR ...]
#
# METHOD=circle-fit (default) or half-power picks the estimator of damping.csv. A level is
# within the goal when the damping differs by at most 10 % of the runs' mean or their
# standard deviation, whichever is larger, and the frequency by at most 0.5 %; "-" when an
# estimate is missing (too few points kept, status closest or extrapolated left out).
set -euo pipefail
predicted=${1:?usage: $0 PREDICTED_DIR RUN_DIR [RUN_DIR ...]}
shift
[[ $# -ge 1 ]] || { echo "usage: $0 PREDICTED_DIR RUN_DIR [RUN_DIR ...]" >&2; exit 2; }
method=${METHOD:-circle-fit}

{
    awk -F',' -v src=P 'NR > 1 { print src "," $0 }' "$predicted/damping.csv"
    for run in "$@"; do
        awk -F',' -v src=R 'NR > 1 { print src "," $0 }' "$run/damping.csv"
    done
} | awk -F',' -v method="$method" '
$6 == method {
    key = $2 "," $3
    if (!(key in seen)) { seen[key] = 1; order[++n] = key }
    if ($1 == "P") { pf[key] = $4; pz[key] = $5 }
    else { k = ++rn[key]; rf[key, k] = $4; rz[key, k] = $5 }
}
function mean(a, key, m,    s, i) { s = 0; for (i = 1; i <= m; ++i) s += a[key, i]; return s / m }
function sd(a, key, m, mu,    s, i) {
    if (m < 2) return 0
    s = 0; for (i = 1; i <= m; ++i) s += (a[key, i] - mu) ^ 2
    return sqrt(s / (m - 1))
}
END {
    print "| arrangement | level [g] | f_n runs [Hz] | f_n predicted [Hz] | diff | zeta runs [%] | zeta predicted [%] | diff | within |"
    print "|---|---|---|---|---|---|---|---|---|"
    for (i = 1; i <= n; ++i) {
        key = order[i]; split(key, part, ",")
        m = rn[key]
        if (m == 0 || !(key in pf)) {
            printf "| %s | %s | %s | %s | - | %s | %s | - | - |\n", part[1], part[2],
                m ? sprintf("%.4f", mean(rf, key, m)) : "-", (key in pf) ? sprintf("%.4f", pf[key]) : "-",
                m ? sprintf("%.3f", 100 * mean(rz, key, m)) : "-", (key in pz) ? sprintf("%.3f", 100 * pz[key]) : "-"
            continue
        }
        fm = mean(rf, key, m); fs = sd(rf, key, m, fm)
        zm = mean(rz, key, m); zs = sd(rz, key, m, zm)
        df = 100 * (pf[key] - fm) / fm
        dz = 100 * (pz[key] - zm) / zm
        allowed = 0.1 * zm > zs ? 0.1 * zm : zs
        ok = (pz[key] - zm <= allowed && zm - pz[key] <= allowed && df <= 0.5 && df >= -0.5) ? "yes" : "no"
        printf "| %s | %s | %.4f ± %.4f (%d) | %.4f | %+.2f %% | %.3f ± %.3f | %.3f | %+.1f %% | %s |\n",
            part[1], part[2], fm, fs, m, pf[key], df, 100 * zm, 100 * zs, 100 * pz[key], dz, ok
    }
}'
