#!/usr/bin/env python3
"""--reuse-memory: freed blocks under 32 MiB stay with superjoin for its next ones.

A 2e5-equation frame (bench/gen_frame) is solved with --reuse-memory no and
with the default (yes), both with --huge-pages no (ordinary pages: the fault
counts then do not depend on the kernel's huge pages) and one thread:
- the listings are byte-identical (where a block comes from changes no result);
- the default takes at most MAX_FAULT_RATIO of the minor page faults of
  the run without: blocks freed and asked for again (the solves' work vectors,
  CHOLMOD's workspaces, the assembly's temporaries) are reused from the heap
  instead of being unmapped and faulted in afresh (measured 85 000 against
  94 700 at one thread on ordinary pages; on huge pages with threads 34 000
  against 42 500);
- its peak resident memory is at most PEAK_SLACK_MIB above the run without
  (measured 229 against 230 MiB at one thread; with threads 221 against 219
  MB, and 240 MB with a trim threshold of 1 GiB instead of 16 MiB);
- allocator tunables the user set stand: with GLIBC_TUNABLES=USER_TUNABLES
  (every block above 128 KiB mapped on its own) the default run takes at
  least TUNABLES_MIN_RATIO x the faults of the default without it;
- a value other than yes or no is a usage error (exit 2) naming the option.
Faults and peaks are counted per child (os.wait4), not timed. Skipped (77)
where the C library is not glibc (the policy is glibc's allocator's).

usage: reuse_memory.py SUPERJOIN GEN_FRAME WORKDIR
"""
import os
import subprocess
import sys

MAX_FAULT_RATIO = 0.95
PEAK_SLACK_MIB = 16
# the user's tunables stand: every block above 128 KiB mapped on its own,
# freed blocks unmapped (measured 123 000 faults against the default's 85 000)
USER_TUNABLES = "glibc.malloc.mmap_threshold=131072"
TUNABLES_MIN_RATIO = 1.2
SKIP = 77


def run(cmd, cwd, env):
    """Exit status, minor page faults, peak resident set (KiB) and stderr of one child."""
    proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    err = proc.stderr.read().decode()
    proc.stderr.close()
    _, status, usage = os.wait4(proc.pid, 0)
    return os.waitstatus_to_exitcode(status), usage.ru_minflt, usage.ru_maxrss, err


def main():
    superjoin, gen_frame, work = sys.argv[1:4]
    try:
        libc = os.confstr("CS_GNU_LIBC_VERSION") or ""
    except (ValueError, OSError):
        libc = ""
    if not libc.startswith("glibc"):
        print("skipped: the policy is glibc's allocator's (this C library: " + (libc or "unknown") + ")")
        return SKIP
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "reuse.deck")
    subprocess.run([gen_frame, "--dofs", "2e5", deck], check=True, stdout=subprocess.DEVNULL)
    env = {k: v for k, v in os.environ.items()
           if k not in ("GLIBC_TUNABLES", "MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_")}
    env.update(OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")   # one arena's worth of timing
    base = [superjoin, "-q", "--condense", "no", "--huge-pages", "no", "reuse.deck"]
    runs = {"no": (["--reuse-memory", "no"], env),
            "default": ([], env),   # yes is the default
            "tunables": ([], dict(env, GLIBC_TUNABLES=USER_TUNABLES))}
    failures = []
    faults, peak = {}, {}
    for r, (opt, e) in runs.items():
        rc, faults[r], peak[r], err = run(base + opt + ["-o", f"reuse_{r}.lst"], work, e)
        if rc != 0:
            failures.append(f"run {r}: exit {rc}: {err.strip()}")
    if not failures:
        with open(os.path.join(work, "reuse_no.lst"), "rb") as a, \
                open(os.path.join(work, "reuse_default.lst"), "rb") as b:
            if a.read() != b.read():
                failures.append("the listings of --reuse-memory no and the default (yes) differ")
        print(f"minor page faults: --reuse-memory no {faults['no']}, default {faults['default']}, with the "
              f"user's tunables {faults['tunables']}; peak {peak['no'] // 1024} and {peak['default'] // 1024} MiB")
        if faults["default"] > MAX_FAULT_RATIO * faults["no"]:
            failures.append(f"the default took {faults['default']} minor faults, more than "
                            f"{MAX_FAULT_RATIO} x the {faults['no']} of --reuse-memory no")
        if peak["default"] > peak["no"] + PEAK_SLACK_MIB * 1024:
            failures.append(f"the default peaked at {peak['default'] // 1024} MiB, more than "
                            f"{PEAK_SLACK_MIB} MiB above the {peak['no'] // 1024} MiB of --reuse-memory no")
        if faults["tunables"] < TUNABLES_MIN_RATIO * faults["default"]:
            failures.append(f"with GLIBC_TUNABLES={USER_TUNABLES} the run took {faults['tunables']} minor faults, "
                            f"less than {TUNABLES_MIN_RATIO} x the default's {faults['default']}: the user's "
                            "tunables did not stand")
    rc, _, _, err = run([superjoin, "--reuse-memory", "maybe", "reuse.deck"], work, env)
    if rc != 2 or "--reuse-memory 'maybe' (yes, no)" not in err:
        failures.append(f"--reuse-memory maybe: exit {rc}, stderr {err.strip()!r} (want exit 2 naming the option)")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
