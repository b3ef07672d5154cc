#!/usr/bin/env bash
# VTK output from the command line and from the deck: option checks, *OUTPUT,
# VTK= resolved against the deck's directory, --vtk overriding it, and a run
# that fails while writing leaves the previous files untouched and no temporaries.
# usage: run_vtk_cli.sh SUPERJOIN PYTHON SOURCE_DIR WORK_DIR
set -u
bin=$1; py=$2; src=$3; work=$4
check="$src/tests/vtk/check_vtk.py"
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
pass=0; fail=0
ok() { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*"; }
expect() {  # expect STATUS DESCRIPTION -- command...
  local want=$1 what=$2; shift 3
  "$@" >out.txt 2>err.txt; local rc=$?
  if [ "$rc" -eq "$want" ] && ! grep -qiE 'runtime error|backtrace|segmentation' err.txt; then ok
  else bad "$what: status $rc (want $want)"; cat err.txt; fi
}
demo="$src/decks/demo.deck"

expect 2 "--vtk without a value" -- "$bin" --vtk
expect 2 "--vtk naming a directory" -- "$bin" -q --vtk out/ "$demo" -o x.lst
grep -q 'needs a file name' err.txt && ok || bad "no reason given for --vtk out/"
expect 2 "--vtk .pvd" -- "$bin" -q --vtk .pvd "$demo" -o x.lst
"$bin" --help | grep -q -- '--vtk FILE' && ok || bad "--help lacks --vtk"

# *OUTPUT in the deck: relative to the deck's directory, whatever the working directory.
mkdir -p proj
{ cat "$demo"; printf '*OUTPUT, VTK=res/frame\n'; } > proj/frame.deck
expect 0 "deck with *OUTPUT" -- "$bin" -q proj/frame.deck --csv csv
for f in frame.pvd frame_1.vtu frame_2.vtu; do [ -s proj/res/$f ] && ok || bad "proj/res/$f not written"; done
[ ! -e res ] && ok || bad "*OUTPUT path taken relative to the working directory"
"$py" "$check" proj/res/frame.pvd --csv csv >check.txt && ok || { bad "check of the *OUTPUT files"; cat check.txt; }
# --check writes nothing; --vtk overrides the deck.
rm -rf proj/res
expect 0 "--check with *OUTPUT" -- "$bin" -q --check proj/frame.deck
[ ! -e proj/res ] && ok || bad "--check wrote VTK files"
expect 0 "--vtk over *OUTPUT" -- "$bin" -q proj/frame.deck --vtk other/x
[ -s other/x.pvd ] && [ ! -e proj/res ] && ok || bad "--vtk did not override *OUTPUT"
# *OUTPUT inside a step is allowed (Abaqus habit) and means the whole run.
sed 's/^\*STEP, NAME=ROOF$/*STEP, NAME=ROOF\n*OUTPUT, FIELD, VTK=instep/' "$demo" > proj/instep.deck
expect 0 "*OUTPUT inside *STEP" -- "$bin" -q proj/instep.deck
[ -s proj/instep_1.vtu ] && [ -s proj/instep_2.vtu ] && ok || bad "*OUTPUT inside *STEP did not write every step"

# A failure while writing keeps the previous files and leaves no temporary.
expect 0 "good run" -- "$bin" -q "$demo" -o keep.lst --vtk keep/demo
cp -r keep saved
mkdir keep/demo_2.vtu.tmp        # the second piece cannot be written
expect 4 "unwritable piece" -- "$bin" -q "$demo" -o keep.lst --vtk keep/demo
grep -q 'demo_2.vtu.tmp' err.txt && ok || { bad "message does not name the file"; cat err.txt; }
for f in demo.pvd demo_1.vtu demo_2.vtu; do cmp -s keep/$f saved/$f && ok || bad "failed run changed $f"; done
[ -z "$(find keep -name '*.tmp' -type f)" ] && ok || bad "temporary files left: $(find keep -name '*.tmp' -type f)"
rm -rf keep/demo_2.vtu.tmp
touch afile
expect 4 "directory that is a file" -- "$bin" -q "$demo" -o f.lst --vtk afile/x
grep -q "cannot create directory 'afile'" err.txt && ok || { bad "message for an impossible directory"; cat err.txt; }

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
