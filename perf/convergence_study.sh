#!/usr/bin/env bash
# Convergence study of a damping curve: how much each numerical setting moves the damping and
# natural frequency per level, against the scatter of the bed's filling.
#
#   [SETS='KEY=VALUE ...'] perf/convergence_study.sh SHAKERBENCH CONFIG OUT_DIR [SEEDS] [VARIANTS...]
#
# Every variant runs CONFIG with SEEDS fillings (campaign.seeds, default 5), the --set values
# of SETS (common to all variants: levels, arrangements) and the variant's own, into
# OUT_DIR/<variant>; its damping.csv holds the mean and the scatter per level and method. An
# interrupted study resumes: run the same command again (each variant resumes from its
# checkpoints; OUT_DIR/wall_times.txt then holds the wall time of the last part).
#
# The table (OUT_DIR/convergence.md) gives, per variant, level and method, the mean damping
# and frequency, their change against the baseline, the chance part of that change (two
# standard deviations of the difference of two means of fillings) and the baseline's seed
# scatter. A change within its chance part is not resolved by the fillings run: to show that
# a setting moves the curve by less than a quarter of the scatter, run more fillings.
#
# VARIANTS (default: all, in the order of the list below) name entries of that list, run in
# the order given; add your own in the same form.
set -euo pipefail

if [[ $# -lt 3 ]]; then
    echo "usage: $0 SHAKERBENCH CONFIG OUT_DIR [SEEDS] [VARIANTS...]" >&2
    exit 2
fi
shakerbench=$1
config=$2
out=$3
seeds=${4:-5}
shift $(($# < 4 ? $# : 4))

# The config's own values (with SETS) that the variants scale: the Hooke law's stiffness
# varies as the inverse square of the allowed overlap, so stiffness x s is the overlap
# fraction / sqrt(s); the tighter tolerance's 8-period windows get four times the budget.
damper=${DAMPER:-pd}
key_args=(keys "$config")
for s in ${SETS:-}; do key_args+=(--set "$s"); done
value_of() {  # the value of a dotted key as `shakerbench keys` prints it
    "$shakerbench" "${key_args[@]}" | awk -v key="$1" '$1 == key && !found { print $3; found = 1 }'
}
overlap=$(value_of "dampers.$damper.contact.max_overlap_fraction")
budget=$(value_of controller.max_periods)
if [[ -z $overlap || -z $budget ]]; then
    echo "$0: $config has no dampers.$damper.contact.max_overlap_fraction or controller.max_periods (DAMPER=NAME names the damper)" >&2
    exit 2
fi
overlap_for() { awk -v o="$overlap" -v s="$1" 'BEGIN { printf "%.6g", o / sqrt(s) }'; }

# name | --set assignments (space separated). The baseline's time step is the config's, by
# default the automatic one (docs/dem.md: t_c/10 for a Hooke contact of restitution 0.9).
variants=(
    "baseline|"
    "dt_tc/10|dampers.$damper.contact.time_step_fraction=0.1"
    "stiffness_x0.5|dampers.$damper.contact.max_overlap_fraction=$(overlap_for 0.5)"
    "stiffness_x2|dampers.$damper.contact.max_overlap_fraction=$(overlap_for 2)"
    "stiffness_x4|dampers.$damper.contact.max_overlap_fraction=$(overlap_for 4)"
    "stiffness_per_level|dampers.$damper.contact.stiffness_for=level"
    "dt_tc/40|dampers.$damper.contact.time_step_fraction=0.025"
    "dt_tc/80|dampers.$damper.contact.time_step_fraction=0.0125"
    "modes_3|structure.modes=3"
    "modes_12|structure.modes=12"
    "grid_11|campaign.frequencies.count=11"
    "tolerance_0.02|controller.tolerance=0.02 controller.window_periods=8 controller.max_periods=$((4 * budget))"
)

# The variants named on the command line, in their order; all of them otherwise.
selected=("$@")
if ((${#selected[@]} == 0)); then
    for entry in "${variants[@]}"; do selected+=("${entry%%|*}"); done
fi
mkdir -p "$out"
for name in "${selected[@]}"; do
    sets=
    found=0
    for entry in "${variants[@]}"; do
        if [[ ${entry%%|*} == "$name" ]]; then
            sets=${entry#*|}
            found=1
        fi
    done
    if ((!found)); then
        echo "$0: no variant '$name' (see the list in the script)" >&2
        exit 2
    fi
    dir="$out/${name//\//_}"
    args=(run "$config" --out "$dir" -q --set "campaign.seeds=$seeds")
    for s in ${SETS:-} $sets; do args+=(--set "$s"); done
    echo "== $name: ${args[*]}" >&2
    start=$(date +%s)
    "$shakerbench" "${args[@]}" >/dev/null
    echo "$name $(($(date +%s) - start))" >>"$out/wall_times.txt"
done

# The table: one row per variant, level and method (damping.csv: level_g is column 2,
# natural_frequency_hz 3, damping_ratio 4, method 5, fillings 9, damping_ratio_std 11).
table="$out/convergence.md"
{
    echo "| variant | level [g] | method | damping [%] (fillings) | change vs baseline | ± (2 std of the change) | baseline seed scatter (std) | frequency [Hz] | change |"
    echo "|---|---|---|---|---|---|---|---|---|"
    for dir in "$out/baseline" $(find "$out" -mindepth 1 -maxdepth 1 -type d ! -name baseline | sort); do
        [[ -f "$dir/damping.csv" ]] || continue
        awk -F, -v name="$(basename "$dir")" '
            FNR == 1 { next }
            NR == FNR { bz[$2 "|" $5] = $4; bf[$2 "|" $5] = $3; bs[$2 "|" $5] = $11; bn[$2 "|" $5] = $9; next }
            {
                key = $2 "|" $5
                dz = dfr = sz = unc = ""
                if (key in bz) {
                    dz = sprintf("%+.1f %%", 100 * ($4 / bz[key] - 1))
                    dfr = sprintf("%+.2f %%", 100 * ($3 / bf[key] - 1))
                    sz = sprintf("%.1f %%", 100 * bs[key] / bz[key])
                    # The means of n and m fillings differ by chance with the standard
                    # deviation std * sqrt(1/n + 1/m) (the baseline scatter for both).
                    unc = sprintf("%.1f %%", 200 * bs[key] * sqrt(1 / bn[key] + 1 / $9) / bz[key])
                }
                printf "| %s | %s | %s | %.3f (%s) | %s | %s | %s | %.4f | %s |\n",
                       name, $2, $5, 100 * $4, $9, dz, unc, sz, $3, dfr
            }' "$out/baseline/damping.csv" "$dir/damping.csv"
    done
} >"$table"
cat "$table"
