#!/usr/bin/env bash
# Configure and build superjoin into build/ (Release). Extra arguments go to cmake.
# With -DSUPERJOIN_MPI=ON the build goes to build-mpi/, with -DSUPERJOIN_MUMPS=ON
# to build-mumps/, after installing the packages they need (tools/deps.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=build; deps=()
for arg in "$@"; do
  case "$arg" in
    -DSUPERJOIN_MPI=ON) dir=build-mpi; deps+=(--mpi) ;;
    -DSUPERJOIN_MUMPS=ON) [ "$dir" = build ] && dir=build-mumps; deps+=(--mumps) ;;
  esac
done
bash "$root/tools/deps.sh" "${deps[@]}"
cmake -S "$root" -B "$root/$dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$root/$dir" -j"$(nproc)"
