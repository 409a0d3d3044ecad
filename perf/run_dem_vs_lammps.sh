#!/usr/bin/env bash
# ShakerBench DEM against LAMMPS on the reference problems of docs/performance.md, in one run:
#   (a) paper-000 damper (120 x 3 mm steel, 19 x 25 mm cylinder, 6.3 Hz, 3 g), one thread;
#   (b) 5,000 x 2 mm steel in paper 002's 30 x 30 x 50 mm cavity, settled bed, 120 Hz 10.5 g,
#       one and two threads (LAMMPS: 1 and 2 MPI ranks).
# Same initial state, law, excitation, time step and step counts on both sides. ShakerBench
# adapts its Verlet skin (docs/dem.md); LAMMPS runs at the configured skin and, when they
# differ, again at the skin ShakerBench ended with, and the ratio is taken against the faster
# of its two runs.
# Prints particle-steps/s per wall second and per CPU second (on a shared host the CPU figure is
# the stable one for one thread), the ratio ShakerBench / LAMMPS and the peak RSS of each process.
#
# Usage: perf/run_dem_vs_lammps.sh [build-dir]      (default: build/perf, Release)
# Environment: STEPS_A, WARMUP_A, STEPS_B, WARMUP_B override the step counts (defaults: those of
# dem_throughput, 300000 + 200000 for (a), 10000 + 5000 for (b)); THREADS_B="1 2";
# COUNTS_B="5000" (sphere counts of (b), its footprint scaled with the count: "5000 50000"
# measures the scaling in N; SKIP_A=1 leaves (a) out).
# Needs lmp (Debian `lammps`), mpirun (for 2 ranks) and GNU time (scripts/install-deps.sh).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
build="${1:-$root/build/perf}"
work="${TMPDIR:-/tmp}/sb_dem_vs_lammps"
threads_b="${THREADS_B:-1 2}"
counts_b="${COUNTS_B:-5000}"
command -v lmp > /dev/null || { echo "lmp not found: apt-get install -y lammps" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "/usr/bin/time not found: scripts/install-deps.sh" >&2; exit 2; }
mkdir -p "$work"

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSB_BUILD_BENCHMARKS=ON \
    -DSB_BUILD_TESTS=OFF > "$work/cmake.log"
cmake --build "$build" --target dem_throughput -j2 > "$work/build.log"
bench="$build/perf/dem_throughput"

steps_args() {  # case -> --warmup/--steps overrides from the environment
    local w s
    if [ "$1" = a ]; then w="${WARMUP_A:-}"; s="${STEPS_A:-}"; else w="${WARMUP_B:-}"; s="${STEPS_B:-}"; fi
    [ -n "$w" ] && printf -- '--warmup %s ' "$w"
    [ -n "$s" ] && printf -- '--steps %s ' "$s"
    return 0
}
peak_rss_mb() { awk -F': ' '/Maximum resident set size/ {printf "%.1f", $2 / 1024}' "$1"; }
field() { tr ' ' '\n' < "$2" | awk -F= -v k="$1" '$1 == k {print $2}'; }

# LAMMPS: the last `run` is the timed one; CPU seconds = loop time x CPU use.
lammps_rates() {  # log particles steps -> "wall_rate cpu_rate"
    awk -v n="$2" -v s="$3" '
        /^Loop time of/ {loop = $4}
        /% CPU use/ {cpu = $1; sub("%", "", cpu)}
        END {printf "%.4g %.4g", n * s / loop, n * s / (loop * cpu / 100)}' "$1"
}

report() {  # label wall cpu rss
    printf '%-46s %14s %14s %8s MB\n' "$1" "$2" "$3" "$4"
}

run_case() {  # case threads [count]
    local c="$1" t="$2" vars n steps ours lmp_cmd size=() tag="$1"
    if [ -n "${3:-}" ] && [ "$3" != 5000 ]; then size=(--count "$3"); tag="$1$3"; fi
    "$bench" "$c" "${size[@]}" --bed "$work/bed_$tag.txt" --write-lammps-data "$work/$tag.data"
    # shellcheck disable=SC2046
    vars="$("$bench" "$c" "${size[@]}" $(steps_args "$c") --lammps-vars 1)"
    # shellcheck disable=SC2046
    /usr/bin/time -v -o "$work/time_sb_${tag}_$t.txt" "$bench" "$c" "${size[@]}" --threads "$t" \
        --bed "$work/bed_$tag.txt" $(steps_args "$c") > "$work/sb_${tag}_$t.txt"
    n="$(field particles "$work/sb_${tag}_$t.txt")"
    steps="$(field steps "$work/sb_${tag}_$t.txt")"
    ours="$(field particle_steps_per_s "$work/sb_${tag}_$t.txt") $(field particle_steps_per_cpu_s "$work/sb_${tag}_$t.txt")"
    # shellcheck disable=SC2086
    report "($tag) ShakerBench, $t thread(s)" ${ours} "$(peak_rss_mb "$work/time_sb_${tag}_$t.txt")"

    if [ "$c" = a ]; then
        lmp_cmd=(lmp -log none -in "$root/validation/lammps/in.damper" -var data "$work/a.data"
            -var out "$work/lammps_series_a.txt" -var every 1000000)
    else
        lmp_cmd=(lmp -log none -in "$root/validation/lammps/in.box5000" -var data "$work/$tag.data")
    fi
    if [ "$t" -gt 1 ]; then
        command -v mpirun > /dev/null || { echo "mpirun not found: skipping LAMMPS x$t"; return; }
        lmp_cmd=(mpirun --allow-run-as-root --oversubscribe -np "$t" "${lmp_cmd[@]}")
    fi
    local theirs="0 0" skin_sb skin_cfg
    skin_sb="$(field skin_m "$work/sb_${tag}_$t.txt")"
    skin_cfg="$(awk '{for (k = 1; k < NF; ++k) if ($k == "-var" && $(k + 1) == "skin") print $(k + 2)}' <<< "$vars")"
    for skin in $(printf '%s\n%s\n' "$skin_cfg" "$skin_sb" | awk '!seen[$1 + 0]++'); do
        local suffix="${tag}_$t"
        [ "$skin" = "$skin_cfg" ] || suffix="${tag}_${t}_adapted"
        # shellcheck disable=SC2046,SC2001
        /usr/bin/time -v -o "$work/time_lmp_$suffix.txt" "${lmp_cmd[@]}" \
            $(sed "s/-var skin [^ ]*/-var skin $skin/" <<< "$vars") > "$work/lmp_$suffix.log"
        local rates
        rates="$(lammps_rates "$work/lmp_$suffix.log" "$n" "$steps")"
        # shellcheck disable=SC2086
        report "($tag) LAMMPS, $t process(es), skin $skin" $rates "$(peak_rss_mb "$work/time_lmp_$suffix.txt")"
        # shellcheck disable=SC2086
        theirs="$(echo $theirs $rates | awk '{print ($3 > $1 ? $3 : $1), ($4 > $2 ? $4 : $2)}')"
    done
    # shellcheck disable=SC2086
    set -- $ours $theirs
    awk -v a="$1" -v b="$2" -v c="$3" -v d="$4" -v label="($tag) ratio ShakerBench / LAMMPS" \
        'BEGIN {printf "%-46s %13.2fx %13.2fx\n", label, a / c, b / d}'
}

uptime
printf '%-46s %14s %14s %10s\n' "run" "p-steps/s" "p-steps/cpu-s" "peak RSS"
[ "${SKIP_A:-0}" = 1 ] || run_case a 1
for count in $counts_b; do
    for t in $threads_b; do run_case b "$t" "$count"; done
done
echo "logs and data: $work"
