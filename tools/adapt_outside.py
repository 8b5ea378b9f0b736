#!/usr/bin/env python3
"""-ts_vshmm_adapt on the problems of docs/accuracy.md sections 13-23 that are not examples of their
own (BUILD_DIR/tools/outside_problems, built from tools/outside_problems.cpp): for each, an RK4
reference at two steps (their largest weighted difference printed as "ref"), then the adaptive run
at each tolerance: the largest weighted error over the sampled times, |q - q*| / (tol (1 + |q*|))
over the observables (1 = the tolerance met), the time where it is largest, the work (split
evaluations of the accepted steps, and with the estimates and rejected tries), the sum of the
steps' estimates, and what single-rate RK4 steps at the run's micro steps would take (the work with
the estimates against it: above 1x the run saved nothing, and says so).

    python3 tools/adapt_outside.py BUILD_DIR [--tols 1e-1,1e-2,1e-3] [--only SUBSTRING] [--jobs N]
                                   [-- extra options for the adaptive runs]

About seven minutes on two cores (the references, the spread of rates and the limit cycle at eps = 1e-4 most of it).
"""
import math
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

# name, problem, final time, reference step, options (DeltaT 0.1 throughout)
PROBLEMS = [
    ('slow explicit time dependence (section 13)', 0, 2, 1e-5, ['-eps', '1e-3']),
    ('slow explicit time dependence to t = 10 (section 24)', 0, 10, 1e-5, ['-eps', '1e-3']),
    ('slow harmonic driven by a slaved nonlinearity', 4, 2, 1e-5, ['-eps', '1e-3']),
    ('fast rate varying with the slow variable', 5, 2, 1e-5, ['-eps', '1e-3']),
    ('slow forcing inside the fast split (section 18)', 8, 2, 1e-5, ['-eps', '1e-3']),
    ('a load switched on inside a macro step', 11, 2, 1e-5, ['-eps', '1e-3']),
    ('a fast level with a spread of rates, 1e3 and 1e6 (section 22)', 12, 2, 2e-6, ['-eps', '1e-3', '-eps2', '1e-3']),
    ('Michaelis-Menten, eps 3e-3 (section 22)', 16, 2, 1e-5, ['-eps', '3e-3']),
    ('Michaelis-Menten, eps 1e-3', 16, 2, 1e-5, ['-eps', '1e-3']),
    ('nested cascade', 17, 2, 5e-6, ['-eps', '3e-3', '-eps2', '3e-5']),
    ('slaved cubic', 18, 2, 1e-5, ['-eps', '3e-3', '-a', '3']),
    ('three-level chemistry', 19, 2, 2e-6, ['-eps', '3e-3', '-eps2', '1e-5']),
    ('cubic relaxation, slows near its manifold (section 23)', 20, 2, 1e-5, ['-eps', '1e-3']),
    ('cubic relaxation from (3, 0)', 20, 2, 1e-5, ['-eps', '1e-3', '-x0', '3,0']),
    ('cubic relaxation, additive splits', 20, 2, 1e-5, ['-eps', '1e-3', '-additive']),
    ('quadratic relaxation', 24, 2, 1e-5, ['-eps', '1e-3']),
    ('three levels, the medium one a cubic relaxation', 25, 2, 2e-6, ['-eps', '1e-3', '-eps2', '1e-5']),
    ('non-normal fast level, transient growth 50', 21, 2, 1e-5, ['-eps', '1e-3', '-a', '50']),
    ('steep switch of the fast equilibrium, tanh(20 (x - 1))', 22, 3, 1e-5, ['-eps', '1e-3', '-a', '20']),
    ('slow rotation at the speed of a slaved fast variable', 23, 10, 1e-5, ['-eps', '1e-3']),
    ('Michaelis-Menten with a small constant K = 0.1', 26, 4, 1e-5, ['-eps', '1e-3', '-a', '0.1']),
    ('fast rotation that slows down, driving y (said, not met at 1e-3)', 28, 3, 1e-6, ['-eps', '1e-3']),
    ('a fast limit cycle (van der Pol, Hopf parameter x; section 25)', 29, 2, 1e-5, ['-eps', '1e-3']),
    ('the same limit cycle at eps 1e-4 (section 25)', 29, 2, 1e-6, ['-eps', '1e-4']),
    ('two fast rotations 10 apart, their beat drives x (section 26)', 30, 2, 1e-5, ['-eps', '1e-3', '-a', '10']),
    ('a beat in the medium level of three (section 26)', 32, 2, 1e-6, ['-eps', '1e-3', '-eps2', '1e-6', '-a', '10']),
    ('three fast rotations in a triad resonance (section 26)', 31, 2, 1e-6, ['-eps', '1e-3', '-a', '10']),
    ('four fast rotations in a quartet resonance (section 34)', 36, 2, 1e-6, ['-eps', '1e-3', '-a', '10']),
    ('a beat that slows from 500 to rest at t = 1.5 (section 34)', 37, 2, 1e-6, ['-eps', '1e-3', '-a', '1.5', '-b', '0.5']),
    ('a saddle of the slow equation, errors grow e^(0.72 t), to t = 4 (section 35)', 38, 4, 1e-5, ['-eps', '1e-3']),
    ('a saddle, a = 2: errors grow e^(1.7 t), to t = 4 (section 35)', 38, 4, 1e-5, ['-eps', '1e-3', '-a', '2', '-x0', '0.81,0.6895']),
    ('a saddle from x = 0.3: runs away (section 35)', 38, 4, 1e-5, ['-eps', '1e-3', '-x0', '0.3,0.9553']),
    ('a growth the slow Jacobian does not show, e^t, to t = 4 (section 35)', 39, 4, 1e-5, ['-eps', '1e-3']),
    ("Kapitza's pendulum, inverted, A = 0.002, w = 1000, to t = 4: an error turned by a slow oscillation (section 36)", 40, 4, 1e-5, ['-eps', '1e-3', '-a', '0.002']),
    ('a slow predator-prey cycle (a center), the predator fed by a slaved fast variable, to t = 8 (section 36)', 41, 8, 1e-5, ['-eps', '1e-3']),
    ("a switch in the fast level: its equilibrium jumps by 3 at t = 2.47, inside a steady step, to t = 5 (section 37)", 42, 5, 1e-5, ['-eps', '1e-3', '-a', '3', '-b', '2.47']),
    ('the beat through squares, 8 q1^2 q2^2 - 2 (section 26)', 33, 2, 1e-6, ['-eps', '1e-3', '-a', '5']),
    ('a fast band whose slowest rate is 30 (section 27: savings that do not pay)', 34, 2, 1e-5, ['-eps', '1e-3', '-a', '30']),
    ('a slow rotation at 20, 2 radians a macro step, scales not separated (section 28)', 35, 2, 1e-5, ['-eps', '1e-2', '-a', '20']),
    ('the same at 40, 4 radians a macro step (section 28)', 35, 2, 1e-5, ['-eps', '1e-2', '-a', '40']),
    ('the same at 40, additive splits (section 28)', 35, 2, 1e-5, ['-eps', '1e-2', '-a', '40', '-additive']),
]


def run(build, prob, T, args):
    p = subprocess.run(['%s/tools/outside_problems' % build, '-prob', str(prob), '-ts_max_time', str(T), '-ts_dt', '0.1'] + args,
                       capture_output=True, text=True)
    rows, work = {}, None
    for line in p.stdout.splitlines():
        w = line.split()
        if w and w[0] == 'T':
            rows[round(float(w[1]), 8)] = [float(x) for x in w[2:] if not x.startswith('S')]
        elif w and w[0] == 'WORK':
            work = ' '.join(w[1:])
    return rows, work, (p.stderr.strip().splitlines() or [''])[-1] if p.returncode else None


def error(rows, ref, tol):
    worst, at = 0.0, None
    for t, q in ref.items():
        if t not in rows or abs(round(t / 0.1) * 0.1 - t) > 1e-9:
            continue
        for a, b in zip(rows[t], q):
            e = abs(a - b) / (tol * (1 + abs(b))) if math.isfinite(a) else float('inf')
            if not e <= worst:
                worst, at = e, t
    return worst, at


def case(build, name, prob, T, h, args, tols, extra):
    refs = []
    for dt in (h, h / 2):
        n = int(round(0.1 / dt))
        refs.append(run(build, prob, T, args + ['-ts_type', 'rk', '-ts_rk_type', '4', '-ts_dt', str(0.1 / n), '-ts_monitor_skip', '0'])[0])
    agree = error(refs[0], refs[1], 1.0)[0]
    out = ['%s: ref %.1e' % (name, agree)]
    for tol in tols:
        rows, work, failed = run(build, prob, T, args + ['-ts_type', 'vshmm', '-ts_vshmm_adapt', '-ts_vshmm_warnings_viewer', 'none',
                                                          '-ts_rtol', str(tol), '-ts_atol', str(tol)] + extra)
        if failed is not None:
            out.append('  %g: failed: %s' % (tol, failed[:100]))
            continue
        e, at = error(rows, refs[1], tol)
        w = work.split()
        paid = ' (%.2fx single-rate)' % (float(w[1]) / float(w[-1])) if len(w) >= 5 and float(w[-1]) > 0 else ''
        out.append('  %g: %.2f tol (t = %s), work %s%s' % (tol, e, at, work, paid))
    return '\n'.join(out)


def main():
    argv, extra = sys.argv[1:], []
    if '--' in argv:
        argv, extra = argv[:argv.index('--')], argv[argv.index('--') + 1:]
    if not argv:
        sys.exit(__doc__)
    build, tols, only, jobs = argv[0], [1e-1, 1e-2, 1e-3], [], 2
    i = 1
    while i < len(argv):
        if argv[i] == '--tols':
            tols = [float(x) for x in argv[i + 1].split(',')]
        elif argv[i] == '--only':
            only.append(argv[i + 1])
        elif argv[i] == '--jobs':
            jobs = int(argv[i + 1])
        else:
            sys.exit('unknown argument %s\n%s' % (argv[i], __doc__))
        i += 2
    chosen = [p for p in PROBLEMS if not only or any(s in p[0] for s in only)]
    with ThreadPoolExecutor(jobs) as pool:
        for text in pool.map(lambda p: case(build, *p, tols, extra), chosen):
            print(text, flush=True)


if __name__ == '__main__':
    main()
