#!/usr/bin/env python3
"""The accuracy-on-request suite of docs/accuracy.md: every ODE example under
`-ts_type vshmm -ts_vshmm_adapt -ts_rtol tol -ts_atol tol` for tol = 1e-1, 1e-2, 1e-3, with the
largest weighted error over the sampled times against converged references,
|q - q*| / (tol (1 + |q*|)) (2-norm over the observables, as TSVSHMM weighs them; 1 = the
tolerance met), and the work (split evaluations of the accepted steps plus estimation and
rejected tries).

    python3 tools/adapt_suite.py BUILD_DIR [--only SUBSTRING ...] [--jobs N] [--sweep] [--states]
                                           [--tols T1,T2,...] [--global] [-- extra options]

--tols replaces the three tolerances (e.g. 3e-2,5e-3,2e-3 for the ones between them).

--global runs every problem with -ts_vshmm_adapt_global_estimate and prints, at each sampled time,
the weighted error against the reference, the carried comparison's global estimate and the sum, the
root of the sum of squares and the signed sum of the steps' estimates so far (from -info), then how
each compares with the error over all sampled times (docs/accuracy.md section 21).

Options after `--` are passed to every run (to try a variant of the control). With --sweep, each
problem is also run with fixed parameters over a grid (hand tuning: micro step and savings
factors, written as the paper's and the benchmark's rules scaled), and each adaptive run is set
beside the cheapest fixed configuration whose error is at most its own (the ratio of their work).
With --states the
oscillators also start from three more states (docs/accuracy.md section 2), with references
made here by BUILD_DIR/tools/oscillatory_reference (RK4, dt = 2.5e-8 and 1.25e-8,
Richardson-extrapolated as fifth order; about a minute). References:
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


OTHER_STATES = ['0.8,0.6,0.2,0.3', '1.2,0.4,-0.1,0.6', '0.9,0.7,0.3,0.2']


def oscillator_reference(build, x0, T, eps=1e-3, refinement=None):
    """I1, I2 at 0.8, 1.6, ... T from x0 (None: the example's): RK4 at dt = eps^2 / 40 and eps^2 / 80
    (2.5e-8 and 1.25e-8 at eps = 1e-3), Richardson (fifth order). With a list `refinement`, the
    largest difference of the two runs is appended to it."""
    vals = []
    for dt in (eps * eps / 40, eps * eps / 80):
        out = subprocess.run(['%s/tools/oscillatory_reference' % build, '--dt', '%g' % dt, '--tmax', '%g' % T, '--print', '0.8', '--eps', '%g' % eps]
                             + (['--x0', x0] if x0 else []), capture_output=True, text=True).stdout
        vals.append({round(float(m.group(1)), 6): (float(m.group(2)), float(m.group(3)))
                     for m in re.finditer(r'^t (\S+) I1 (\S+) I2 (\S+)', out, re.M) if float(m.group(1)) > 0})
    if refinement is not None:
        refinement.append(max(abs(a - b) for t in vals[1] for a, b in zip(vals[0][t], vals[1][t])))
    return {t: tuple(f + (f - c) / 31 for c, f in zip(vals[0][t], vals[1][t])) for t in vals[1]}


def problems(build=None, states=False):
    out = []
    if states:
        for x0 in OTHER_STATES:
            ref = oscillator_reference(build, x0, 4.0)
            for T in (0.8, 4.0):
                out.append(('oscillators x0=%s t=%g' % (x0, T), 'examples/ode/oscillatory', ['-ts_max_time', '%g' % T, '-x0', x0], ['I1', 'I2'],
                            {t: v for t, v in ref.items() if t <= T + 1e-9}))
    for T in (0.8, 4.0):
        ref = {t: v for t, v in OSC.items() if t <= T + 1e-9}
        out.append(('oscillators t=%g' % T, 'examples/ode/oscillatory', ['-ts_max_time', '%g' % T], ['I1', 'I2'], ref))
    out.append(('dissipative eps=1e-2', 'examples/ode/dissipative', ['-eps', '1e-2', '-ts_max_time', '2', '-print_interval', '0.5'], ['xi'], DISS2))
    out.append(('dissipative eps=1e-4', 'examples/ode/dissipative', ['-eps', '1e-4', '-ts_max_time', '2', '-print_interval', '0.5'], ['xi'], DISS4))
    for n in range(2, 7):
        out.append(('chain %d scales' % n, 'examples/stress/chain', ['-scales', str(n), '-print_interval', '0.5'], ['x0'], CHAIN))
    return out


def measure(build, prob, options):
    """Runs the example with options; returns (relative error, work, steps, estimates) or a reason."""
    name, exe, args, names, ref = prob
    cmd = ['%s/%s' % (build, exe), '-ts_type', 'vshmm', '-no_timing', '-ts_vshmm_warnings_viewer', 'none'] + args + options
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode:
        return 'failed: ' + (p.stderr.strip().splitlines() or ['?'])[-1][:120]
    worst, seen = 0.0, 0
    pat = r't (\S+)' + ''.join(r' %s (\S+)' % q for q in names)
    for m in re.finditer(pat, p.stdout):
        t = float(m.group(1))
        for tr, r in ref.items():
            if abs(t - tr) < 1e-9:
                e = math.sqrt(sum(((float(m.group(2 + i)) - r[i]) / (1 + abs(r[i]))) ** 2 for i in range(len(r))) / len(r))
                worst, seen = max(worst, e if math.isfinite(e) else float('inf')), seen + 1
    if not seen:
        return 'failed: no sampled time matches the reference'
    w = int(re.search(r'rhs_evaluations (\d+)', p.stdout).group(1))
    m = re.search(r'estimation_evaluations (\d+)', p.stdout)
    est = int(m.group(1)) if m else 0
    return worst, w + est, w, est


def run(build, prob, tol, extra):
    r = measure(build, prob, ['-ts_vshmm_adapt', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol] + extra)
    if isinstance(r, str):
        return prob[0], tol, None, None, r
    return prob[0], tol, r[0] / tol, r[1], 'steps %d + estimates %d' % (r[2], r[3])


def global_rows(build, prob, tol, extra):
    """(t, weighted error, global estimate, sum of the steps' estimates) at the sampled times of a
    run with -ts_vshmm_adapt_global_estimate, or a reason."""
    name, exe, args, names, ref = prob
    cmd = ['%s/%s' % (build, exe), '-ts_type', 'vshmm', '-no_timing', '-ts_vshmm_warnings_viewer', 'none'] + args + [
        '-ts_vshmm_adapt', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol, '-ts_vshmm_adapt_global_estimate', '-info'] + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode:
        return 'failed: ' + (p.stderr.strip().splitlines() or ['?'])[-1][:120]
    est = {round(float(m.group(1)), 6): (float(m.group(2)), float(m.group(3)))
           for m in re.finditer(r'carried comparison at t = (\S+): global estimate (\S+) .*sum to (\S+)', p.stdout)}
    acc = {round(float(m.group(1)), 6): (float(m.group(2)), float(m.group(3)))
           for m in re.finditer(r"accepted steps' estimates at t = (\S+): sum \S+, root of the sum of squares (\S+), signed sum (\S+)", p.stdout)}
    rows = []
    for m in re.finditer(r'^t (\S+)' + ''.join(r' %s (\S+)' % q for q in names), p.stdout, re.M):
        t = float(m.group(1))
        for tr, r in ref.items():
            if abs(t - tr) < 1e-9 and round(t, 6) in est:
                e = math.sqrt(sum(((float(m.group(2 + i)) - r[i]) / (tol * (1 + abs(r[i])))) ** 2 for i in range(len(r))) / len(r))
                rows.append((t, e) + est[round(t, 6)] + acc.get(round(t, 6), (float('nan'), float('nan'))))
    return rows


def print_global(results):
    print('| problem | tol | sampled times: t: true / global / sum / root of the sum of squares / signed sum of the steps\' estimates |')
    print('|---|---|---|')
    kinds = (('global', 2), ('sum', 3), ('rss', 4), ('signed', 5))
    ratios = {k: [] for k, _ in kinds}
    runs = {k: [] for k, _ in kinds}
    for name, tol, rows in results:
        if isinstance(rows, str) or not rows:
            print('| %s | %g | %s |' % (name, tol, rows or 'no sampled time'))
            continue
        print('| %s | %g | %s |' % (name, tol, ', '.join('%g: %.2g / %.2g / %.2g / %.2g / %.2g' % r for r in rows)))
        for k, i in kinds:
            if any(not (r[i] >= 0) for r in rows):  # no signed sum without observables
                continue
            ratios[k] += [r[i] / r[1] for r in rows if r[1] > 0]
            if max(r[1] for r in rows) > 0:
                runs[k].append(max(r[i] for r in rows) / max(r[1] for r in rows))
    for k, _ in kinds:
        v, w = sorted(ratios[k]), sorted(runs[k])
        if not v:
            continue
        print('%s / true error at %d sampled times: median %.2f, within [1/2, 2] at %d, below 1/2 at %d; largest over a run below half the largest true error in %d of %d runs'
              % (k, len(v), v[len(v) // 2], sum(0.5 <= x <= 2 for x in v), sum(x < 0.5 for x in v), sum(x < 0.5 for x in w), len(w)))


def grid(prob):
    """Fixed configurations (label, options) of the hand-tuning sweep of a problem."""
    name = prob[0]
    out = []
    if name.startswith('chain'):
        # the benchmark's ladder (docs/stress.md: dt = e^K, mean h_1 = e/2, mean h_j = e^(j-1)),
        # h_1 scaled by f (f = 0: alpha_1 = 1, the slow pair all but merged) and the faster steps
        # by g, dt by d
        K, e = int(name.split()[1]) - 1, 1e-2
        for d in (1.0, 0.5, 0.25):
            dt = d * e ** K
            for f in (0, 0.0625, 0.125, 0.25, 0.5, 1, 2):
                for g in (0.25, 0.5, 1):
                    alpha = [f * (e / 2) / dt if f > 0 else 1.0] + [g * e ** (j - 1) / dt for j in range(2, K + 1)]
                    out.append(('dt %g, h1 %g e/2, h_j %g e^(j-1)' % (dt, f, g),
                                ['-ts_vshmm_micro_dt', '%g' % dt, '-ts_vshmm_savings_factors', ','.join('%g' % a for a in alpha)]))
    elif name.startswith('dissipative eps=1e-2'):
        for dt in (2.5e-4, 1.25e-4, 1e-4, 5e-5, 2.5e-5):
            for a1 in (5, 10, 20, 50, 100, 200, 400, 1000):
                for a2 in (1, 2, 5, 10, 20, 40):
                    out.append(('dt %g alpha %d,%d' % (dt, a1, a2), ['-ts_vshmm_micro_dt', '%g' % dt, '-ts_vshmm_savings_factors', '%d,%d' % (a1, a2)]))
    elif name.startswith('oscillators'):
        # separations sigma_0 (slow/medium), sigma_1 (medium/fast) of docs/accuracy.md section 1
        for dt in (5e-8, 1e-7, 2e-7):
            for s0 in (5, 10, 20, 40, 80):
                for s1 in (3, 5, 10, 20):
                    A1 = dt * 1000 / s1
                    A0 = A1 * 1000 / s0
                    out.append(('dt %g sigma %g,%g' % (dt, s0, s1), ['-ts_vshmm_micro_dt', '%g' % dt, '-ts_vshmm_savings_factors',
                                                                   '%g,%g' % (A0 / dt - A1 / dt, A1 / dt - 1)]))
    return out


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    argv = sys.argv[1:]
    extra = []
    if '--' in argv:
        i = argv.index('--')
        argv, extra = argv[:i], argv[i + 1:]
    build, only, jobs, sweep, states, tols, glob = argv[0], [], 2, False, False, (1e-1, 1e-2, 1e-3), False
    i = 1
    while i < len(argv):
        if argv[i] == '--only':
            only.append(argv[i + 1])
            i += 2
        elif argv[i] == '--states':
            states = True
            i += 1
        elif argv[i] == '--sweep':
            sweep = True
            i += 1
        elif argv[i] == '--tols':
            tols = tuple(float(t) for t in argv[i + 1].split(','))
            i += 2
        elif argv[i] == '--global':
            glob = True
            i += 1
        elif argv[i] == '--jobs':
            jobs = int(argv[i + 1])
            i += 2
        else:
            sys.exit('unknown argument ' + argv[i])
    probs = [p for p in problems(build, states) if not only or any(o in p[0] for o in only)]
    tasks = [(p, tol) for p in probs for tol in tols]
    if glob:
        with ThreadPoolExecutor(jobs) as pool:
            print_global(list(pool.map(lambda a: (a[0][0], a[1], global_rows(build, a[0], a[1], extra)), tasks)))
        return
    with ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(lambda a: run(build, a[0], a[1], extra), tasks))
    fixed = {}
    if sweep:
        for p in probs:
            configs = grid(p)
            with ThreadPoolExecutor(jobs) as pool:
                rs = list(pool.map(lambda c: (c[0], measure(build, p, c[1] + extra)), configs))
            fixed[p[0]] = sorted((r[1], r[0], label) for label, r in rs if not isinstance(r, str))
    print('| problem | tol | largest weighted error | work | | cheapest fixed configuration with at most that error: work (error), ratio |')
    print('|---|---|---|---|---|---|')
    for name, tol, err, work, note in results:
        best = '-'
        if name in fixed and err is not None:
            ok = [f for f in fixed[name] if f[1] <= err * tol]
            best = '%.3g (%.2g, %s), %.2fx' % (ok[0][0], ok[0][1], ok[0][2], work / ok[0][0]) if ok else 'none of %d' % len(fixed[name])
        print('| %s | %g | %s | %s | %s | %s |' % (name, tol, '%.2f' % err if err is not None else '-', '%.3g' % work if work else '-', note, best))


if __name__ == '__main__':
    main()
