#!/usr/bin/env python3
"""--huge-pages: large arrays ask the kernel for transparent huge pages.

A 2e5-equation frame (bench/gen_frame) is solved twice, --huge-pages no and
yes (the default):
- the listings are byte-identical (the advice changes no result);
- where the kernel's transparent huge pages are "madvise" (the setting under
  which the advice matters), the run with it takes at most MAX_FAULT_RATIO of
  the minor page faults of the run without: 2 MiB pages instead of 4 KiB ones
  for CHOLMOD's factor and copies, K's values and rows, the scatter map and
  the element results (measured 43 000 against 106 000). Under "always" or
  "never" the two runs fault alike, and this check is said to be skipped. A
  failed check is excused (and said) only when the kernel could not find
  free huge pages during the yes run (/proc/vmstat, machine-wide: more
  thp_fault_fallback than thp_fault_alloc, the memory fragmented); a run that
  never asked for them (the advice broken) adds to neither, and fails;
- a value other than yes or no is a usage error (exit 2) naming the option.
Faults are counted per child (os.wait4), not timed.

usage: huge_pages.py SUPERJOIN GEN_FRAME WORKDIR
"""
import os
import subprocess
import sys

MAX_FAULT_RATIO = 0.6
THP_MODE = "/sys/kernel/mm/transparent_hugepage/enabled"


def run(cmd, cwd):
    """Exit status and minor page faults of one child."""
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    err = proc.stderr.read().decode()
    proc.stderr.close()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, usage.ru_minflt, err


def thp_faults():
    """The machine's huge-page faults so far: given, and fallen back to small pages."""
    counts = {"thp_fault_alloc": 0, "thp_fault_fallback": 0}
    try:
        with open("/proc/vmstat") as f:
            for line in f:
                key, _, value = line.partition(" ")
                if key in counts:
                    counts[key] = int(value)
    except OSError:
        pass
    return counts


def thp_mode():
    try:
        with open(THP_MODE) as f:
            text = f.read()
    except OSError:
        return "absent"
    start, end = text.find("["), text.find("]")
    return text[start + 1:end] if 0 <= start < end else "unknown"


def main():
    superjoin, gen_frame, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "frame.deck")
    subprocess.run([gen_frame, "--dofs", "2e5", deck], check=True, stdout=subprocess.DEVNULL)
    failures = []
    faults = {}
    for h in ("no", "yes"):
        before = thp_faults()
        rc, faults[h], err = run([superjoin, "-q", "--condense", "no", "--huge-pages", h, "frame.deck",
                                  "-o", f"frame_{h}.lst"], work)
        if rc != 0:
            failures.append(f"--huge-pages {h}: exit {rc}: {err.strip()}")
        if h == "yes":
            after = thp_faults()
            given = after["thp_fault_alloc"] - before["thp_fault_alloc"]
            fallen = after["thp_fault_fallback"] - before["thp_fault_fallback"]
    if not failures:
        with open(os.path.join(work, "frame_no.lst"), "rb") as a, open(os.path.join(work, "frame_yes.lst"), "rb") as b:
            if a.read() != b.read():
                failures.append("the listings of --huge-pages no and yes differ")
    mode = thp_mode()
    print(f"minor page faults: --huge-pages no {faults['no']}, yes {faults['yes']} (kernel THP mode: {mode}); "
          f"during the yes run huge pages given {given}, fallen back {fallen}")
    if mode != "madvise":
        print(f"fault check skipped: the advice matters only under 'madvise' (this kernel: {mode})")
    elif faults["yes"] > MAX_FAULT_RATIO * faults["no"]:
        if fallen > given:
            print("fault check excused: the kernel found no free huge pages for most requests (memory fragmented)")
        else:
            failures.append(f"--huge-pages yes took {faults['yes']} minor faults, more than "
                            f"{MAX_FAULT_RATIO} x the {faults['no']} of --huge-pages no")
    rc, _, err = run([superjoin, "--huge-pages", "maybe", "frame.deck"], work)
    if rc != 2 or "--huge-pages 'maybe' (yes, no)" not in err:
        failures.append(f"--huge-pages maybe: exit {rc}, stderr {err.strip()!r} (want exit 2 naming the option)")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
