#!/usr/bin/env bash
# Installs the Debian packages ShakerBench needs, only those that are missing.
# Usage: scripts/install-deps.sh [--test | --mpi]   (--test adds what the test suite and the
# fuzz targets need, OpenMPI included; --mpi adds OpenMPI alone, for the SB_WITH_MPI build of
# docs/cluster.md)
set -euo pipefail

# gnuplot draws the campaign's SVG plots: the main job needs it as much as the tests do.
packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libspectra-dev libfftw3-dev libnlopt-cxx-dev
          libtomlplusplus-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
          gnuplot-nox)
mpi=(openmpi-bin libopenmpi-dev)
if [[ "${1:-}" == "--test" ]]; then
    # clang with libFuzzer and its OpenMP runtime: the 'fuzz' preset (scripts/fuzz.sh). The
    # ci build runs with SB_WITH_MPI: a test runs mpirun -np 2.
    packages+=(clang-format lammps time clang libclang-rt-14-dev libomp-dev "${mpi[@]}")
elif [[ "${1:-}" == "--mpi" ]]; then
    packages+=("${mpi[@]}")
elif [[ -n "${1:-}" ]]; then
    echo "install-deps: unknown option '$1' (use --test or --mpi)" >&2
    exit 2
fi

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done

if ((${#missing[@]} == 0)); then
    echo "install-deps: all ${#packages[@]} packages present"
    exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then
    sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
