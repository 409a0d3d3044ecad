#!/usr/bin/env bash
# design.md: the leaf modules (dem, structure, control, identification) never include each
# other, nor bench/ or correlation/; bench/ never includes correlation/. Prints offenders.
set -euo pipefail
cd "$(dirname "$0")/.."

status=0
check() {  # check FOLDER FORBIDDEN...
    local folder=$1; shift
    [[ -d "$folder" ]] || return 0
    for other in "$@"; do
        if hits=$(grep -rnE "#include [\"<]${other}/" "$folder" --include='*.hpp' --include='*.cpp' --include='*.h'); then
            echo "architecture: $folder/ must not include $other/:"; echo "$hits"; status=1
        fi
    done
}
leaves=(dem structure control identification)
for leaf in "${leaves[@]}"; do
    others=()
    for o in "${leaves[@]}" bench correlation apps; do [[ "$o" != "$leaf" ]] && others+=("$o"); done
    check "$leaf" "${others[@]}"
done
check core dem structure control identification bench correlation apps
check bench correlation apps
check correlation apps
[[ $status -eq 0 ]] && echo "architecture: ok"
exit $status
