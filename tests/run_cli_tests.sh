#!/usr/bin/env bash
# Command-line behaviour: options, exit statuses, no listing on failure.
# usage: run_cli_tests.sh SUPERJOIN SOURCE_DIR WORK_DIR
set -u
bin=$1; src=$2; work=$3
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
pass=0; fail=0
expect() {  # expect STATUS DESCRIPTION -- command...
  local want=$1 what=$2; shift 3
  "$@" >out.txt 2>err.txt; local rc=$?
  if [ "$rc" -eq "$want" ] && ! grep -qiE 'runtime error|backtrace|segmentation' err.txt; then pass=$((pass+1))
  else fail=$((fail+1)); echo "FAIL: $what: status $rc (want $want)"; cat err.txt; fi
}
expect 0 "help" -- "$bin" --help
grep -q -- '--formulation' out.txt || { fail=$((fail+1)); echo "FAIL: --help lacks options"; }
expect 0 "version" -- "$bin" --version
expect 2 "unknown option" -- "$bin" --frobnicate
expect 2 "option without value" -- "$bin" -o
expect 2 "unknown solver" -- "$bin" --solver magic "$src/decks/demo.deck"
expect 2 "unknown formulation" -- "$bin" --formulation x "$src/decks/demo.deck"
expect 2 "two decks" -- "$bin" a.deck b.deck
expect 4 "missing deck" -- "$bin" no_such.deck
expect 0 "check only" -- "$bin" -q --check "$src/decks/demo.deck" -o check.lst
[ ! -e check.lst ] || { fail=$((fail+1)); echo "FAIL: --check wrote a listing"; }
expect 0 "demo without deck" -- "$bin" -q
"$bin" 2>err.txt >/dev/null
grep -q 'no deck given: solving the bundled demo deck' err.txt || { fail=$((fail+1)); echo "FAIL: demo run does not say what it solves"; }
grep -q 'listing written to demo.lst' err.txt || { fail=$((fail+1)); echo "FAIL: demo run does not say where the listing went"; }
[ -s demo.lst ] || { fail=$((fail+1)); echo "FAIL: no demo.lst"; }
grep -q 'END OF LISTING' demo.lst || { fail=$((fail+1)); echo "FAIL: demo listing incomplete"; }
# FreeCAD accepts a CalculiX binary only if its no-argument run prints CalculiX on stdout
"$bin" >out.txt 2>/dev/null
grep -q 'CalculiX' out.txt || { fail=$((fail+1)); echo "FAIL: the no-argument run does not name CalculiX on stdout"; }
# As ccx -i JOB (FreeCAD passes "-i " with a blank): JOB.dat, .frd, .sta, the listing, an empty stderr
sed -n '1,/^\*STEP/p' "$src/tests/ccx/truss.inp" > job.inp
printf '*STATIC\n*CLOAD\n2,1,1.\n*NODE PRINT,NSET=NALL\nU\n*NODE FILE\nU\n*END STEP\n' >> job.inp
expect 0 "ccx -i" -- "$bin" "-i " job
# (gfortran's -fcheck=all of the Debug build reports array temporaries on stderr: not the program's output)
grep -v -e '^At line [0-9]* of file ' -e '^Fortran runtime warning: An array temporary was created$' err.txt > err_program.txt
[ ! -s err_program.txt ] && grep -q 'Job finished' out.txt || { fail=$((fail+1)); echo "FAIL: -i: stderr not empty or no Job finished"; }
for f in job.dat job.frd job.sta job.lst; do [ -s $f ] || { fail=$((fail+1)); echo "FAIL: -i wrote no $f"; }; done
# -i reads a CalculiX deck: one-value SECTION=CIRC is the diameter (issue 25 item 2), said in the
# listing; the same beam with Abaqus's radius 1.0 in a plain run must move the same
printf '*NODE, NSET=NALL\n1,0,0,0\n2,10,0,0\n*ELEMENT,TYPE=B31,ELSET=EB\n1,1,2\n*MATERIAL,NAME=S\n*ELASTIC\n1000.,0.3\n*BEAM SECTION,ELSET=EB,MATERIAL=S,SECTION=CIRC\n%s\n0,0,1\n*BOUNDARY\n1,1,6\n*STEP\n*STATIC\n*CLOAD\n2,2,1e-3\n*END STEP\n' 2.0 > circ.inp
sed 's/^2.0$/1.0/' circ.inp > circ_r.inp
expect 0 "ccx -i circ" -- "$bin" -i circ
expect 0 "circ radius" -- "$bin" -q circ_r.inp -o circ_r.lst
grep -q 'one value, read as the diameter (ccx -i reads a CalculiX deck' circ.lst || { fail=$((fail+1)); echo "FAIL: -i does not say it read CIRC as the diameter"; }
[ "$(sed -n '/^DISPLACEMENTS/,/^$/p' circ.lst)" = "$(sed -n '/^DISPLACEMENTS/,/^$/p' circ_r.lst)" ] && grep -q '^DISPLACEMENTS' circ.lst || { fail=$((fail+1)); echo "FAIL: -i CIRC 2.0 does not move as radius 1.0"; }
expect 4 "ccx -i missing job" -- "$bin" -i no_such_job
expect 2 "ccx -i without job" -- "$bin" -i
for s in cholmod umfpack lapack; do
  expect 0 "solver $s" -- "$bin" -q --solver $s "$src/decks/demo.deck" -o demo_$s.lst
done
# MUMPS: solves when built in, otherwise a usage error naming the cmake option
if "$bin" --solver mumps --version >/dev/null 2>&1; then
  for s in mumps mumps-ldlt; do
    expect 0 "solver $s" -- "$bin" -q --solver $s "$src/decks/demo.deck" -o demo_$s.lst
  done
else
  expect 2 "solver mumps not built" -- "$bin" -q --solver mumps "$src/decks/demo.deck" -o demo_mumps.lst
  grep -q 'SUPERJOIN_MUMPS=ON' err.txt || { fail=$((fail+1)); echo "FAIL: --solver mumps without MUMPS does not say how to build it"; }
fi
# Under PENALTY the demo's RIGID joints get the default g = k/sqrt(eps): solved
# (exit 0), the MAXRATIO warning printed also under -q, the g range in the notes.
for d in "$src"/decks/*.deck; do
  expect 0 "penalty $(basename "$d")" -- "$bin" -q --formulation penalty "$d" -o pen.lst
done
expect 0 "penalty" -- "$bin" -q --formulation penalty "$src/decks/demo.deck" -o pen.lst
grep -q 'warning: MAXRATIO' err.txt || { fail=$((fail+1)); echo "FAIL: -q hid the MAXRATIO warning"; }
grep -q '1/sqrt(epsilon)' pen.lst || { fail=$((fail+1)); echo "FAIL: penalty default g not in the notes"; }
# LARGE=1e12 given explicitly: numerically singular (MAXRATIO past 1e13), refused
# with a hint on the formulation.
sed '1i *CONTROLS, RIGID=LARGE, LARGE=1e12' "$src/decks/demo.deck" > large.deck
expect 3 "penalty LARGE=1e12" -- "$bin" -q --formulation penalty large.deck -o pen.lst
grep -q 'under PENALTY' err.txt || { fail=$((fail+1)); echo "FAIL: penalty breakdown without the formulation hint"; }
# LARGE=1e10: solved, but the residual judges it inaccurate: exit 5, listing
# written, the warning shown under -q; --accept-inaccurate makes it 0.
sed '1i *CONTROLS, RIGID=LARGE, LARGE=1e10' "$src/decks/demo.deck" > large.deck
rm -f pen.lst
expect 5 "inaccurate" -- "$bin" -q --formulation penalty large.deck -o pen.lst
grep -q 'warning: relative residual' err.txt || { fail=$((fail+1)); echo "FAIL: -q hid the residual warning"; }
grep -q 'error: the results are judged inaccurate' err.txt || { fail=$((fail+1)); echo "FAIL: no exit-5 message"; }
grep -q 'END OF LISTING' pen.lst || { fail=$((fail+1)); echo "FAIL: exit 5 without the listing"; }
expect 0 "accept inaccurate" -- "$bin" -q --accept-inaccurate --formulation penalty large.deck -o pen.lst
grep -q 'warning: relative residual' err.txt || { fail=$((fail+1)); echo "FAIL: --accept-inaccurate hid the warning"; }
# A joint study whose second value (g = 0) releases the joint into a hinge: never
# exit 0. The Release build factors the hinge and its residual (2.6) judges the
# run inaccurate although the first value's does not (exit 5; before 2026-11-29
# the doubt of any group of steps after the first was dropped when the groups'
# results were merged: exit 0); the Debug build's round-off finds the mechanism
# (exit 3). Either way the listing holds the values solved.
"${PYTHON:-python3}" "$src/bench/gen_panels.py" --mesh 6 --values 1e4,0,1e7 > release.deck
for how in "--condense yes" "--condense no"; do
  rm -f rel.lst
  "$bin" -q $how release.deck -o rel.lst >out.txt 2>err.txt; rc=$?
  case $rc in
    5) grep -q 'error: the results are judged inaccurate' err.txt && pass=$((pass+1)) ||
         { fail=$((fail+1)); echo "FAIL: joint study $how: exit 5 without its message"; } ;;
    3) grep -q 'mechanism' err.txt && pass=$((pass+1)) ||
         { fail=$((fail+1)); echo "FAIL: joint study $how: exit 3 without a mechanism"; } ;;
    *) fail=$((fail+1)); echo "FAIL: joint study $how releasing its joint: status $rc (want 5, or 3 for a mechanism)" ;;
  esac
  grep -q 'END OF LISTING' rel.lst || { fail=$((fail+1)); echo "FAIL: joint study $how: no listing"; }
done
# A turned instance sharing a condensation: its interior's direction without
# stiffness is the turned one (tests/parts/turned_free_direction.deck): a load
# along Z on B.3 is carried, as in the monolithic run; one along Y is refused.
expect 0 "turned instance, load on a stiff direction" -- "$bin" -q --condense yes "$src/tests/parts/turned_free_direction.deck" -o tf.lst --csv tfc
expect 0 "turned instance, monolithic" -- "$bin" -q --condense no "$src/tests/parts/turned_free_direction.deck" -o tfm.lst --csv tfm
[ "$(grep '^1,B,3,' tfc/displacements.csv | cut -d, -f6 | cut -c1-12)" = "$(grep '^1,B,3,' tfm/displacements.csv | cut -d, -f6 | cut -c1-12)" ] \
  || { fail=$((fail+1)); echo "FAIL: turned instance: B.3's u3 condensed differs from monolithic"; }
sed 's/^B.3, 3, 1000.0/B.3, 2, 1000.0/' "$src/tests/parts/turned_free_direction.deck" > tf_free.deck
expect 3 "turned instance, load on its direction without stiffness" -- "$bin" -q --condense yes tf_free.deck -o tf2.lst
grep -q 'load on a DOF without stiffness: substructure B node 3 DOF 3 in the axes of its part' err.txt \
  || { fail=$((fail+1)); echo "FAIL: turned instance: the load on its free direction not refused as such"; }
expect 0 "export matrix" -- "$bin" -q --export-matrix k.mtx "$src/decks/demo.deck" -o mm.lst
head -1 k.mtx | grep -q '%%MatrixMarket matrix coordinate real symmetric' || { fail=$((fail+1)); echo "FAIL: matrix market header"; }
expect 0 "csv" -- "$bin" -q "$src/decks/demo.deck" -o c.lst --csv csvdir
for f in displacements reactions contact_forces element_forces; do
  [ -s csvdir/$f.csv ] || { fail=$((fail+1)); echo "FAIL: no $f.csv"; }
done
head -1 csvdir/nodes.csv | grep -qx 'substructure,node,x,y,z' || { fail=$((fail+1)); echo "FAIL: nodes.csv header"; }
[ "$(tail -n +2 csvdir/nodes.csv | cut -d, -f1,2 | sort)" = "$(tail -n +2 csvdir/displacements.csv | cut -d, -f2,3 | sort -u)" ] \
  || { fail=$((fail+1)); echo "FAIL: nodes.csv does not list the nodes of displacements.csv"; }
head -1 csvdir/displacements.csv | grep -qx 'step,substructure,node,u1,u2,u3,ur1,ur2,ur3' || { fail=$((fail+1)); echo "FAIL: csv header"; }
# Plausibility: the demo with E in MPa (lengths in m) sways 2.7 km on a 7 m
# frame: a warning naming the node and what to check, also under -q; exit 0.
sed 's/^2\.1e11,/2.1e5,/' "$src/decks/demo.deck" > mpa.deck
expect 0 "units mix-up" -- "$bin" -q mpa.deck -o mpa.lst
grep -q "warning: step WIND: displacement 2.67E+003 at COLL.5 is 3.70E+002 times the model's size 7.21E+000" err.txt \
  || { fail=$((fail+1)); echo "FAIL: no plausibility warning"; cat err.txt; }
grep -q 'Check the units' mpa.lst || { fail=$((fail+1)); echo "FAIL: plausibility warning not in the listing"; }
# Contact node pairs far apart: the hinge deck with S3 moved by 0.5 along x
# (and its hinge made rigid): one warning per contact, with the count and the
# farthest pair; POSITION TOLERANCE=0.2 (x the model's size 4.5) silences it.
sed -e 's/^1, 3, 0$/1, 3.5, 0/' -e 's/^2, 4, 0$/2, 4.5, 0/' -e 's/^2, 1, 6, 6, 0\.$/2, 1, 6, 6, RIGID/' \
  "$src/tests/singular/hinge_three_parts.deck" | grep -v '^\*\*' > gap.deck
expect 0 "contact gap" -- "$bin" -q gap.deck -o gap.lst
grep -q "warning: contact HINGE: 1 of 1 node pair(s) farther apart than 4.50E-003 (1.0E-003 x the model's size), the farthest S2.2 - S3.1 at 5.00E-001" err.txt \
  || { fail=$((fail+1)); echo "FAIL: no contact gap warning"; cat err.txt; }
[ "$(grep -c 'warning: contact' err.txt)" -eq 1 ] || { fail=$((fail+1)); echo "FAIL: contact J12 (coincident) warned"; }
grep -c 'WARNING: contact HINGE' gap.lst | grep -qx 1 || { fail=$((fail+1)); echo "FAIL: contact gap warning not once in the listing"; }
expect 0 "contact gap, --check" -- "$bin" -q --check gap.deck
grep -q "warning: contact HINGE: 1 of 1 node pair" err.txt || { fail=$((fail+1)); echo "FAIL: --check without the contact gap warning"; }
sed 's/^2, 1, 6, 6, RIGID$/2, 1, 6, 6, 0./' gap.deck > gap3.deck
expect 3 "contact gap and a mechanism" -- "$bin" -q gap3.deck -o gap3.lst
grep -q "warning: contact HINGE: 1 of 1 node pair" err.txt || { fail=$((fail+1)); echo "FAIL: a failed run without the contact gap warning"; }
sed '1i *CONTROLS, POSITION TOLERANCE=0.2' gap.deck > gap2.deck
expect 0 "contact gap within tolerance" -- "$bin" -q gap2.deck -o gap.lst
[ ! -s err.txt ] || { fail=$((fail+1)); echo "FAIL: warned within POSITION TOLERANCE"; cat err.txt; }
# progress on stderr unless quiet
"$bin" "$src/decks/demo.deck" -o p.lst 2>err.txt >/dev/null
grep -q 'superjoin: factor' err.txt || { fail=$((fail+1)); echo "FAIL: no phase report on stderr"; }
"$bin" -q "$src/decks/demo.deck" -o p.lst 2>err.txt >/dev/null
[ ! -s err.txt ] || { fail=$((fail+1)); echo "FAIL: -q still printed"; cat err.txt; }
# A failing run keeps the previous good listing and leaves no temporary file.
cp "$src/decks/demo.deck" x.deck
"$bin" -q x.deck -o x.lst
printf '*NODE\n1, 0, 0\n*SUPPORT\n1, 6, 6\n*CLOAD\n1, 1, 5.0\n' > y.deck
cp x.lst y.lst
expect 3 "mechanism" -- "$bin" -q y.deck -o y.lst
cmp -s x.lst y.lst || { fail=$((fail+1)); echo "FAIL: failed run touched the previous listing"; }
# A mechanism's mode goes to the VTK and CSV outputs asked for: the hinge of
# tests/singular/hinge_three_parts.deck, S3 rotating about S3.1.
expect 3 "mechanism mode files" -- "$bin" -q "$src/tests/singular/hinge_three_parts.deck" -o h.lst --vtk hv/h --csv hc
grep -q 'the mode is written to hv/h_mechanism.vtu hc/mechanism.csv' err.txt || { fail=$((fail+1)); echo "FAIL: mode files not named"; }
grep -qx 'S3,2,0,1.0000000000000000E+000,0,0,0,1.0000000000000000E+000' hc/mechanism.csv || { fail=$((fail+1)); echo "FAIL: mechanism.csv S3.2"; cat hc/mechanism.csv; }
grep -qx 'S1,3,0,0,0,0,0,0' hc/mechanism.csv || { fail=$((fail+1)); echo "FAIL: mechanism.csv: the fixed part moves"; }
grep -q 'Name="mechanism"' hv/h_mechanism.vtu || { fail=$((fail+1)); echo "FAIL: no mechanism array in the VTU"; }
[ ! -e h.lst ] || { fail=$((fail+1)); echo "FAIL: a mechanism run wrote a listing"; }
ls *.tmp >/dev/null 2>&1 && { fail=$((fail+1)); echo "FAIL: temporary files left"; }
# Outputs are renamed over their names: never over a device or a FIFO, and a
# symbolic link keeps pointing at its (rewritten) file.
mkfifo fifo.lst 2>/dev/null || true
expect 4 "fifo output" -- "$bin" -q "$src/decks/demo.deck" -o fifo.lst
grep -q 'is not a regular file' err.txt || { fail=$((fail+1)); echo "FAIL: fifo output without a message"; }
[ -p fifo.lst ] || { fail=$((fail+1)); echo "FAIL: the fifo was replaced"; }
echo old > target.lst; ln -sf target.lst link.lst
expect 0 "symlink output" -- "$bin" -q "$src/decks/demo.deck" -o link.lst
[ -L link.lst ] || { fail=$((fail+1)); echo "FAIL: the symbolic link was replaced"; }
grep -q 'END OF LISTING' target.lst || { fail=$((fail+1)); echo "FAIL: the link's file was not written"; }
# Load combinations with output requests: the envelope lists every element's
# end forces, also those of elements no *EL PRINT names and no support or
# contact touches (they were listed as zero).
comb_deck() {
  printf '*NODE\n1, 0, 0\n2, 1, 0\n3, 2, 0\n4, 3, 0\n5, 4, 0\n'
  printf '*ELEMENT, TYPE=B23, ELSET=BEAM\n1, 1, 2\n2, 2, 3\n3, 3, 4\n4, 4, 5\n*ELSET, ELSET=E1\n 1\n'
  printf '*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL\n5.0e-3, 8.0e-5\n'
  printf '*BOUNDARY\n 1, 1, 2\n 5, 2, 2\n*STEP, NAME=G\n%b*DLOAD\n BEAM, PY, -2000.0\n*END STEP\n' "$1"
  printf '*STEP, NAME=Q\n*CLOAD\n 3, 2, -9000.0\n*END STEP\n'
  printf '*LOAD COMBINATION, NAME=ULS\n G, 1.35\n Q, 1.5\n*LOAD COMBINATION, NAME=UPLIFT\n G, 0.9\n Q, -1.5\n'
}
comb_deck '*EL PRINT, ELSET=E1\n S\n' > combreq.deck
comb_deck '' > comb.deck
expect 0 "combinations with requests" -- "$bin" -q combreq.deck -o combreq.lst
expect 0 "combinations without requests" -- "$bin" -q comb.deck -o comb.lst
sed -n '/^ENVELOPE OF THE LOAD COMBINATIONS/,/^END OF LISTING/p' comb.lst > comb.env
sed -n '/^ENVELOPE OF THE LOAD COMBINATIONS/,/^END OF LISTING/p' combreq.lst > combreq.env
grep -q 'element results listed for 1 of 4' combreq.lst || { fail=$((fail+1)); echo "FAIL: combreq.lst: no note on the listed elements"; }
[ -s comb.env ] && cmp -s comb.env combreq.env || { fail=$((fail+1)); echo "FAIL: the envelope differs with requests"; diff comb.env combreq.env | head; }
# A deck read from a pipe or a FIFO (a shell's <(...), mkfifo): read to its end, solved as
# the same file would be (a stream read of its unknown size read nothing before)
expect 0 "deck from a pipe" -- "$bin" -q <(cat "$src/decks/demo.deck") -o pipe.lst
expect 0 "deck as a file" -- "$bin" -q "$src/decks/demo.deck" -o file.lst
[ "$(sed -n '/^DISPLACEMENTS/,$p' pipe.lst)" = "$(sed -n '/^DISPLACEMENTS/,$p' file.lst)" ] && grep -q '^DISPLACEMENTS' file.lst ||
  { fail=$((fail+1)); echo "FAIL: the deck read from a pipe does not solve as the file"; }
rm -f deck.fifo && mkfifo deck.fifo && { timeout 60 sh -c "cat '$src/decks/demo.deck' > deck.fifo" & }
expect 0 "deck from a FIFO" -- timeout 60 "$bin" -q deck.fifo -o fifodeck.lst
wait
[ "$(sed -n '/^DISPLACEMENTS/,$p' fifodeck.lst)" = "$(sed -n '/^DISPLACEMENTS/,$p' file.lst)" ] ||
  { fail=$((fail+1)); echo "FAIL: the deck read from a FIFO does not solve as the file"; }
# OpenBLAS's kernels (utils/blas_core.c): -v names them; a user's OPENBLAS_CORETYPE stands;
# without it, on a CPU with AVX2 and FMA, never kernels older than AVX2 (Debian 12's OpenBLAS
# takes newer CPUs than it knows for Prescott: superjoin starts again with OPENBLAS_CORETYPE,
# and keeps its own name doing so).
if env -u OPENBLAS_CORETYPE "$bin" -v --check "$src/decks/demo.deck" 2>err.txt >/dev/null &&
   grep -q '^superjoin: BLAS: OpenBLAS kernels' err.txt; then
  OPENBLAS_CORETYPE=Haswell "$bin" -v --check "$src/decks/demo.deck" 2>err2.txt >/dev/null
  grep -q 'built for this one CPU type' err.txt ||
    grep -q '^superjoin: BLAS: OpenBLAS kernels Haswell (OPENBLAS_CORETYPE)$' err2.txt ||
    { fail=$((fail+1)); echo "FAIL: OPENBLAS_CORETYPE=Haswell is not what runs"; grep BLAS err2.txt; }
  ! grep -q 'set OPENBLAS_CORETYPE=' err.txt ||
    { fail=$((fail+1)); echo "FAIL: superjoin did not start again with OpenBLAS's kernels for this CPU:"; grep BLAS err.txt; }
  if grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo && ! grep -q 'built for this one CPU type' err.txt; then
    older='Katmai|Coppermine|Northwood|Prescott|Banias|Atom|Core2|Penryn|Dunnington|Nehalem|Athlon|Opteron|Opteron_SSE3|Barcelona|Nano|Sandybridge|Bobcat|Bulldozer|Piledriver|Steamroller|Unknown'
    ! grep -qiE "^superjoin: BLAS: OpenBLAS kernels ($older)( |$)" err.txt ||
      { fail=$((fail+1)); echo "FAIL: kernels older than this CPU's AVX2:"; grep BLAS err.txt; }
  fi
  if grep -q 'set by superjoin' err.txt; then
    # the new start keeps the names of the process and its threads (not "exe"): the deck
    # is a FIFO, so the second start waits there, after its set-up, until the deck is
    # written into it
    cp "$bin" ./sjname && rm -f in.fifo && mkfifo in.fifo
    env -u OPENBLAS_CORETYPE ./sjname -q in.fifo -o name.lst 2>/dev/null & pid=$!
    names=
    for _ in $(seq 300); do
      if grep -qa 'SUPERJOIN_BLAS_CORE_FROM=' /proc/$pid/environ 2>/dev/null; then
        names=$(cat /proc/$pid/task/*/comm 2>/dev/null | sort -u | tr '\n' ' ')
        [ "$names" = "sjname " ] && break
      fi
      sleep 0.01
    done
    timeout 5 sh -c "cat '$src/decks/demo.deck' > in.fifo" || true
    kill $pid 2>/dev/null; wait $pid 2>/dev/null
    [ "$names" = "sjname " ] || { fail=$((fail+1)); echo "FAIL: after its new start the process and its threads are named '$names', not sjname"; }
  fi
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
