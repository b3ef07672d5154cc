#!/usr/bin/env python3
"""--reuse-memory: freed blocks under 32 MiB stay with superjoin for its next ones.

A 2e5-equation frame (bench/gen_frame) is solved twice, --reuse-memory no and
yes (the default), both with --huge-pages no (ordinary pages: the fault counts
then do not depend on the kernel's huge pages):
- the listings are byte-identical (where a block comes from changes no result);
- the run with it takes at most MAX_FAULT_RATIO of the minor page faults of
  the run without: blocks freed and asked for again (the solves' work vectors,
  CHOLMOD's workspaces, the assembly's temporaries) are reused from the heap
  instead of being unmapped and faulted in afresh (measured 96 300 against
  105 600 on ordinary pages; on huge pages 34 000 against 42 500);
- its peak resident memory is at most PEAK_SLACK_MIB above the run without,
  the bound of the free heap it keeps (measured 221 against 219 MB; keeping
  the whole free top instead, a trim threshold of 1 GiB, peaks at 240 MB);
- a value other than yes or no is a usage error (exit 2) naming the option.
Faults and peaks are counted per child (os.wait4), not timed.

usage: reuse_memory.py SUPERJOIN GEN_FRAME WORKDIR
"""
import os
import subprocess
import sys

MAX_FAULT_RATIO = 0.95
PEAK_SLACK_MIB = 16


def run(cmd, cwd):
    """Exit status, minor page faults, peak resident set (KiB) and stderr of one child."""
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    err = proc.stderr.read().decode()
    proc.stderr.close()
    _, status, usage = os.wait4(proc.pid, 0)
    return os.waitstatus_to_exitcode(status), usage.ru_minflt, usage.ru_maxrss, err


def main():
    superjoin, gen_frame, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "reuse.deck")
    subprocess.run([gen_frame, "--dofs", "2e5", deck], check=True, stdout=subprocess.DEVNULL)
    failures = []
    faults, peak = {}, {}
    for r in ("no", "yes"):
        rc, faults[r], peak[r], err = run([superjoin, "-q", "--condense", "no", "--huge-pages", "no",
                                           "--reuse-memory", r, "reuse.deck", "-o", f"reuse_{r}.lst"], work)
        if rc != 0:
            failures.append(f"--reuse-memory {r}: exit {rc}: {err.strip()}")
    if not failures:
        with open(os.path.join(work, "reuse_no.lst"), "rb") as a, open(os.path.join(work, "reuse_yes.lst"), "rb") as b:
            if a.read() != b.read():
                failures.append("the listings of --reuse-memory no and yes differ")
        print(f"minor page faults: --reuse-memory no {faults['no']}, yes {faults['yes']}; "
              f"peak {peak['no'] // 1024} and {peak['yes'] // 1024} MiB")
        if faults["yes"] > MAX_FAULT_RATIO * faults["no"]:
            failures.append(f"--reuse-memory yes took {faults['yes']} minor faults, more than "
                            f"{MAX_FAULT_RATIO} x the {faults['no']} of --reuse-memory no")
        if peak["yes"] > peak["no"] + PEAK_SLACK_MIB * 1024:
            failures.append(f"--reuse-memory yes peaked at {peak['yes'] // 1024} MiB, more than "
                            f"{PEAK_SLACK_MIB} MiB above the {peak['no'] // 1024} MiB of --reuse-memory no")
    rc, _, _, err = run([superjoin, "--reuse-memory", "maybe", "reuse.deck"], work)
    if rc != 2 or "--reuse-memory 'maybe' (yes, no)" not in err:
        failures.append(f"--reuse-memory maybe: exit {rc}, stderr {err.strip()!r} (want exit 2 naming the option)")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
