#!/usr/bin/env python3
"""solid_bench.py -- solid parts (C3D20R, C3D10): superjoin against CalculiX
2.20 (`ccx -i job`) and against bare CHOLMOD on the matrix superjoin exported.

For every element type and size: bench/gen_solid.py writes one CalculiX deck
(both programs read it unchanged); superjoin runs once with --export-matrix
(K.mtx for build/cholmod_bare, the driver of bench/run_frame.sh and
bench/ab_bare.sh); then ROUNDS rounds of superjoin and bare CHOLMOD in turn
(interleaved, so each pair runs under the same load of the shared machine);
then ccx once (killed after --ccx-timeout seconds). Wall clock and peak
resident set from /usr/bin/time -v; the load average before each run. The
table gives medians over the rounds and the ratios:

  ccx/sj time   ccx wall / superjoin wall           (target >= 5)
  sj/ccx mem    superjoin peak / ccx peak           (target <= 0.2)
  sj/bare       superjoin wall / bare analyze+factorize+solve (target <= 1.3;
                bare's reading of K.mtx is left out: it stands for superjoin's
                read and assembly, as in bench/run_frame.sh)

usage: bench/solid_bench.py [--types C3D20R,C3D10] [--shape plate|block]
           [--rounds 3] [--ccx-max 1e5] [--ccx-timeout 600] [--work DIR] [SIZE ...]
SIZE: nodal DOFs wanted (default 1e4 3e4 1e5 3e5). --ccx-max: largest size ccx
is run at (0: never). Environment: SUPERJOIN (default build/superjoin).
Needs ccx, gcc with CHOLMOD headers (libsuitesparse-dev), /usr/bin/time.
"""
import argparse
import os
import re
import signal
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, 'build')
BARE = os.path.join(BUILD, 'cholmod_bare')


def load():
    with open('/proc/loadavg') as f:
        return float(f.read().split()[0])


def timed(cmd, cwd, log, timeout=None):
    """Run cmd under /usr/bin/time -v: (status, wall s, peak MB, load before, stdout+stderr text)."""
    tfile = log + '.time'
    ld = load()
    t0 = time.monotonic()
    with open(log, 'w') as out:
        proc = subprocess.Popen(['/usr/bin/time', '-v', '-o', tfile] + cmd, cwd=cwd, stdout=out,
                                stderr=subprocess.STDOUT, start_new_session=True)
        try:
            rc = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)   # its own process group: time and the program it runs
            proc.wait()
            return 'timeout', time.monotonic() - t0, None, ld, ''
    wall = time.monotonic() - t0
    peak = None
    if os.path.exists(tfile):
        m = re.search(r'Maximum resident set size \(kbytes\): (\d+)', open(tfile).read())
        peak = int(m.group(1)) / 1024.0 if m else None
    return rc, wall, peak, ld, open(log).read()


def build_bare():
    sources = [os.path.join(ROOT, 'bench', 'cholmod_bare.c'), os.path.join(ROOT, 'src', 'utils', 'blas_core.c')]
    if not os.path.exists(BARE) or max(map(os.path.getmtime, sources)) > os.path.getmtime(BARE):
        os.makedirs(BUILD, exist_ok=True)
        subprocess.check_call(['gcc', '-O2', '-I/usr/include/suitesparse', *sources, '-lcholmod',
                               '-lsuitesparseconfig', '-lm', '-o', BARE])


def phases(text):
    """superjoin -v phase seconds, and its equation / factor counts."""
    ph = {m.group(1): float(m.group(2)) for m in re.finditer(r'^superjoin: (\w+) ([0-9.]+) s', text, re.M)}
    m = re.search(r'equations (\d+), nonzeros (\d+)', text)
    n = re.search(r'factor nonzeros (\d+)', text)
    return ph, (int(m.group(1)) if m else 0), (int(n.group(1)) if n else 0)


def bare_time(text):
    t = {m.group(1): float(m.group(2)) for m in re.finditer(r'^time (\w+) +([0-9.eE+-]+)', text, re.M)}
    return t.get('analyze', 0.0) + t.get('factor', 0.0) + t.get('solve', 0.0)


def probe_u3(path, ccx):
    """The probe's vertical displacement, from ccx's .dat or superjoin's listing."""
    if not os.path.exists(path):
        return None
    lines = open(path).read().splitlines()
    for i, line in enumerate(lines):
        if ccx and 'displacements (vx,vy,vz) for set PROBE' in line:
            return float(lines[i + 2].split()[3])
        if not ccx and line.strip().startswith('MAIN ') and 'displacements' in lines[i - 2]:
            return float(line.split()[4].replace('E', 'e'))
    return None


def med(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def fmt(x, f='%.2f'):
    return 'NA' if x is None else f % x


def one(args, etype, size, sj):
    d = os.path.join(args.work, '%s-%s-%s' % (etype, args.shape, size))
    os.makedirs(d, exist_ok=True)
    deck = os.path.join(d, 'job.inp')
    g = subprocess.run([sys.executable, os.path.join(ROOT, 'bench', 'gen_solid.py'), '--type', etype, '--shape',
                        args.shape, '--dofs', size, deck], stderr=subprocess.PIPE, text=True, check=True)
    info = g.stderr.strip()
    print('solid_bench: ' + info, file=sys.stderr)
    rc, *_ = timed([sj, '-q', 'job.inp', '-o', 'export.lst', '--export-matrix', 'K.mtx'], d, os.path.join(d, 'export.log'))
    if rc != 0:
        sys.exit('solid_bench: superjoin export run failed (%s), see %s/export.log' % (rc, d))
    sj_w, sj_m, b_t, b_w, b_m, loads, ph_all = [], [], [], [], [], [], []
    neq = nnzl = 0
    for r in range(args.rounds):
        print('solid_bench: %s %s round %d/%d' % (etype, size, r + 1, args.rounds), file=sys.stderr)
        rc, w, m, ld, text = timed([sj, '-v', 'job.inp', '-o', 'job.lst'], d, os.path.join(d, 'sj.log'))
        if rc != 0:
            sys.exit('solid_bench: superjoin failed (%s), see %s/sj.log' % (rc, d))
        ph, neq, nnzl = phases(text)
        sj_w.append(w); sj_m.append(m); loads.append(ld); ph_all.append(ph)
        rc, w, m, ld, text = timed([BARE, 'K.mtx'], d, os.path.join(d, 'bare.log'))
        if rc != 0:
            sys.exit('solid_bench: cholmod_bare failed (%s), see %s/bare.log' % (rc, d))
        b_t.append(bare_time(text)); b_w.append(w); b_m.append(m); loads.append(ld)
    os.remove(os.path.join(d, 'K.mtx'))
    ccx = (None, None, None, 'not run')
    if args.ccx_max > 0 and float(size) <= args.ccx_max:
        print('solid_bench: %s %s ccx' % (etype, size), file=sys.stderr)
        env_rc, w, m, ld, _ = timed(['ccx', '-i', 'job'], d, os.path.join(d, 'ccx.log'), timeout=args.ccx_timeout)
        loads.append(ld)
        if env_rc == 0 and probe_u3(os.path.join(d, 'job.dat'), True) is not None:
            ccx = (w, m, probe_u3(os.path.join(d, 'job.dat'), True), 'ok')
        else:
            ccx = (None, None, None, 'timeout' if env_rc == 'timeout' else 'failed')
    u_sj = probe_u3(os.path.join(d, 'job.lst'), False)
    phm = {k: med([p.get(k) for p in ph_all]) for k in ('read', 'assemble', 'order', 'factor', 'solve', 'health',
                                                        'recover', 'write')}
    return dict(etype=etype, size=size, info=info, neq=neq, nnzl=nnzl, sj=med(sj_w), sj_mb=med(sj_m), sj_all=sj_w,
                bare=med(b_t), bare_wall=med(b_w), bare_mb=med(b_m), bare_all=b_t, ccx=ccx[0], ccx_mb=ccx[1],
                ccx_status=ccx[3], u_ccx=ccx[2], u_sj=u_sj, load=(min(loads), max(loads)), ph=phm)


def ratio(a, b):
    return None if a is None or b is None or b == 0 else a / b


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('sizes', nargs='*', default=['1e4', '3e4', '1e5', '3e5'])
    ap.add_argument('--types', default='C3D20R,C3D10')
    ap.add_argument('--shape', default='plate', choices=['plate', 'block'])
    ap.add_argument('--rounds', type=int, default=3)
    ap.add_argument('--ccx-max', type=float, default=1e5)
    ap.add_argument('--ccx-timeout', type=float, default=600)
    ap.add_argument('--work', default=os.path.join(BUILD, 'solid_bench'))
    args = ap.parse_args()
    sj = os.environ.get('SUPERJOIN', os.path.join(BUILD, 'superjoin'))
    build_bare()
    rows = []
    for t in args.types.split(','):
        for s in args.sizes:
            rows.append(one(args, t, s, sj))
            print('solid_bench: ' + row_text(rows[-1]), file=sys.stderr)   # kept if a later size is cut short
    print('\nsuperjoin against ccx 2.20 and bare CHOLMOD, shape %s, %d cores, medians of %d rounds '
          '(superjoin and bare in turn); times s, memory MB' % (args.shape, os.cpu_count(), args.rounds))
    print(HEAD)
    for r in rows:
        print(row_text(r))
    print('\nsuperjoin phases (medians, s):')
    for r in rows:
        print('  %-7s %6s  %s   rounds sj %s bare %s' % (r['etype'], r['size'], '  '.join(
            '%s %s' % (k, fmt(v)) for k, v in r['ph'].items()), ' '.join('%.2f' % x for x in r['sj_all']),
            ' '.join('%.2f' % x for x in r['bare_all'])))
    print('targets: ccx/sj >= 5, mem = sj peak / ccx peak <= 0.2, sj/bare <= 1.3; load = 1-min load average '
          'before the runs (min-max)')


HEAD = '%-7s %6s %8s %10s | %7s %7s | %7s %7s | %7s %7s %6s | %7s %6s %6s | %9s' % (
    'type', 'size', 'equat.', 'nnz(L)', 'sj', 'sjMB', 'bare', 'bareMB', 'ccx', 'ccxMB', 'u3 rel', 'sj/bare',
    'ccx/sj', 'mem', 'load')


def row_text(r):
    """One line of the table."""
    du = None if r['u_ccx'] is None or r['u_sj'] is None else abs(r['u_sj'] - r['u_ccx']) / abs(r['u_ccx'])
    return ('%-7s %6s %8d %10d | %7s %7s | %7s %7s | %7s %7s %6s | %7s %6s %6s | %4.1f-%4.1f' % (
        r['etype'], r['size'], r['neq'], r['nnzl'], fmt(r['sj']), fmt(r['sj_mb'], '%.0f'), fmt(r['bare']),
        fmt(r['bare_mb'], '%.0f'), fmt(r['ccx']) if r['ccx'] is not None else r['ccx_status'],
        fmt(r['ccx_mb'], '%.0f'), fmt(du, '%.0e'), fmt(ratio(r['sj'], r['bare']), '%.3f'),
        fmt(ratio(r['ccx'], r['sj'])), fmt(ratio(r['sj_mb'], r['ccx_mb'])), r['load'][0], r['load'][1]))


if __name__ == '__main__':
    main()
