#!/usr/bin/env python3
"""The accuracy-on-request suite of docs/accuracy.md: every ODE example under
`-ts_type vshmm -ts_vshmm_adapt -ts_rtol tol -ts_atol tol` for tol = 1e-1, 1e-2, 1e-3, with the
largest weighted error over the sampled times against converged references,
|q - q*| / (tol (1 + |q*|)) (2-norm over the observables, as TSVSHMM weighs them; 1 = the
tolerance met), and the work (split evaluations of the accepted steps plus estimation and
rejected tries).

    python3 tools/adapt_suite.py BUILD_DIR [--only SUBSTRING ...] [--jobs N] [-- extra options]

Options after `--` are passed to every run (to try a variant of the control). References:
oscillators docs/ode-experiments.md (RK4 refined to 3.125e-9); dissipative eps = 1e-2
docs/dissipative.md; eps = 1e-4 the averaged equation (error O(eps)); chain the 2-scale RK4 DNS
(x0 of every chain, docs/stress.md).
"""
import math
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

OSC = {0.8: (0.9917765569, 0.2191992747), 1.6: (1.2304052452, 0.1062292854),
       2.4: (1.6617390748, 0.0672940017), 3.2: (2.2970790734, 0.0653347175),
       4.0: (3.1028359265, 0.1136357960)}
DISS2 = {0.5: (3.5919081136,), 1.0: (2.5925732631,), 1.5: (1.7508010332,), 2.0: (1.4816640204,)}
DISS4 = {0.5: (3.59246882,), 1.0: (2.59329491,), 1.5: (1.75107208,), 2.0: (1.48172016,)}
CHAIN = {0.5: (1.16260191,), 1.0: (1.32405634,), 1.5: (1.46656720,), 2.0: (1.58389403,)}


def problems():
    out = []
    for T in (0.8, 4.0):
        ref = {t: v for t, v in OSC.items() if t <= T + 1e-9}
        out.append(('oscillators t=%g' % T, 'examples/ode/oscillatory', ['-ts_max_time', '%g' % T], ['I1', 'I2'], ref))
    out.append(('dissipative eps=1e-2', 'examples/ode/dissipative', ['-eps', '1e-2', '-ts_max_time', '2', '-print_interval', '0.5'], ['xi'], DISS2))
    out.append(('dissipative eps=1e-4', 'examples/ode/dissipative', ['-eps', '1e-4', '-ts_max_time', '2', '-print_interval', '0.5'], ['xi'], DISS4))
    for n in range(2, 7):
        out.append(('chain %d scales' % n, 'examples/stress/chain', ['-scales', str(n), '-print_interval', '0.5'], ['x0'], CHAIN))
    return out


def run(build, prob, tol, extra):
    name, exe, args, names, ref = prob
    cmd = ['%s/%s' % (build, exe), '-ts_type', 'vshmm', '-ts_vshmm_adapt', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol,
           '-no_timing', '-ts_vshmm_warnings_viewer', 'none'] + args + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode:
        return name, tol, None, None, 'failed: ' + (p.stderr.strip().splitlines() or ['?'])[-1][:120]
    worst = 0.0
    pat = r't (\S+)' + ''.join(r' %s (\S+)' % q for q in names)
    for m in re.finditer(pat, p.stdout):
        t = float(m.group(1))
        for tr, r in ref.items():
            if abs(t - tr) < 1e-9:
                e = math.sqrt(sum(((float(m.group(2 + i)) - r[i]) / (tol * (1 + abs(r[i])))) ** 2 for i in range(len(r))) / len(r))
                worst = max(worst, e)
    w = int(re.search(r'rhs_evaluations (\d+)', p.stdout).group(1))
    m = re.search(r'estimation_evaluations (\d+)', p.stdout)
    est = int(m.group(1)) if m else 0
    return name, tol, worst, w + est, 'steps %d + estimates %d' % (w, est)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    argv = sys.argv[1:]
    extra = []
    if '--' in argv:
        i = argv.index('--')
        argv, extra = argv[:i], argv[i + 1:]
    build, only, jobs = argv[0], [], 2
    i = 1
    while i < len(argv):
        if argv[i] == '--only':
            only.append(argv[i + 1])
            i += 2
        elif argv[i] == '--jobs':
            jobs = int(argv[i + 1])
            i += 2
        else:
            sys.exit('unknown argument ' + argv[i])
    probs = [p for p in problems() if not only or any(o in p[0] for o in only)]
    tasks = [(p, tol) for p in probs for tol in (1e-1, 1e-2, 1e-3)]
    with ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(lambda a: run(build, a[0], a[1], extra), tasks))
    print('| problem | tol | largest weighted error | work | |')
    print('|---|---|---|---|---|')
    for name, tol, err, work, note in results:
        print('| %s | %g | %s | %s | %s |' % (name, tol, '%.2f' % err if err is not None else '-', '%.3g' % work if work else '-', note))


if __name__ == '__main__':
    main()
