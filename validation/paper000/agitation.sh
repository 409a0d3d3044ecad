#!/usr/bin/env bash
# Which layers of the bed move at resonance: per arrangement, level and filling of a recording
# directory written with output.energy = true, the point of largest accelerance
# |acc_<control> / force| (points.csv) and its energy.csv row: the mean kinetic energy relative
# to the enclosure of the particles in each horizontal layer (bottom first, in µJ), their sum,
# and the share of it in the upper half of the cavity.
#
#   validation/paper000/agitation.sh OUT [CONTROL_CHANNEL]      # default channel: acc_damper
set -euo pipefail
if [[ $# -lt 1 || ! -f $1/points.csv || ! -f $1/energy.csv ]]; then
    echo "usage: $0 OUT [CONTROL_CHANNEL]  (OUT: a recording directory with points.csv and energy.csv)" >&2
    exit 2
fi
out=$1
channel=${2:-acc_damper}
awk -F, -v channel="$channel" '
    # points.csv has a filling column only with several fillings per sweep
    function filling(f) { return (f, "filling") in col ? $col[f, "filling"] : 0 }
    FNR == 1 {
        file++
        for (c = 1; c <= NF; ++c) col[file, $c] = c
        if (file == 1 && !((1, "force_re") in col && (1, channel "_re") in col)) {
            print "points.csv has no force_re or " channel "_re column" > "/dev/stderr"
            exit 2
        }
        if (file == 2) {
            for (c = 1; c <= NF; ++c) if ($c ~ /^layer_[0-9]+_kinetic_j$/) kinetic[++layers] = c
            if (layers == 0) {
                print "energy.csv has no layer_<k>_kinetic_j columns" > "/dev/stderr"
                exit 2
            }
        }
        next
    }
    file == 1 {
        fr = $col[1, "force_re"]; fi = $col[1, "force_im"]
        ar = $col[1, channel "_re"]; ai = $col[1, channel "_im"]
        f2 = fr * fr + fi * fi
        if (f2 == 0) next
        h = sqrt((ar * ar + ai * ai) / f2)
        key = $1 SUBSEP $2 SUBSEP filling(1)
        if (!(key in best) || h > best[key]) { best[key] = h; at[key] = $3 }
        next
    }
    {
        key = $1 SUBSEP $2 SUBSEP filling(2)
        if (!(key in at) || ($3 - at[key]) ^ 2 > (1e-6 * at[key]) ^ 2) next
        total = upper = 0
        text = ""
        for (l = 1; l <= layers; ++l) {
            e = 1e6 * $kinetic[l]
            total += e
            if (l > layers / 2) upper += e
            text = text sprintf("%s%.3g", l > 1 ? ", " : "", e)
        }
        printf "| %s | %s g | %s | %.3f Hz | %.3g | %s | %.0f %% |\n", $1, $2, filling(2), $3,
               best[key], text, (total > 0 ? 100 * upper / total : 0)
    }' "$out/points.csv" "$out/energy.csv" |
    sort -t'|' -k2,2 -k3,3n -k4,4n |
    { echo "| arrangement | level | filling | resonance | accelerance [(m/s²)/N] | agitation per layer, bottom first [µJ] | upper half |"
      echo "|---|---|---|---|---|---|---|"; cat; }
