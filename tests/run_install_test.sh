#!/usr/bin/env bash
# `cmake --install` puts the binary and the man page under a prefix, the
# installed binary runs, and the man page renders without warnings (with
# man -l or groff, whichever is present; that part is skipped without both).
# usage: run_install_test.sh CMAKE BUILD_DIR WORK_DIR
set -u
cmake=$1; build=$2; work=$3
rm -rf "$work"; mkdir -p "$work" || exit 1
prefix="$work/prefix"
fail=0
"$cmake" --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 || { echo "FAIL: cmake --install"; cat "$work/install.log"; exit 1; }
[ -x "$prefix/bin/superjoin" ] || { echo "FAIL: no bin/superjoin"; fail=1; }
"$prefix/bin/superjoin" --version | grep -q '^superjoin ' || { echo "FAIL: installed binary does not run"; fail=1; }
page="$prefix/share/man/man1/superjoin.1"
[ -s "$page" ] || { echo "FAIL: no share/man/man1/superjoin.1"; exit 1; }
rendered=""
if command -v man >/dev/null 2>&1; then
  MANWIDTH=80 man --warnings -l "$page" >"$work/man.txt" 2>"$work/man.err" || { echo "FAIL: man -l"; fail=1; }
  rendered="$work/man.txt"
elif command -v groff >/dev/null 2>&1; then
  groff -man -Tascii -ww "$page" >"$work/man.txt" 2>"$work/man.err" || { echo "FAIL: groff"; fail=1; }
  rendered="$work/man.txt"
else
  echo "neither man nor groff: rendering not checked"
fi
if [ -n "$rendered" ]; then
  [ ! -s "$work/man.err" ] || { echo "FAIL: the man page renders with warnings:"; cat "$work/man.err"; fail=1; }
  # every option that --help lists is described in the page
  for opt in $("$prefix/bin/superjoin" --help | grep -oE '^  (-[a-z], )?--?[a-z-]+' | grep -oE -- '--?[a-z-]+'); do
    grep -qE -- "^ +(-[a-z], )?$opt([ ,]|$)" "$rendered" || { echo "FAIL: man page lacks $opt"; fail=1; }
  done
fi
[ $fail -eq 0 ] && echo "install: bin/superjoin and share/man/man1/superjoin.1 installed; man page renders cleanly"
exit $fail
