#!/usr/bin/env bash
# run_frame.sh -- superjoin against bare CHOLMOD on generated 3D building frames.
#
# For every size: generate a deck (bench/gen_frame.f90), run superjoin once with
# --export-matrix to get the reduced stiffness matrix K.mtx, run superjoin again
# without the export (the timing that counts: phase times from its stderr, wall
# clock, peak resident set), then run bench/cholmod_bare.c on K.mtx (CHOLMOD's
# own analyze + factorize + solve, default settings, and once more with
# superjoin's settings). Prints a table and writes a CSV.
#
# superjoin "order" is CHOLMOD analyze (ordering + symbolic) and "factor" the
# numeric factorization, so superjoin's total is compared with the bare
# analyze + factorize + solve (cholmod_bare's reading of the .mtx file is left
# out: it stands for superjoin's read + assemble).
#
# Run from anywhere; paths are relative to the repository root. See
# doc/performance.md for the figures and how to read them.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=$ROOT/build
SUPERJOIN=${SUPERJOIN:-$BUILD/superjoin}
SUPERJOIN_ARGS=${SUPERJOIN_ARGS:-}
GEN=$BUILD/gen_frame
BARE=$BUILD/cholmod_bare
SCRATCH=${BENCH_DIR:-$BUILD/bench}
CSV=$ROOT/bench/results/frame.csv
SHAPE=tower
REPEAT=1
KEEP=0
DEFAULT_SIZES=(1e3 1e4 1e5 1e6)

usage() {
    cat <<EOF
usage: bench/run_frame.sh [-s SHAPE] [-r N] [-k] [-o CSV] [SIZE...]

  SIZE      number of equations (1e3, 25000, ...) for gen_frame --dofs, or an
            explicit grid NXxNYxNZ (e.g. 12x12x154); default: ${DEFAULT_SIZES[*]}
  -s SHAPE  tower | block | long: building shape for numeric sizes (default tower;
            see gen_frame --help); stiffened: S4 plate with B33 stiffeners joined
            by compliant contacts (bench/gen_stiffened.py)
  -r N      time the plain superjoin run and cholmod_bare N times, keep the
            fastest (default 1)
  -k        keep the decks, listings and K.mtx files in the scratch directory
  -o CSV    CSV output (default bench/results/frame.csv)
  -h        this text

environment: SUPERJOIN (binary, default build/superjoin), SUPERJOIN_ARGS
(extra superjoin options, e.g. "--solver cholmod"), BENCH_DIR (scratch
directory, default build/bench).
needs: gfortran, gcc and CHOLMOD headers/libraries (libsuitesparse-dev) to build
the helpers, /usr/bin/time (Debian package 'time') for the peak memory.
EOF
}

die() { echo "run_frame.sh: $*" >&2; exit 1; }

while getopts ":s:r:ko:h" opt; do
    case $opt in
        s) SHAPE=$OPTARG ;;
        r) REPEAT=$OPTARG ;;
        k) KEEP=1 ;;
        o) CSV=$OPTARG ;;
        h) usage; exit 0 ;;
        :) usage >&2; die "option -$OPTARG needs a value" ;;
        *) usage >&2; die "unknown option -$OPTARG" ;;
    esac
done
shift $((OPTIND - 1))
case $SHAPE in tower | block | long | stiffened) ;; *) die "unknown shape '$SHAPE' (tower, block, long or stiffened)" ;; esac
[[ $REPEAT =~ ^[1-9][0-9]*$ ]] || die "-r needs a positive integer, got '$REPEAT'"
if (($# > 0)); then SIZES=("$@"); else SIZES=("${DEFAULT_SIZES[@]}"); fi
for s in "${SIZES[@]}"; do
    [[ $s =~ ^[0-9]+(\.[0-9]+)?([eE][0-9]+)?$ || $s =~ ^[0-9]+x[0-9]+x[0-9]+$ ]] ||
        die "bad size '$s' (a number such as 1e5, or NXxNYxNZ)"
done

# ------------------------------------------------------------------ tools
# Peak resident set: /usr/bin/time -v if present, else python3's getrusage (the
# fallback adds python's start-up to the wall clock, and the forked child's
# pre-exec python pages, ~10 MB, to the peak: fine at 1e5 and up).
TIMER=
if [[ -x /usr/bin/time ]] && /usr/bin/time -v true >/dev/null 2>&1; then
    TIMER=gnu
elif command -v python3 >/dev/null 2>&1; then
    TIMER=python
    echo "run_frame.sh: /usr/bin/time not found, using python3 getrusage for the peak memory" \
        "(install it with: apt-get install time)" >&2
else
    echo "run_frame.sh: neither /usr/bin/time nor python3 found: peak memory will be NA" \
        "(install GNU time with: apt-get install time)" >&2
fi

build_helpers() {
    mkdir -p "$BUILD"
    if [[ ! -x $GEN || $ROOT/bench/gen_frame.f90 -nt $GEN ]]; then
        echo "run_frame.sh: building $GEN" >&2
        gfortran -O2 "$ROOT/bench/gen_frame.f90" -J "$BUILD" -o "$GEN"
    fi
    if [[ ! -x $BARE || $ROOT/bench/cholmod_bare.c -nt $BARE || $ROOT/src/utils/blas_core.c -nt $BARE ]]; then
        echo "run_frame.sh: building $BARE" >&2
        gcc -O2 -I/usr/include/suitesparse "$ROOT/bench/cholmod_bare.c" "$ROOT/src/utils/blas_core.c" \
            -lcholmod -lsuitesparseconfig -lm -o "$BARE"
    fi
    if [[ ! -x $SUPERJOIN ]]; then
        echo "run_frame.sh: building superjoin" >&2
        cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
        cmake --build "$BUILD" -j2 --target superjoin >/dev/null
    fi
    [[ -x $SUPERJOIN ]] || die "no superjoin binary at $SUPERJOIN"
}

now_ns() { date +%s%N; }

# run_measured PREFIX CMD...: runs CMD with stdout in PREFIX.out, stderr in
# PREFIX.err; sets RC, WALL (seconds) and PEAK_KB (NA if unknown).
run_measured() {
    local prefix=$1 t0 t1
    shift
    RC=0
    t0=$(now_ns)
    case $TIMER in
        gnu) /usr/bin/time -v -o "$prefix.time" "$@" >"$prefix.out" 2>"$prefix.err" || RC=$? ;;
        python)
            python3 - "$prefix.time" "$@" >"$prefix.out" 2>"$prefix.err" <<'PY' || RC=$?
import resource, subprocess, sys
rc = subprocess.call(sys.argv[2:])
with open(sys.argv[1], "w") as f:
    f.write("Maximum resident set size (kbytes): %d\n"
            % resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
sys.exit(rc)
PY
            ;;
        *) "$@" >"$prefix.out" 2>"$prefix.err" || RC=$? ;;
    esac
    t1=$(now_ns)
    WALL=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }')
    PEAK_KB=NA
    if [[ -f $prefix.time ]]; then
        PEAK_KB=$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$prefix.time")
        [[ -n $PEAK_KB ]] || PEAK_KB=NA
    fi
}

# phase NAME FILE: seconds of "superjoin: NAME <s> s" on superjoin's stderr (0 if absent).
phase() { awk -v p="$1" '$1 == "superjoin:" && $2 == p { print $3; f = 1; exit } END { if (!f) print 0 }' "$2"; }
# bare KEY FILE: first number after "time KEY" in cholmod_bare's output.
bare_time() { awk -v k="$1" '$1 == "time" && $2 == k { print $3; exit }' "$2"; }
mb() { awk -v k="$1" 'BEGIN { if (k == "NA") print "NA"; else printf "%.1f", k / 1024 }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "NA" || b == "NA" || b + 0 == 0) print "NA"; else printf "%.3f", a / b }'; }

fail_run() {
    echo "run_frame.sh: $1 failed (exit $RC); last lines of $2:" >&2
    tail -5 "$2" >&2
    exit 1
}

# ------------------------------------------------------------------ main
build_helpers
mkdir -p "$SCRATCH" "$(dirname "$CSV")"
HEADER="shape,size,grid,dofs,equations,nnz,nnz_L,solver,ordering,read_s,assemble_s,order_s,factor_s,solve_s,health_s,recover_s,write_s,other_s,total_s,peak_MB"
HEADER+=",bare_analyze_s,bare_factor_s,bare_solve_s,bare_total_s,bare_peak_MB,bare_cholmod_MB,bare_nnz_L,bare_factor_kind"
HEADER+=",ratio_total,io_share,mem_ratio,bare_sjsettings_total_s,export_run_peak_MB"
echo "$HEADER" >"$CSV"

ROWS=()
for size in "${SIZES[@]}"; do
    shape=$SHAPE
    [[ $size == *x*x* ]] && shape=grid
    dir=$SCRATCH/frame-$shape-$size
    mkdir -p "$dir"
    deck=$dir/frame.deck
    if [[ $size == *x*x* ]]; then
        IFS=x read -r nx ny nz <<<"$size"
        "$GEN" "$nx" "$ny" "$nz" "$deck" 2>"$dir/gen.err" || { cat "$dir/gen.err" >&2; exit 1; }
    elif [[ $SHAPE == stiffened ]]; then
        python3 "$ROOT/bench/gen_stiffened.py" --dofs "$size" "$deck" 2>"$dir/gen.err" || { cat "$dir/gen.err" >&2; exit 1; }
    else
        "$GEN" --dofs "$size" --shape "$SHAPE" "$deck" 2>"$dir/gen.err" || { cat "$dir/gen.err" >&2; exit 1; }
    fi
    # "gen_frame: 12 x 12 x 154 frame: 997920 equations (1242720 nodal DOFs ...)"
    grid=$(awk '{ print $2 "x" $4 "x" $6 }' "$dir/gen.err")
    dofs=$(awk '{ for (i = 1; i <= NF; i++) if ($i == "nodal") { gsub(/\(/, "", $(i - 1)); print $(i - 1) } }' "$dir/gen.err")
    echo "run_frame.sh: $size ($SHAPE $grid, $dofs DOFs): export run" >&2

    # 1. export run (matrix for the bare run; its own time is not the one that counts)
    # shellcheck disable=SC2086
    run_measured "$dir/export" "$SUPERJOIN" $SUPERJOIN_ARGS --export-matrix "$dir/K.mtx" "$deck" -o "$dir/frame.lst"
    ((RC == 0)) || fail_run superjoin "$dir/export.err"
    export_peak=$PEAK_KB

    # 2. plain runs: keep the fastest
    best=
    for ((k = 1; k <= REPEAT; k++)); do
        echo "run_frame.sh: $size: superjoin run $k/$REPEAT" >&2
        # shellcheck disable=SC2086
        run_measured "$dir/run" "$SUPERJOIN" $SUPERJOIN_ARGS "$deck" -o "$dir/frame.lst"
        ((RC == 0)) || fail_run superjoin "$dir/run.err"
        if [[ -z $best ]] || awk -v a="$WALL" -v b="$best" 'BEGIN { exit !(a < b) }'; then
            best=$WALL
            cp "$dir/run.err" "$dir/best.err"
            sj_peak=$PEAK_KB
        fi
    done
    f=$dir/best.err
    t_read=$(phase read "$f"); t_asm=$(phase assemble "$f"); t_order=$(phase order "$f")
    t_factor=$(phase factor "$f"); t_solve=$(phase solve "$f"); t_write=$(phase write "$f")
    t_health=$(phase health "$f"); t_recover=$(phase recover "$f")
    # assemble line: "equations N, nonzeros M"; factor line: "NAME, factor nonzeros L"
    neq=$(awk '$2 == "assemble" { gsub(/,/, ""); for (i = 1; i <= NF; i++) if ($i == "equations") print $(i + 1) }' "$f")
    nnz=$(awk '$2 == "assemble" { for (i = 1; i <= NF; i++) if ($i == "nonzeros") print $(i + 1) }' "$f")
    nnzl=$(awk '$2 == "factor" { for (i = 1; i <= NF; i++) if ($i == "nonzeros") print $(i + 1) }' "$f")
    solver=$(awk '$2 == "factor" { s = $5; for (i = 6; i <= NF && $i !~ /,$/; i++) s = s " " $i; if (i <= NF) s = s " " $i; sub(/,$/, "", s); print s }' "$f")
    ordering=$(awk '$2 == "order" { s = $5; for (i = 6; i <= NF; i++) s = s " " $i; print s }' "$f")
    total=$best
    other=$(awk -v t="$total" -v a="$t_read" -v b="$t_asm" -v c="$t_order" -v d="$t_factor" -v e="$t_solve" \
        -v g="$t_write" -v h="$t_health" -v r="$t_recover" \
        'BEGIN { o = t - a - b - c - d - e - g - h - r; printf "%.3f", (o < 0 ? 0 : o) }')

    # 3. bare CHOLMOD, default settings: keep the fastest analyze+factor+solve
    bare_best=
    for ((k = 1; k <= REPEAT; k++)); do
        echo "run_frame.sh: $size: cholmod_bare run $k/$REPEAT" >&2
        run_measured "$dir/bare" "$BARE" "$dir/K.mtx"
        ((RC == 0)) || fail_run cholmod_bare "$dir/bare.err"
        bt=$(awk -v a="$(bare_time analyze "$dir/bare.out")" -v b="$(bare_time factor "$dir/bare.out")" \
            -v c="$(bare_time solve "$dir/bare.out")" 'BEGIN { printf "%.4f", a + b + c }')
        if [[ -z $bare_best ]] || awk -v a="$bt" -v b="$bare_best" 'BEGIN { exit !(a < b) }'; then
            bare_best=$bt
            cp "$dir/bare.out" "$dir/bare_best.out"
            bare_peak=$PEAK_KB
        fi
    done
    bo=$dir/bare_best.out
    b_an=$(bare_time analyze "$bo"); b_fa=$(bare_time factor "$bo"); b_so=$(bare_time solve "$bo")
    b_cm=$(awk '$1 == "peak" && $2 == "CHOLMOD" { print $3 }' "$bo")
    b_hwm=$(awk '$1 == "peak" && $2 == "VmHWM" { printf "%.0f", $3 * 1024 }' "$bo")
    [[ $bare_peak == NA ]] && bare_peak=${b_hwm:-NA}
    b_nnzl=$(awk '$1 == "nnz(L)" { print $2 }' "$bo")
    b_kind=$(awk '$1 == "factor" { print $2 " " $3 }' "$bo")

    # 4. bare CHOLMOD with superjoin's settings (supernodal LL^T), for reference
    echo "run_frame.sh: $size: cholmod_bare --superjoin" >&2
    run_measured "$dir/bare_sj" "$BARE" --superjoin "$dir/K.mtx"
    ((RC == 0)) || fail_run "cholmod_bare --superjoin" "$dir/bare_sj.err"
    bsj=$(awk -v a="$(bare_time analyze "$dir/bare_sj.out")" -v b="$(bare_time factor "$dir/bare_sj.out")" \
        -v c="$(bare_time solve "$dir/bare_sj.out")" 'BEGIN { printf "%.4f", a + b + c }')

    ratio_total=$(ratio "$total" "$bare_best")
    io_share=$(awk -v t="$total" -v a="$t_read" -v b="$t_asm" -v g="$t_write" 'BEGIN { printf "%.3f", (a + b + g) / t }')
    mem_ratio=$(ratio "$sj_peak" "$bare_peak")
    row="$shape,$size,$grid,$dofs,$neq,$nnz,$nnzl,$solver,$ordering,$t_read,$t_asm,$t_order,$t_factor,$t_solve,$t_health,$t_recover,$t_write,$other,$total,$(mb "$sj_peak")"
    row+=",$b_an,$b_fa,$b_so,$bare_best,$(mb "$bare_peak"),$b_cm,$b_nnzl,$b_kind"
    row+=",$ratio_total,$io_share,$mem_ratio,$bsj,$(mb "$export_peak")"
    echo "$row" >>"$CSV"
    ROWS+=("$row")
    ((KEEP == 1)) || rm -f "$dir/K.mtx" "$dir/frame.deck" "$dir/frame.lst"
done

# ------------------------------------------------------------------ table
echo
echo "$("$SUPERJOIN" --version 2>/dev/null | head -1) vs bare CHOLMOD; shape $SHAPE; $(nproc) cores; times in s, memory in MB"
printf '%-6s %-10s %8s %9s %9s | %5s %5s %5s %6s %5s %5s %5s %5s %5s %6s %7s | %6s %6s | %6s %5s %5s\n' \
    size grid equations nnz "nnz(L)" read asm order factor solve hlth recov write other total peakMB \
    bare bareMB ratio io mem
for row in "${ROWS[@]}"; do
    IFS=, read -r -a c <<<"$row"
    printf '%-6s %-10s %8s %9s %9s | %5.2f %5.2f %5.2f %6.2f %5.2f %5.2f %5.2f %5.2f %5.2f %6.2f %7s | %6.2f %6s | %6s %5s %5s\n' \
        "${c[1]}" "${c[2]}" "${c[4]}" "${c[5]}" "${c[6]}" "${c[9]}" "${c[10]}" "${c[11]}" "${c[12]}" "${c[13]}" \
        "${c[14]}" "${c[15]}" "${c[16]}" "${c[17]}" "${c[18]}" "${c[19]}" "${c[23]}" "${c[24]}" "${c[28]}" "${c[29]}" "${c[30]}"
done
echo "bare = cholmod_bare analyze+factorize+solve (CHOLMOD defaults); ratio = total/bare (target <= 1.3);"
echo "io = (read+assemble+write)/total (target <= 0.2); mem = peak/bare peak (target <= 1.5);"
echo "hlth/recov = health checks and result recovery; other = wall - listed phases (start-up, exit)."
echo "CSV: $CSV"
