#!/usr/bin/env bash
# Install the Debian packages superjoin needs, if any is missing.
# usage: deps.sh [--test] [--freecad] [--bench] [--mumps | --mpi]
#   (no option)  what building and running the solver needs (tools/build.sh, tools/demo)
#   --test       also what the test suite uses: Python, gnuplot (tools/render,
#                ctest render.png), valgrind, CalculiX GraphiX (ctest ccx.frd_cgx)
#   --freecad    also FreeCAD's freecadcmd and CalculiX (ctest ccx.freecad_dropin, skipped
#                without them: FreeCAD's install alone takes minutes, beyond tools/test's budget)
#   --bench      also what the benchmarks use (bench/): Python, GNU time,
#                CalculiX (cross-checks); no test runs them
#   --mumps      also sequential MUMPS (cmake -DSUPERJOIN_MUMPS=ON)
#   --mpi        also Open MPI and MUMPS with PT-SCOTCH (cmake -DSUPERJOIN_MPI=ON)
set -euo pipefail
packages=(gfortran gcc cmake make liblapack-dev libopenblas-dev libsuitesparse-dev libmetis-dev)
for opt in "$@"; do
  case "$opt" in
    --test) packages+=(python3 gnuplot-nox valgrind calculix-cgx) ;;
    --freecad) packages+=(freecad-python3 calculix-ccx) ;;
    --bench) packages+=(python3 time calculix-ccx) ;;
    --mumps) packages+=(libmumps-seq-dev) ;;
    --mpi) packages+=(openmpi-bin libopenmpi-dev libmumps-ptscotch-dev) ;;
    *) echo "usage: deps.sh [--test] [--freecad] [--bench] [--mumps | --mpi]" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "superjoin: installing ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then SUDO=""; elif command -v sudo >/dev/null; then SUDO="sudo"; else
  echo "superjoin: need root to install: ${missing[*]}" >&2; exit 1; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
