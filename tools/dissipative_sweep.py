#!/usr/bin/env python3
"""Hand-tuning sweep of TSVSHMM on the dissipative example (eps = 1e-2, DeltaT = 0.1, t <= 2):
240 fixed configurations (micro step x alpha_1 x alpha_2). For each error level it prints the
cheapest configuration whose error (largest over t = 0.5, 1, 1.5, 2 of |xi - xi*| / (1 + |xi*|),
against the converged DNS of docs/dissipative.md) is at most that level, and with --adapt the
runs of -ts_vshmm_adapt at tol 1e-1, 1e-2, 1e-3 beside them (docs/accuracy.md, section 3).

    python3 tools/dissipative_sweep.py BUILD_DIR [--adapt]
"""
import re
import subprocess
import sys

REF = {0.5: 3.5919081136, 1.0: 2.5925732631, 1.5: 1.7508010332, 2.0: 1.4816640204}


def run(exe, args):
    out = subprocess.run([exe, '-ts_max_time', '2', '-no_timing', '-print_interval', '0.5'] + args,
                         capture_output=True, text=True).stdout
    err = 0.0
    for m in re.finditer(r't (\S+) xi (\S+)', out):
        t, x = float(m.group(1)), float(m.group(2))
        for tr, r in REF.items():
            if abs(t - tr) < 1e-9:
                err = max(err, abs(x - r) / (1 + abs(r)))
    m = re.search(r'rhs_evaluations (\d+)', out)
    if not m:
        return None
    work = int(m.group(1))
    m = re.search(r'estimation_evaluations (\d+)', out)
    return err, work + (int(m.group(1)) if m else 0)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    exe = sys.argv[1] + '/examples/ode/dissipative'
    res = []
    for dt in ['2.5e-4', '1.25e-4', '1e-4', '5e-5', '2.5e-5']:
        for a1 in [5, 10, 20, 50, 100, 200, 400, 1000]:
            for a2 in [1, 2, 5, 10, 20, 40]:
                r = run(exe, ['-ts_type', 'vshmm', '-ts_vshmm_micro_dt', dt, '-ts_vshmm_savings_factors', '%d,%d' % (a1, a2)])
                if r:
                    res.append((r[1], r[0], 'dt %s alpha %d,%d' % (dt, a1, a2)))
    res.sort()
    levels = [3e-2, 2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4]
    if '--adapt' in sys.argv:
        for tol in (1e-1, 1e-2, 1e-3):
            e, w = run(exe, ['-ts_type', 'vshmm', '-ts_vshmm_adapt', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol])
            print('adapt tol %g: error %.2e, work %d' % (tol, e, w))
            levels.append(e)
    for lim in sorted(set(levels), reverse=True):
        best = [r for r in res if r[1] <= lim][:2]
        print('error <= %.2e: %s' % (lim, '; '.join('%d evaluations (%.2e, %s)' % b for b in best) if best else 'none'))


if __name__ == '__main__':
    main()
