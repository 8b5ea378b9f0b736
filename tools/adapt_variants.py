#!/usr/bin/env python3
"""-ts_vshmm_adapt on parameters tools/adapt_suite.py does not use (docs/accuracy.md section 10):
the oscillators at eps = 5e-3 and 2e-3 (t = 0.8, 2.4), the dissipative example at eps = 3e-2,
3e-3, 1e-3, the relaxation chain at other separations e. Each reference is a DNS (RK4; the
oscillators by tools/oscillatory_reference, Richardson-extrapolated) at two steps, and their
largest difference is printed beside it ("ref refine diff"). Per tolerance: the largest weighted
error over the sampled times |q - q*| / (tol (1 + |q*|)) (2-norm over the observables), the work
(split evaluations with the estimates).

    python3 tools/adapt_variants.py BUILD_DIR [TOLS (default 1e-1,3e-2,1e-2,3e-3,1e-3)] [SUBSTRING] [-- extra options]

Options after `--` are passed to every adaptive run (not to the references), e.g. `-- -ts_vshmm_kernel
constant` for another kernel or `-- -ts_vshmm_rk_type 3` for another inner method.

About 10 minutes in all (the oscillators' references most of it).
"""
import os
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from adapt_suite import measure, oscillator_reference  # noqa: E402  (the suite's error and work, its oscillator reference)


def dns_reference(build, exe, args, names, dt, refinement):
    """The observables at the sampled times by RK4 at dt / 2 (times rounded to 1e-3: the DNS steps
    need not land on them); the largest difference from dt is appended to `refinement`."""
    refs = []
    pat = r'^t (\S+)' + ''.join(r' %s (\S+)' % q for q in names)
    for h in (dt, dt / 2):
        out = subprocess.run(['%s/%s' % (build, exe), '-ts_type', 'rk', '-ts_rk_type', '4', '-ts_dt', '%g' % h, '-no_timing'] + args,
                             capture_output=True, text=True).stdout
        refs.append({round(float(m.group(1)), 3): tuple(float(m.group(2 + i)) for i in range(len(names)))
                     for m in re.finditer(pat, out, re.M) if float(m.group(1)) > 0})
    refinement.append(max(abs(a - b) for t in refs[1] for a, b in zip(refs[0][t], refs[1][t])))
    return refs[1]


def cases():
    out = []
    for eps in (5e-3, 2e-3):
        for T in (0.8, 2.4):
            out.append(('oscillators eps=%g t=%g' % (eps, T), 'examples/ode/oscillatory', ['-eps', '%g' % eps, '-ts_max_time', '%g' % T], ['I1', 'I2'], ('osc', eps, T)))
    for eps in (3e-2, 3e-3, 1e-3):
        out.append(('dissipative eps=%g' % eps, 'examples/ode/dissipative', ['-eps', '%g' % eps, '-ts_max_time', '2', '-print_interval', '0.5'], ['xi'],
                    ('dns', min(1e-4, eps * eps / 4))))
    for e, n in ((3e-2, 3), (3e-2, 4), (1e-1, 3), (5e-3, 2), (3e-3, 3)):
        out.append(('chain e=%g scales %d' % (e, n), 'examples/stress/chain', ['-scales', str(n), '-e', '%g' % e, '-print_interval', '0.5'], ['x0'],
                    ('dns', min(1e-3, e ** (n - 1) / 4))))
    return out


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    argv, extra = sys.argv, []
    if '--' in argv:
        argv, extra = argv[:argv.index('--')], argv[argv.index('--') + 1:]
    build = argv[1]
    tols = [float(t) for t in (argv[2] if len(argv) > 2 else '1e-1,3e-2,1e-2,3e-3,1e-3').split(',')]
    only = argv[3] if len(argv) > 3 else ''
    for name, exe, args, names, how in cases():
        if only and only not in name:
            continue
        refinement = []
        if how[0] == 'osc':
            ref = oscillator_reference(build, None, how[2], how[1], refinement)
        else:
            ref = dns_reference(build, exe, args, names, how[1], refinement)
        prob = (name, exe, args, names, ref)
        with ThreadPoolExecutor(2) as pool:
            res = list(pool.map(lambda tol: measure(build, prob, ['-ts_vshmm_adapt', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol] + extra), tols))
        print('%-28s ref refine diff %.1e | ' % (name, refinement[0]) + ' | '.join(
            '%g: %s' % (tol, r if isinstance(r, str) else '%.2f %.2g' % (r[0] / tol, r[1])) for tol, r in zip(tols, res)), flush=True)


if __name__ == '__main__':
    main()
