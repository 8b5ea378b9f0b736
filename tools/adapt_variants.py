#!/usr/bin/env python3
"""-ts_vshmm_adapt on parameters tools/adapt_suite.py does not use (docs/accuracy.md section 10):
the oscillators at eps = 5e-3 and 2e-3 (t = 0.8, 2.4), the dissipative example at eps = 3e-2,
3e-3, 1e-3, the relaxation chain at other separations e. Each reference is a DNS (RK4; the
oscillators by tools/oscillatory_reference, Richardson-extrapolated) at two steps, and their
largest difference is printed beside it ("ref refine diff"). Per tolerance: the largest weighted
error over the sampled times |q - q*| / (tol (1 + |q*|)) (2-norm over the observables), the work
(split evaluations with the estimates).

    python3 tools/adapt_variants.py BUILD_DIR [TOLS (default 1e-1,3e-2,1e-2,3e-3,1e-3)] [SUBSTRING]

About 10 minutes in all (the oscillators' references most of it).
"""
import math, re, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
if len(sys.argv) < 2:
    sys.exit(__doc__)
B = sys.argv[1]
TOLS = [float(t) for t in (sys.argv[2] if len(sys.argv) > 2 else '1e-1,3e-2,1e-2,3e-3,1e-3').split(',')]

def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)

def parse(out, names):
    pat = r'^t (\S+)' + ''.join(r' %s (\S+)' % q for q in names)
    return {round(float(m.group(1)), 3): tuple(float(m.group(2 + i)) for i in range(len(names))) for m in re.finditer(pat, out, re.M)}

def osc_ref(eps, T):
    vals = []
    for dt in (eps * eps * 2.5e-2, eps * eps * 1.25e-2):
        out = run([B + '/tools/oscillatory_reference', '--dt', '%g' % dt, '--tmax', '%g' % T, '--print', '0.8', '--eps', '%g' % eps]).stdout
        vals.append({round(float(m.group(1)), 6): (float(m.group(2)), float(m.group(3))) for m in re.finditer(r'^t (\S+) I1 (\S+) I2 (\S+)', out, re.M) if float(m.group(1)) > 0})
    d = max(abs(a - b) for t in vals[1] for a, b in zip(vals[0][t], vals[1][t]))
    return {t: tuple(f + (f - c) / 31 for c, f in zip(vals[0][t], vals[1][t])) for t in vals[1]}, d

def dns_ref(exe, args, names, dt):
    refs = []
    for h in (dt, dt / 2):
        out = run([B + '/' + exe, '-ts_type', 'rk', '-ts_rk_type', '4', '-ts_dt', '%g' % h, '-no_timing'] + args).stdout
        refs.append(parse(out, names))
    d = max(abs(a - b) for t in refs[1] for a, b in zip(refs[0][t], refs[1][t]))
    return refs[1], d

def adapt(exe, args, names, ref, tol):
    p = run([B + '/' + exe, '-ts_type', 'vshmm', '-no_timing', '-ts_vshmm_warnings_viewer', 'none', '-ts_vshmm_adapt', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol] + args)
    if p.returncode:
        return None, 0, (p.stderr.strip().splitlines() or ['?'])[-1][:100]
    got = parse(p.stdout, names)
    worst, seen = 0, 0
    for t, r in ref.items():
        if t in got and t > 0:
            e = math.sqrt(sum(((g - x) / (1 + abs(x))) ** 2 for g, x in zip(got[t], r)) / len(r))
            worst, seen = max(worst, e), seen + 1
    if not seen:
        return None, 0, 'no sampled time matches the reference'
    w = int(re.search(r'rhs_evaluations (\d+)', p.stdout).group(1))
    m = re.search(r'estimation_evaluations (\d+)', p.stdout)
    warn = 'warned' if 'warning' in p.stderr.lower() or 'warning' in p.stdout.lower() else ''
    return worst / tol, w + (int(m.group(1)) if m else 0), warn

cases = []
for eps in (5e-3, 2e-3):
    for T in (0.8, 2.4):
        cases.append(('oscillators eps=%g t=%g' % (eps, T), 'examples/ode/oscillatory', ['-eps', '%g' % eps, '-ts_max_time', '%g' % T], ['I1', 'I2'], ('osc', eps, T)))
for eps in (3e-2, 3e-3, 1e-3):
    cases.append(('dissipative eps=%g' % eps, 'examples/ode/dissipative', ['-eps', '%g' % eps, '-ts_max_time', '2', '-print_interval', '0.5'], ['xi'], ('dns', min(1e-4, eps * eps / 4))))
for e, n in ((3e-2, 3), (3e-2, 4), (1e-1, 3), (5e-3, 2), (3e-3, 3)):
    cases.append(('chain e=%g scales %d' % (e, n), 'examples/stress/chain', ['-scales', str(n), '-e', '%g' % e, '-print_interval', '0.5'], ['x0'], ('dns', min(1e-3, e ** (n - 1) / 4))))
only = sys.argv[3] if len(sys.argv) > 3 else ''
for name, exe, args, names, how in cases:
    if only and only not in name: continue
    if how[0] == 'osc':
        ref, d = osc_ref(how[1], how[2])
    else:
        ref, d = dns_ref(exe, args, names, how[1])
    with ThreadPoolExecutor(2) as pool:
        res = list(pool.map(lambda tol: adapt(exe, args, names, ref, tol), TOLS))
    print('%-28s ref refine diff %.1e | ' % (name, d) + ' | '.join('%g: %s' % (tol, ('%.2f %.2g %s' % r) if r[0] is not None else r[2]) for tol, r in zip(TOLS, res)), flush=True)
