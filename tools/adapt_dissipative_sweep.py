#!/usr/bin/env python3
"""-ts_vshmm_adapt on the dissipative example at parameters neither the suite nor the variants use
(docs/accuracy.md section 22): eps = 5e-3 and 2e-3, three initial states, sampling intervals 0.1
and 0.5, tolerances 1e-2, 3e-3, 1e-3, component and additive splits (72 runs). Each reference is
RK4 at dt = eps^2 / 8, checked against eps^2 / 16 (their largest difference in xi is printed).
Per run: the largest weighted error of xi over the sampled times |xi - xi*| / (tol (1 + |xi*|))
and the work (split evaluations with the estimates).

    python3 tools/adapt_dissipative_sweep.py BUILD_DIR

About 8 minutes on two cores (the references most of it).
"""
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

STATES = ('5,-10,5', '3,0,0', '1,2,-3')  # (-2, 1, 1) grows eta like e^(4t/eps): its stiffness outruns a fixed RK4 reference step


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    exe = '%s/examples/ode/dissipative' % sys.argv[1]

    def run(args):
        return subprocess.run([exe, '-no_timing', '-ts_vshmm_warnings_viewer', 'none'] + args, capture_output=True, text=True)

    def xi(out):
        return {round(float(m.group(1)), 6): float(m.group(2)) for m in re.finditer(r'^t (\S+) xi (\S+)', out, re.M)}

    def reference(case):
        eps, x0 = case
        dt = eps * eps / 8
        a, b = (xi(run(['-eps', '%g' % eps, '-x0', x0, '-ts_type', 'rk', '-ts_rk_type', '4', '-ts_dt', '%g' % h, '-print_interval', '0.1']).stdout) for h in (dt, dt / 2))
        return case, b, max(abs(a[t] - b[t]) for t in b)

    cases = [(eps, x0) for eps in (5e-3, 2e-3) for x0 in STATES]
    with ThreadPoolExecutor(2) as pool:
        refs = list(pool.map(reference, cases))
    jobs = [(eps, x0, r, diff, DT, tol, kind) for (eps, x0), r, diff in refs for DT in (0.1, 0.5) for tol in (1e-2, 3e-3, 1e-3) for kind in ('component', 'additive')]

    def adaptive(job):
        eps, x0, r, diff, DT, tol, kind = job
        p = run(['-eps', '%g' % eps, '-x0', x0, '-ts_type', 'vshmm', '-ts_dt', '%g' % DT, '-print_interval', '%g' % DT, '-split_kind', kind, '-ts_vshmm_adapt', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol])
        if p.returncode:
            return job, 'failed: ' + (p.stderr.strip().splitlines() or ['?'])[-1][:100], 0
        v = xi(p.stdout)
        e = max(abs(v[t] - r[t]) / (tol * (1 + abs(r[t]))) for t in v if t in r and t > 0)
        w = int(re.search(r'rhs_evaluations (\d+)', p.stdout).group(1)) + int(re.search(r'estimation_evaluations (\d+)', p.stdout).group(1))
        return job, '%.2f' % e, w

    with ThreadPoolExecutor(2) as pool:
        for (eps, x0, r, diff, DT, tol, kind), e, w in pool.map(adaptive, jobs):
            print('eps %g x0 %s (reference refined: %.1e) DeltaT %g tol %g %s: %s tol, work %d' % (eps, x0, diff, DT, tol, kind, e, w), flush=True)


if __name__ == '__main__':
    main()
