#!/usr/bin/env bash
# docs/architecture.md: the leaf modules (dem, structure, control,
# identification) never include each other, nor config/, bench/, distributed/, correlation/ or
# apps/; config/ sees only core/; bench/ never includes distributed/ or correlation/;
# distributed/ never includes correlation/; only config/ sees toml++ (its sources, never its
# public headers), apart from identification's recording.toml reader; only
# distributed/session.cpp sees MPI. Prints the offenders.
set -euo pipefail
cd "$(dirname "$0")/.."

status=0
sources() { grep -rnE "$1" "${@:2}" --include='*.hpp' --include='*.cpp' --include='*.h' || true; }

check() {  # check FOLDER FORBIDDEN...
    local folder=$1; shift
    [[ -d "$folder" ]] || return 0
    for other in "$@"; do
        hits=$(sources "#include [\"<]${other}/" "$folder")
        if [[ -n "$hits" ]]; then
            echo "architecture: $folder/ must not include $other/:"; echo "$hits"; status=1
        fi
    done
}
leaves=(dem structure control identification)
for leaf in "${leaves[@]}"; do
    others=()
    for o in "${leaves[@]}" config bench distributed correlation apps; do [[ "$o" != "$leaf" ]] && others+=("$o"); done
    check "$leaf" "${others[@]}"
done
check core dem structure control identification config bench distributed correlation apps
check config dem structure control identification bench distributed correlation apps
check bench distributed correlation apps
check distributed correlation apps
check correlation apps

# toml++: config/'s sources and its internal config/toml_tree.hpp, and identification's
# reader of recording.toml (a data file, not a config).
hits=$(sources '#include [<"]toml\+\+' core dem structure control identification config bench \
           correlation apps perf tests fuzz \
       | grep -vE '^config/[a-z_]+\.cpp:|^config/toml_tree\.hpp:|^identification/recording_toml\.cpp:' \
       || true)
if [[ -n "$hits" ]]; then
    echo "architecture: only config/ (its sources) may include toml++:"; echo "$hits"; status=1
fi
hits=$(sources '#include "config/toml_tree\.hpp"' core dem structure control identification config \
           bench correlation apps perf tests fuzz | grep -vE '^config/[a-z_]+\.cpp:' || true)
if [[ -n "$hits" ]]; then
    echo "architecture: config/toml_tree.hpp is internal to config/:"; echo "$hits"; status=1
fi

# MPI: distributed/session.cpp alone (a build without MPI compiles it without).
hits=$(sources '#include [<"]mpi\.h' core dem structure control identification config bench \
           distributed correlation apps perf tests | grep -vE '^distributed/session\.cpp:' || true)
if [[ -n "$hits" ]]; then
    echo "architecture: only distributed/session.cpp may include mpi.h:"; echo "$hits"; status=1
fi

[[ $status -eq 0 ]] && echo "architecture: ok"
exit $status
