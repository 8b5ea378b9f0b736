#!/usr/bin/env python3
"""Work-precision benchmark of TSVSHMM against the integrators a user would pick instead.

    python3 bench/run_bench.py --build build [--quick] [--out DIR] [--docs]

Runs every problem with every method over its accuracy parameter (the examples as they are, with
options, and the drivers of bench/), measures the error against converged references and the
cost, and writes into DIR (default BUILD/bench or BUILD/bench-quick):
  results.csv       one row per run
  references.txt    the references and their refinement
  tables.md         the tables of docs/performance.md
  *.png, *.svg      the work-precision figures (gnuplot)
With --docs the tables replace the generated blocks of docs/performance.md and the figures are
copied to docs/figures/ (what `make bench` does).

Error: for the ODE problems, max over the sampled times t_i and the observables q (oscillators:
I1, I2; dissipative: xi; chain: x0) of |q(t_i) - q*(t_i)| / (1 + |q*(t_i)|), i.e. the weighted
error of PETSc's tolerances with atol = rtol = 1 in the max norm (an error of 1e-2 = the tolerance
atol = rtol = 1e-2 met at every sample). For the spectral scenes, max over the output times of
the relative L2 error of the grid solution against the reference DNS.
Cost: `calls` = calls of the user's functions (full field, split, IMEX or MRI part, spectral
level field); `ffe` = full-field equivalents = terms f_k evaluated / number of terms (a split call
is 1/(K+1) of a full field; spectral: level-field evaluations, each one inverse and one forward
FFT like a full field); `jac` = Jacobian evaluations (implicit methods, not in calls); wall time
of the solve, all runs of one problem back to back in one process of this script.
Standard library only (Python 3.7+).
"""
import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# ---------------------------------------------------------------------------------------------
# Spectral options: every option name of the spectral examples used here is in this table, so
# that a rename (e.g. a prefix) is one edit.
SPECTRAL_OPTS = {
    'scene': '-options_file_yaml',          # PETSc's, the scene file comes first
    'mode': '-spectral_mode',               # dns | sparse
    'output_times': '-output_times',
    'grid_file': '-grid_solution_file',
    'compare': '-compare_grid_solution',
}
SPECTRAL_SCENES = {
    # name: scene file, program, final time (full), final time (quick), reference DNS step
    'diffusion': dict(scene='examples/scenes/diffusion.yaml', exe='examples/spectral/diffusion',
                      T=1.0, Tquick=0.25, dt_ref=1e-6, nout=4, search_t=0.01),  # DNS: fast growth, dear runs
    'advection': dict(scene='examples/scenes/advection.yaml', exe='examples/spectral/advection',
                      T=36.0, Tquick=9.0, dt_ref=4e-5, nout=4, search_t=None),  # advection: slow growth, search to T
}

# Converged references of the ODE problems (docs/ode-experiments.md "Converged references", RK4
# refined to 3.125e-9, converged to ~1e-7; docs/dissipative.md, RK4 refined to 6.25e-7).
OSC_REF = {0.8: (0.9917765569, 0.2191992747), 1.6: (1.2304052452, 0.1062292854),
           2.4: (1.6617390748, 0.0672940017), 3.2: (2.2970790734, 0.0653347175),
           4.0: (3.1028359265, 0.1136357960)}
DISS_REF_1E2 = {0.5: (3.5919081136,), 1.0: (2.5925732631,), 1.5: (1.7508010332,), 2.0: (1.4816640204,)}


class Bench:
    def __init__(self, args):
        self.build = os.path.abspath(args.build)
        self.quick = args.quick
        self.out = os.path.abspath(args.out or os.path.join(self.build, 'bench-quick' if args.quick else 'bench'))
        os.makedirs(self.out, exist_ok=True)
        self.work = os.path.join(self.out, 'work')
        os.makedirs(self.work, exist_ok=True)
        self.timeout = args.timeout or (30 if self.quick else 150)
        self.max_evals = 4e6 if self.quick else 1e8  # fixed-step runs predicted above this are skipped
        self.max_steps = '200000' if self.quick else '5000000'  # step limit of the adaptive runs
        self.rows = []
        self.notes = []
        self.refnotes = []
        self.sundials = os.path.exists(self.exe('bench/bench_sundials'))
        self.log = open(os.path.join(self.out, 'runs.log'), 'w')

    def exe(self, rel):
        return os.path.join(self.build, rel)

    # --- running ----------------------------------------------------------------------------
    def run(self, cmd, timeout=None):
        """Run a command; returns (stdout, status) with status 'ok', 'failed' or 'timeout'."""
        timeout = timeout or self.timeout
        self.log.write('$ ' + ' '.join(cmd) + '\n')
        self.log.flush()
        try:
            # -options_left: PETSc lists the options no object read, so that a misspelt or renamed
            # option fails the run instead of running something else (the spectral runs once ran
            # their "DNS" as the sparse scene after -mode was renamed -spectral_mode)
            env = dict(os.environ, PETSC_OPTIONS=(os.environ.get('PETSC_OPTIONS', '') + ' -options_left').strip())
            p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout,
                               universal_newlines=True, cwd=self.work, env=env)
        except subprocess.TimeoutExpired:
            self.log.write('  timeout after %g s\n' % timeout)
            return '', 'timeout'
        self.log.write(p.stdout[-3000:] + '\n')
        if 'There are options you set that were not used' in p.stdout or 'There is one unused database option' in p.stdout:
            # a scene file's TSVSHMM parameters are not read when the run asks for another TS type
            # (the spectral DNS and explicit sparse runs); any other unused option fails the run
            left = re.findall(r'^Option left: name:(\S+)', p.stdout, re.M)
            ts_type = cmd[cmd.index('-ts_type') + 1] if '-ts_type' in cmd[:-1] else None
            if not (left and ts_type not in (None, 'vshmm') and all(o.startswith('-ts_vshmm_') for o in left)):
                self.log.write('  unused PETSc options: the run does not do what the benchmark asks\n')
                return p.stdout, 'unused option'
        if 'budget exceeded' in p.stdout:
            return p.stdout, 'budget'
        m = re.search(r'^ts_type \S+ steps (\d+)', p.stdout, re.M)
        if m and int(m.group(1)) >= int(self.max_steps) and '-ts_max_steps' in cmd:
            return p.stdout, 'budget'
        return p.stdout, ('ok' if p.returncode == 0 else 'failed')

    def record(self, problem, method, config, err, calls, ffe, jac, wall, status, family=None):
        row = dict(problem=problem, method=method, family=family or method, config=config,
                   error=err, calls=calls, ffe=ffe, jac=jac, wall=wall, status=status)
        self.rows.append(row)
        print('  %-23s %-34s err %-9s calls %-9s ffe %-9s wall %s %s' % (
            method, config[:34], fmt(err), fmt(calls), fmt(ffe), fmt(wall), '' if status == 'ok' else status))
        sys.stdout.flush()

    # --- ODE problems -----------------------------------------------------------------------
    def ode_error(self, samples, ref):
        """max over the reference times of |q - q*| / (1 + |q*|); inf if a time or value is missing."""
        err = 0.0
        for t, qref in ref.items():
            got = None
            for ts, q in samples:  # the first sample printed at t (4 decimals in the examples' output)
                if abs(ts - t) <= 5e-5 and got is None:
                    got = q
            if got is None or len(got) < len(qref) or any(not math.isfinite(v) for v in got):
                return math.inf
            for a, b in zip(got, qref):
                err = max(err, abs(a - b) / (1.0 + abs(b)))
        return err

    @staticmethod
    def parse_example(out, obs):
        """Samples of an example's output: lines 't T NAME v [NAME v]' (and 'final t ...')."""
        samples = []
        for line in out.splitlines():
            m = re.match(r'^(?:final )?t ([-+0-9.eE]+) (.*)$', line)
            if m:
                vals = re.findall(r'(\w+) ([-+0-9.eE]+|nan|inf|-inf)', m.group(2))
                d = {k: float(v) for k, v in vals}
                if all(o in d for o in obs):
                    samples.append((float(m.group(1)), tuple(d[o] for o in obs)))
        return samples

    @staticmethod
    def parse_driver(out):
        samples = []
        for line in out.splitlines():
            if line.startswith('sample '):
                v = [float(x) for x in line.split()[1:]]
                samples.append((v[0], tuple(v[1:])))
        return samples

    @staticmethod
    def value(out, key, default=None):
        m = re.findall(r'^%s ([-+0-9.eE]+)' % re.escape(key), out, re.M)
        return float(m[-1]) if m else default

    def vshmm_calls(self, out):
        """Split calls of a VSHMM run: steps + estimation/rejected + stability check (from -ts_view)."""
        work = re.search(r'work: .* (\d+) split RHS evaluations', out)
        est = re.search(r'(\d+) split RHS evaluations for estimates', out)
        stab = re.search(r'stability check: .* (\d+) split RHS evaluations', out)
        n = int(work.group(1)) if work else self.value(out, 'rhs_evaluations', math.nan)
        return n + (int(est.group(1)) if est else 0) + (int(stab.group(1)) if stab else 0)

    def ode_problem(self, name, prog, base, obs, ref, nterms, methods):
        """Run every method on one ODE problem. base: options of the example for the problem."""
        print('\n== %s' % name)
        T = max(ref)
        times = ','.join('%g' % t for t in sorted(ref))
        prog_exe = self.exe(prog)
        for meth in methods:
            kind = meth[0]
            if kind == 'vshmm':  # explicit parameters: list of (label, options)
                for label, opts in meth[2]:
                    out, st = self.run([prog_exe] + base + ['-ts_type', 'vshmm', '-ts_max_time', '%g' % T, '-ts_view'] + opts)
                    self.finish_example(name, meth[1], label, out, st, obs, ref, nterms, vshmm=True)
            elif kind == 'vshmm-adapt':
                for tol in meth[2]:
                    out, st = self.run([prog_exe] + base + ['-ts_type', 'vshmm', '-ts_vshmm_adapt', '-ts_rtol', '%g' % tol,
                                                            '-ts_atol', '%g' % tol, '-ts_max_time', '%g' % T, '-ts_view'])
                    self.finish_example(name, meth[1], 'tol %g' % tol, out, st, obs, ref, nterms, vshmm=True)
            elif kind == 'rk-fixed':  # (kind, label, rk type, [dt...]), the dts dividing the sample interval
                for dt in meth[3]:
                    interval = min(ref)
                    n = max(1, int(round(interval / dt)))
                    dt = interval / n
                    stages = {'4': 4, '3': 3, '5dp': 7}.get(meth[2], 4)
                    if stages * T / dt > self.max_evals:
                        self.note('%s, %s dt = %.3g: skipped (%.2g evaluations, beyond the budget of this sweep)' % (name, meth[1], dt, stages * T / dt))
                        continue
                    out, st = self.run([prog_exe] + base + ['-ts_type', 'rk', '-ts_rk_type', meth[2], '-ts_dt', '%.17g' % dt,
                                                            '-ts_max_time', '%g' % T])
                    self.finish_example(name, meth[1], 'dt %.3g' % dt, out, st, obs, ref, nterms)
            elif kind == 'rk-stable':  # the largest stable step, found by bisection
                if 4 * T / meth[3] > self.max_evals:
                    self.note('%s, %s: not run: about %.2g evaluations at the stability limit (%.3g), beyond the budget of this sweep' % (name, meth[1], 4 * T / meth[3], meth[3]))
                    continue
                dt = self.search_stable(name, prog_exe, base, meth[2], T, min(ref), meth[3])
                if dt:
                    out, st = self.run([prog_exe] + base + ['-ts_type', 'rk', '-ts_rk_type', meth[2], '-ts_dt', '%.17g' % dt,
                                                            '-ts_max_time', '%g' % T])
                    self.finish_example(name, meth[1], 'dt %.4g (largest stable)' % dt, out, st, obs, ref, nterms)
            elif kind == 'rk-adapt':
                for tol in meth[3]:
                    out, st = self.run([prog_exe] + base + ['-ts_type', 'rk', '-ts_rk_type', meth[2], '-ts_adapt_type', 'basic',
                                                            '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol, '-ts_dt', '1e-10', '-ts_max_steps', self.max_steps,
                                                            '-ts_max_time', '%g' % T, '-ts_time_span', '0,' + times])
                    self.finish_example(name, meth[1], 'tol %g' % tol, out, st, obs, ref, nterms)
            elif kind == 'mprk':
                for mtype, dt in meth[2]:
                    if 4 * T / dt > self.max_evals:
                        self.note('%s, %s %s dt = %.3g: not run (about %.2g evaluations, beyond the budget of this sweep)' % (name, meth[1], mtype, dt, 4 * T / dt))
                        continue
                    out, st = self.run([prog_exe] + base + ['-ts_type', 'mprk', '-ts_mprk_type', mtype, '-ts_dt', '%.17g' % dt,
                                                            '-ts_max_time', '%g' % T])
                    self.finish_example(name, meth[1], '%s dt %.3g' % (mtype, dt), out, st, obs, ref, nterms)
            elif kind == 'imex':  # bench_imex, (kind, label, driver options, [tol...])
                for tol in meth[3]:
                    out, st = self.run([self.exe('bench/bench_imex')] + meth[2] + ['-times', times, '-ts_adapt_type', 'basic',
                                                                                  '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol])
                    self.finish_driver(name, meth[1], 'tol %g' % tol, out, st, ref, nterms)
            elif kind == 'sundials':  # (kind, label, driver options, [(config label, options)...])
                if not self.sundials:
                    continue
                for label, opts in meth[3]:
                    out, st = self.run([self.exe('bench/bench_sundials')] + meth[2] + opts + ['-times', times])
                    self.finish_driver(name, meth[1], label, out, st, ref, nterms)
        self.flush()

    def finish_example(self, problem, method, config, out, st, obs, ref, nterms, vshmm=False):
        samples = self.parse_example(out, obs)
        err = self.ode_error(samples, ref) if st == 'ok' else math.inf
        if vshmm:
            calls = self.vshmm_calls(out)
            ffe = calls / nterms
        else:
            calls = self.value(out, 'rhs_evaluations', math.nan)
            ffe = calls
        self.record(problem, method, config, err, calls, ffe, 0, self.value(out, 'wall_time', math.nan), st)

    def finish_driver(self, problem, method, config, out, st, ref, nterms):
        samples = self.parse_driver(out)
        err = self.ode_error(samples, ref) if st == 'ok' else math.inf
        self.record(problem, method, config, err, self.value(out, 'calls', math.nan),
                    self.value(out, 'term_evaluations', math.nan) / nterms,
                    self.value(out, 'jacobian_evaluations', 0), self.value(out, 'wall_time', math.nan), st)

    def search_stable(self, name, prog_exe, base, rktype, T, interval, guess):
        """Largest step (interval/n) for which an RK run to T stays bounded: bisection on n."""
        def stable(n):
            dt = interval / n
            out, st = self.run([prog_exe] + base + ['-ts_type', 'rk', '-ts_rk_type', rktype, '-ts_dt', '%.17g' % dt,
                                                    '-ts_max_time', '%g' % T], timeout=self.timeout)
            if st != 'ok' or re.search(r'nan|inf', out, re.I):
                return False
            vals = [float(v) for v in re.findall(r'(?: I1| I2| xi| x0|^max_abs_state) ([-+0-9.eE]+)', out, re.M)]
            return bool(vals) and max(abs(v) for v in vals) < 1e3
        lo = max(1, int(interval / guess / 4))  # probably unstable
        hi = int(interval / guess * 4) + 1       # probably stable
        while not stable(hi):
            hi *= 2
            if hi > 1e9:
                return None
        while lo > 1 and stable(lo):
            lo //= 2
        if stable(lo):
            return interval / lo
        steps = 5 if self.quick else 12
        for _ in range(steps):
            if hi - lo <= max(1, hi // 200):
                break
            mid = (lo + hi) // 2
            if stable(mid):
                hi = mid
            else:
                lo = mid
        self.note('%s: largest stable TSRK %s step %.4g (bisection: %.4g unstable)' % (name, rktype, interval / hi, interval / lo))
        return interval / hi

    def note(self, text):
        self.notes.append(text)
        self.log.write('NOTE ' + text + '\n')

    # --- spectral scenes --------------------------------------------------------------------
    def spectral(self, name):
        sc = SPECTRAL_SCENES[name]
        O = SPECTRAL_OPTS
        T = sc['Tquick'] if self.quick else sc['T']
        outs = [T * (i + 1) / sc['nout'] for i in range(sc['nout'])]
        times = ','.join('%g' % t for t in outs)
        exe = self.exe(sc['exe'])
        scene = [O['scene'], os.path.join(ROOT, sc['scene'])]
        ts = sc['search_t'] or T  # the DNS stability search runs to this time
        print('\n== spectral %s (t = %s)' % (name, times))
        prob = 'spectral %s' % name
        ref = os.path.join(self.work, '%s_ref' % name)

        def go(label, method, opts, compare=True, tms=times, record=True):
            cmd = [exe] + scene + opts + [O['output_times'], tms]
            if compare:
                cmd += [O['compare'], ref]
            out, st = self.run(cmd)
            errs = [float(e) for e in re.findall(r'relative_l2_error ([-+0-9.eE]+|nan|inf|-nan)', out)]
            err = max(errs) if errs and st == 'ok' and len(errs) >= len(tms.split(',')) else math.inf
            if err != err:
                err = math.inf
            lines = re.findall(r'^output t .*$', out, re.M)
            last = lines[-1] if lines else ''
            def field(k):
                m = re.search(k + r' ([-+0-9.eE]+)', last)
                return float(m.group(1)) if m else math.nan
            calls = field('split_evaluations') if 'VSHMM' in method else field('rhs_evaluations')
            ffe = field('rhs_evaluations')
            wall = sum(float(w) for w in re.findall(r'^output t .* wall_time ([-+0-9.eE]+)', out, re.M)[-1:])
            if record:
                self.record(prob, method, label, err, calls, ffe, 0, wall, st)
            return err

        # reference: DNS, RK3, dt_ref; grid files at the output times and at the search time
        dns = [O['mode'], 'dns', '-ts_type', 'rk', '-ts_rk_type', '3']
        dtr = sc['dt_ref'] * (1.5 if self.quick else 1.0)
        t0 = time.time()
        out, st = self.run([exe] + scene + dns + ['-ts_dt', '%g' % dtr, O['output_times'], ('%g,%s' % (ts, times)) if ts < T else times,
                                                  O['grid_file'], ref], timeout=20 * self.timeout)
        if st != 'ok':
            self.note('spectral %s: reference DNS failed (%s); scene skipped' % (name, st))
            return
        self.refnotes.append('spectral %s: reference DNS RK3 dt = %g to t = %g (%.0f s)' % (name, dtr, T, time.time() - t0))

        def stable(mode_opts, dt, horizon):
            return go('', '', mode_opts + ['-ts_dt', '%.6g' % dt], tms='%g' % horizon, record=False) < 0.5

        def search(mode_opts, guess, horizon):
            lo, hi = guess / 8, guess * 2
            while not stable(mode_opts, lo, horizon):
                lo /= 2
            while stable(mode_opts, hi, horizon):
                hi *= 2
            for _ in range(5 if self.quick else 8):
                mid = math.sqrt(lo * hi)
                if stable(mode_opts, mid, horizon):
                    lo = mid
                else:
                    hi = mid
            self.note('spectral %s, %s: largest stable RK3 step %.4g (%.4g unstable; bisection, runs to t = %g)' % (name, 'DNS' if O['mode'] in mode_opts else 'sparse', lo, hi, horizon))
            return lo

        dt_dns = search(dns, 1e-5 if name == 'diffusion' else 1e-4, ts)
        for _ in range(6):  # a short search horizon can miss a slow growth: check the step on the whole run
            if go('dt %.3g (largest stable)' % dt_dns, 'DNS RK3', dns + ['-ts_dt', '%.6g' % dt_dns]) < 0.5:
                break
            self.rows.pop()
            self.note('spectral %s, DNS: RK3 step %.4g unstable over the whole run; 5%% smaller' % (name, dt_dns))
            dt_dns *= 0.95
        # the reference against the DNS at the largest stable step: its own convergence
        sparse = ['-ts_type', 'rk', '-ts_rk_type', '3']
        dt_sp = search(sparse, 1e-5 if name == 'diffusion' else 1e-3, T)  # the sparse runs are cheap: to T
        for f in ([1] if self.quick else [1, 2, 4]):
            go('dt %.3g%s' % (dt_sp / f, ' (largest stable)' if f == 1 else ''), 'sparse RK3', sparse + ['-ts_dt', '%.6g' % (dt_sp / f)])
        scales = [0.5, 1] if self.quick else [0.25, 0.5, 1, 2, 4]
        base_alpha = {'diffusion': [150, 18, 1.5], 'advection': [26, 9, 2]}[name]
        for s in scales:
            alpha = ','.join('%g' % max(1.0, a * s) for a in base_alpha)
            go('scene alpha x%g (%s)' % (s, alpha), 'VSHMM ladder', ['-ts_vshmm_savings_factors', alpha])
        if not self.quick:
            go('tol 1e-2', 'VSHMM adapt', ['-ts_vshmm_adapt', '-ts_rtol', '1e-2', '-ts_atol', '1e-2'])
        self.flush()

    # --- cost per evaluation -------------------------------------------------------------------
    def overhead(self):
        print('\n== cost per evaluation')
        ns = [4, 100000] if self.quick else [4, 1000000]
        self.overheads = []
        for n in ns:
            out, st = self.run([self.exe('bench/bench_overhead'), '-n', str(n), '-cycles', '2000' if n < 100 else '40',
                                '-repeat', '5' if n < 100 else '1'], timeout=10 * self.timeout)
            d = dict(n=n, status=st)
            for key in ['rk4_per_rhs_call', 'vshmm_cosine_per_split_call', 'vshmm_exponential_per_split_call',
                        'setup_with_stability_check', 'setup_without_stability_check']:
                d[key] = self.value(out, key, math.nan)
            for kern in ['cosine', 'exponential']:
                m = re.search(r'vshmm_%s_per_split_call \S+ per_level_evaluation (\S+)' % kern, out)
                d[kern + '_per_level'] = float(m.group(1)) if m else math.nan
            m = re.search(r'stability_evaluations (\d+)', out)
            d['stability_evaluations'] = int(m.group(1)) if m else 0
            self.overheads.append(d)
            print('  n %d: %s' % (n, d))

    # --- output -----------------------------------------------------------------------------
    def load_previous(self):
        """--keep: read the previous run's rows, notes and overheads from the output directory."""
        import json
        path = os.path.join(self.out, 'results.csv')
        state = os.path.join(self.out, 'state.json')
        self.prev = None
        if os.path.exists(path) and os.path.exists(state):
            with open(path) as f:
                old = list(csv.DictReader(f))
            for r in old:
                for k in ('error', 'calls', 'ffe', 'jac', 'wall'):
                    r[k] = float(r[k]) if r[k] not in ('', None) else math.nan
            self.prev = dict(rows=old, **json.load(open(state)))

    def merged(self):
        """(rows, notes, refnotes, overheads): this run's, plus the previous run's for what this run did not redo."""
        prev = getattr(self, 'prev', None)
        ov = getattr(self, 'overheads', None)
        if not prev:
            return self.rows, self.notes, self.refnotes, ov
        redone = []
        for r in self.rows:
            if r['problem'] not in redone:
                redone.append(r['problem'])
        rows, done = [], set()
        for r in prev['rows']:
            if r['problem'] in redone:
                if r['problem'] not in done:
                    rows += [n for n in self.rows if n['problem'] == r['problem']]
                    done.add(r['problem'])
            else:
                rows.append(r)
        rows += [n for n in self.rows if n['problem'] not in done]
        keep = lambda n: not any(n.startswith(p + ':') or n.startswith(p + ',') for p in redone)
        notes = [n for n in prev['notes'] if keep(n) and n not in self.notes] + self.notes
        refnotes = [n for n in prev['refnotes'] if n not in self.refnotes] + self.refnotes
        return rows, notes, refnotes, ov or prev.get('overheads')

    def flush(self):
        import json
        rows, notes, refnotes, ov = self.merged()
        with open(os.path.join(self.out, 'state.json'), 'w') as f:
            json.dump(dict(notes=notes, refnotes=refnotes, overheads=ov), f, indent=1)
        with open(os.path.join(self.out, 'results.csv'), 'w', newline='') as f:
            w = csv.DictWriter(f, fieldnames=['problem', 'method', 'family', 'config', 'error', 'calls', 'ffe', 'jac', 'wall', 'status'])
            w.writeheader()
            for r in rows:
                w.writerow(r)


def fmt(x, digits=2):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return '-'
    if isinstance(x, float) and math.isinf(x):
        return 'inf'
    if x == 0:
        return '0'
    if abs(x) >= 1e4 or abs(x) < 1e-2:
        return ('%.' + str(digits - 1) + 'e') % x
    return ('%.' + str(digits + 1) + 'g') % x


# ---------------------------------------------------------------------------------------------
# The sweeps
def osc_alphas(sigma0, sigma1, radius=1000.0):
    """Savings factors for effective separations sigma_0 (slow/medium), sigma_1 (medium/fast) of the
    oscillators (docs/accuracy.md: A_l = dt (1 + alpha_(l+1) + ... + alpha_K), sigma_l = 1000 A_(l+1) / A_l)."""
    a2 = radius / sigma1 - 1.0
    a1 = radius * (1.0 + a2) / sigma0 - 1.0 - a2
    return '%.6g,%.6g' % (a1, a2)


def ode_sweeps(b, quick):
    """(name, program, base options, observables, reference, number of terms, methods) of every ODE problem."""
    Q = quick
    budget_steps = b.max_steps  # step limit of the adaptive peers (a run that hits it has no error)
    sun_cap = ['-max_steps', budget_steps, '-max_calls', '%d' % b.max_evals]
    pet_cap = ['-ts_max_steps', '200000' if Q else '500000']  # ARKIMEX: implicit steps are dear
    problems = []
    # --- resonant oscillators, eps = 1e-3
    for T in (0.8, 4.0):
        ref = {t: v for t, v in OSC_REF.items() if t <= T + 1e-9}
        sig = [(10, 5), (40, 5)] if Q else [(5, 5), (8, 5), (10, 5), (20, 5), (40, 5), (80, 5)]
        dts = [1e-7] if Q else [1e-7, 5e-8]
        ladder = [('dt %g sigma %g,%g' % (dt, s0, s1), ['-ts_dt', '0.8', '-ts_vshmm_micro_dt', '%g' % dt,
                   '-ts_vshmm_savings_factors', osc_alphas(s0, s1)]) for dt in dts for s0, s1 in sig]
        ladder.append(('paper: dt 1e-7, alpha 68200,330', ['-ts_dt', '0.8', '-ts_vshmm_micro_dt', '1e-7', '-ts_vshmm_savings_factors', '68200,330']))
        tols = [1e-1, 1e-2] if Q else [1e-1, 3e-2, 1e-2, 3e-3, 1e-3]
        L = T > 1  # t = 4: the peers that cannot reach 1e-1 within the budget get fewer points
        tl = lambda ts: [('tol %g' % t, ['-rtol', '%g' % t, '-atol', '%g' % t]) for t in ts]
        methods = [
            ('vshmm', 'VSHMM ladder', ladder),
            ('vshmm-adapt', 'VSHMM adapt', tols),
            ('rk-stable', 'RK4 largest stable', '4', 2.8e-6),
            ('rk-fixed', 'RK4 fixed', '4', [4e-7] if Q else [1e-6, 4e-7, 2e-7] if L else [1e-6, 4e-7, 2e-7, 1e-7, 7e-8, 5e-8, 3.5e-8]),
            ('rk-adapt', 'RK 5dp adaptive', '5dp', [1e-2] if Q else [1e-2, 1e-4] if L else [1e-1, 1e-2, 1e-3, 1e-4]),
            ('imex', 'ARKIMEX (fast implicit)', ['-problem', 'oscillators'] + pet_cap, [1e-3] if Q else [1e-2, 1e-4] if L else [1e-2, 1e-3, 1e-4, 1e-5]),
            ('sundials', 'CVODE Adams', ['-problem', 'oscillators', '-method', 'cvode-adams'] + sun_cap + ([] if Q else ['-max_steps', '25000000']),
             tl([1e-4] if Q else [1e-6, 1e-8] if L else [1e-4, 1e-6, 1e-7, 1e-8, 1e-9])),
            ('sundials', 'CVODE BDF', ['-problem', 'oscillators', '-method', 'cvode-bdf'] + sun_cap,
             tl([1e-4] if Q else [1e-4, 1e-8] if L else [1e-3, 1e-5, 1e-7, 1e-9])),
            ('sundials', 'ARKODE ERK adaptive', ['-problem', 'oscillators', '-method', 'erk'] + sun_cap,
             tl([1e-3] if Q else [1e-3, 1e-5] if L else [1e-2, 1e-3, 1e-4, 1e-5])),
            ('sundials', 'ARKODE MRI', ['-problem', 'oscillators', '-method', 'mri'] + sun_cap,
             [('slow f0, H 1e-2, inner tol 1e-5', ['-mri_slow_terms', '1', '-H', '1e-2', '-rtol', '1e-5', '-atol', '1e-5'])]
             + ([] if L else [('slow f0+f1, H 1e-3, inner tol 1e-5', ['-mri_slow_terms', '2', '-H', '1e-3', '-rtol', '1e-5', '-atol', '1e-5'])])
             + ([] if Q or L else [('slow f0+f1, H 2e-6, inner tol 1e-5', ['-mri_slow_terms', '2', '-H', '2e-6', '-rtol', '1e-5', '-atol', '1e-5'])])),
        ]
        problems.append(('oscillators t=%g' % T, 'examples/ode/oscillatory', ['-eps', '1e-3', '-print_interval', '0.8'],
                         ['I1', 'I2'], ref, 3, methods))
    # --- dissipative, eps = 1e-2 and 1e-4
    for eps, ref in ((1e-2, DISS_REF_1E2), (1e-4, None)):
        if ref is None:
            ref = b.dissipative_reference(eps)
            if ref is None:
                continue
        if eps == 1e-2:
            ladder = [('dt 1e-4 alpha %s' % a, ['-ts_vshmm_micro_dt', '1e-4', '-ts_vshmm_savings_factors', a])
                      for a in (['100,10', '20,5'] if Q else ['200,10', '100,10', '50,5', '20,5', '10,5', '5,2'])]
            ladder += [] if Q else [('dt 5e-5 alpha 40,10', ['-ts_vshmm_micro_dt', '5e-5', '-ts_vshmm_savings_factors', '40,10'])]
            rkdt, guess = ([1e-4] if Q else [2e-4, 1e-4, 5e-5, 2.5e-5, 1.25e-5]), 2.5e-4
        else:
            ladder = [('dt 1e-8 alpha %s' % a, ['-ts_vshmm_micro_dt', '1e-8', '-ts_vshmm_savings_factors', a])
                      for a in (['200000,500'] if Q else ['200000,500', '20000,500', '2000,500'])]
            rkdt, guess = [], 2.5e-8
        tols = [1e-1] if Q else [1e-1, 1e-2, 1e-3]
        sun = lambda m, ts: ('sundials', m[0], ['-problem', 'dissipative', '-eps', '%g' % eps, '-method', m[1]] + sun_cap,
                             [('tol %g' % t, ['-rtol', '%g' % t, '-atol', '%g' % t]) for t in ts])
        methods = [
            ('vshmm', 'VSHMM ladder', ladder),
            ('vshmm-adapt', 'VSHMM adapt', tols),
            ('rk-stable', 'RK4 largest stable', '4', guess),
            ('rk-fixed', 'RK4 fixed', '4', rkdt),
            ('rk-adapt', 'RK 5dp adaptive', '5dp', [1e-3] if Q else [1e-2, 1e-4, 1e-6, 1e-8] if eps > 1e-3 else [1e-2, 1e-6]),
            ('mprk', 'MPRK', [('2a22', 1e-4)] if Q else [(t, dt) for t in ('2a22', '2a23') for dt in (2e-4, 1e-4, 5e-5)] if eps == 1e-2 else [('2a22', 1e-8)]),
            ('imex', 'ARKIMEX (fast implicit)', ['-problem', 'dissipative', '-eps', '%g' % eps] + pet_cap, [1e-4] if Q else [1e-2, 1e-4, 1e-6, 1e-8]),
            sun(('CVODE Adams', 'cvode-adams'), [1e-4] if Q else [1e-2, 1e-4, 1e-6, 1e-8] if eps > 1e-3 else [1e-2, 1e-6]),
            sun(('CVODE BDF', 'cvode-bdf'), [1e-4] if Q else [1e-2, 1e-4, 1e-6, 1e-8]),
            sun(('ARKODE ERK adaptive', 'erk'), [1e-4] if Q else [1e-2, 1e-4, 1e-6, 1e-8] if eps > 1e-3 else [1e-2, 1e-6]),
            ('sundials', 'ARKODE MRI', ['-problem', 'dissipative', '-eps', '%g' % eps, '-method', 'mri', '-mri_slow_terms', '1'] + sun_cap,
             [('slow f0, H %g, inner tol %g' % (H, t), ['-H', '%g' % H, '-rtol', '%g' % t, '-atol', '%g' % t])
              for H, t in ([(1e-2, 1e-4)] if Q else [(1e-1, 1e-4), (1e-2, 1e-4), (1e-2, 1e-6), (1e-3, 1e-8)] if eps > 1e-3 else [(1e-2, 1e-4), (1e-3, 1e-6)])]),
        ]
        problems.append(('dissipative eps=%g' % eps, 'examples/ode/dissipative', ['-eps', '%g' % eps, '-print_interval', '0.5'],
                         ['xi'], ref, 3, methods))
    # --- relaxation chain, K+1 = 2..6 scales, e = 1e-2
    cref = b.chain_reference()
    e = 1e-2
    for n in ([2, 4, 6] if Q else [2, 3, 4, 5, 6]):
        K = n - 1
        dt = e ** K
        ladder = []
        for f in ([1.0] if Q else [1.0, 0.5, 0.25, 0]):  # f = 0: alpha_1 = 1, the slow pair all but merged
            alpha = [f * (e / 2) / dt if f > 0 else 1.0] + [e ** (j - 1) / dt for j in range(2, K + 1)]
            ladder.append(('dt %g, h1 = %g e/2' % (dt, f) if f > 0 else 'dt %g, alpha_1 = 1' % dt, ['-ts_vshmm_micro_dt', '%g' % dt,
                           '-ts_vshmm_savings_factors', ','.join('%g' % a for a in alpha)]))
        base = ['-scales', str(n), '-e', '%g' % e, '-print_interval', '0.5']
        sun = lambda m, ts: ('sundials', m[0], ['-problem', 'chain', '-scales', str(n), '-eps', '%g' % e, '-method', m[1]] + sun_cap,
                             [('tol %g' % t, ['-rtol', '%g' % t, '-atol', '%g' % t]) for t in ts])
        methods = [
            ('vshmm', 'VSHMM ladder', ladder),
            ('vshmm-adapt', 'VSHMM adapt', [1e-2] if Q else [1e-1, 1e-2, 1e-3]),
            ('rk-stable', 'RK4 largest stable', '4', 2.785 * e ** K),
            ('rk-adapt', 'RK 5dp adaptive', '5dp', [1e-4]),
            ('imex', 'ARKIMEX (fast implicit)', ['-problem', 'chain', '-scales', str(n), '-eps', '%g' % e] + pet_cap, [1e-4] if Q else [1e-2, 1e-4, 1e-6]),
            sun(('CVODE BDF', 'cvode-bdf'), [1e-4] if Q else [1e-2, 1e-4, 1e-6]),
            sun(('CVODE Adams', 'cvode-adams'), [1e-4]),
            sun(('ARKODE ERK adaptive', 'erk'), [1e-4]),
            ('sundials', 'ARKODE MRI', ['-problem', 'chain', '-scales', str(n), '-eps', '%g' % e, '-method', 'mri'] + sun_cap,
             [('slow f0..f%d, H %g, inner tol 1e-6' % (K - 1, min(0.05, 0.5 * e ** (K - 1))), ['-H', '%g' % min(0.05, 0.5 * e ** (K - 1)), '-rtol', '1e-6', '-atol', '1e-6'])]),
        ]
        problems.append(('chain %d scales' % n, 'examples/stress/chain', base, ['x0'], cref, n, methods))
    return problems


def dissipative_reference(self, eps):
    """xi at t = 0.5..2 for the dissipative example: ARKIMEX (fast scales implicit) at tolerances
    1e-10 and 1e-12 (bench_imex); the second is the reference, their difference its convergence."""
    vals = []
    for tol in (1e-10, 1e-12):
        out, st = self.run([self.exe('bench/bench_imex'), '-problem', 'dissipative', '-eps', '%g' % eps, '-times', '0.5,1,1.5,2',
                            '-ts_adapt_type', 'basic', '-ts_rtol', '%g' % tol, '-ts_atol', '%g' % tol, '-ts_dt', '1e-10'])
        if st != 'ok':
            self.note('dissipative eps = %g: reference run failed (%s); problem skipped' % (eps, st))
            return None
        vals.append({t: q for t, q in self.parse_driver(out)})
    ref = vals[1]
    diff = max(abs(vals[0][t][0] - ref[t][0]) for t in ref)
    self.refnotes.append('dissipative eps = %g: xi(0.5, 1, 1.5, 2) = %s (ARKIMEX, fast scales implicit, tol 1e-12; '
                         'tol 1e-10 differs by %.1e)' % (eps, ', '.join('%.10f' % ref[t][0] for t in sorted(ref)), diff))
    if eps == 1e-2:
        d = max(abs(ref[t][0] - DISS_REF_1E2[t][0]) for t in DISS_REF_1E2)
        self.refnotes.append('  (eps = 1e-2 against the converged RK4 DNS of docs/dissipative.md: %.1e)' % d)
    return ref


def chain_reference(self):
    """x0 at t = 0.5..2: the 2-scale chain DNS (RK4) with dt = e/100 and e/200; x0(t) is the same for every K."""
    vals = []
    for dt in (1e-4, 5e-5):
        out, st = self.run([self.exe('examples/stress/chain'), '-scales', '2', '-e', '1e-2', '-ts_type', 'rk', '-ts_rk_type', '4',
                            '-ts_dt', '%g' % dt, '-print_interval', '0.5'])
        vals.append({t: q for t, q in self.parse_example(out, ['x0']) if t > 0})
    ref = vals[1]
    diff = max(abs(vals[0][t][0] - ref[t][0]) for t in ref)
    self.refnotes.append('chain (every number of scales): x0(0.5, 1, 1.5, 2) = %s (2-scale DNS, RK4 dt = 5e-5; dt = 1e-4 differs by %.1e; '
                         'x0(t) of the exact solution is the same for every number of scales, docs/stress.md)' %
                         (', '.join('%.8f' % ref[t][0] for t in sorted(ref)), diff))
    return ref


Bench.dissipative_reference = dissipative_reference
Bench.chain_reference = chain_reference


# ---------------------------------------------------------------------------------------------
# Tables and figures
THRESHOLDS = (1e-1, 1e-2, 1e-3)


def cheapest(rows, thr, key='calls'):
    ok = [r for r in rows if r['status'] == 'ok' and r['error'] <= thr and math.isfinite(r[key])]
    return min(ok, key=lambda r: r[key]) if ok else None


def problem_table(rows, problem):
    rs = [r for r in rows if r['problem'] == problem]
    methods = []
    for r in rs:
        if r['method'] not in methods:
            methods.append(r['method'])
    vsh = [r for r in rs if r['method'].startswith('VSHMM')]
    lines = ['| method | ' + ' | '.join('error <= %g: calls (ffe), wall, x VSHMM' % t for t in THRESHOLDS) + ' | best error (calls) |',
             '|---|' + '---|' * (len(THRESHOLDS) + 1)]
    for m in methods:
        mr = [r for r in rs if r['method'] == m]
        cells = []
        for thr in THRESHOLDS:
            c = cheapest(mr, thr)
            v = cheapest(vsh, thr)
            if not c:
                cells.append('not reached')
                continue
            cell = '%s (%s), %s s' % (fmt(c['calls']), fmt(c['ffe']), fmt(c['wall']))
            if v and not m.startswith('VSHMM'):
                cell += ', **%sx** / %sx' % (fmt(c['calls'] / v['calls']), fmt(c['wall'] / v['wall']) if v['wall'] > 0 else '-')
            cell += ' [%s]' % c['config']
            cells.append(cell)
        fin = [r for r in mr if r['status'] == 'ok' and math.isfinite(r['error'])]
        best = min(fin, key=lambda r: r['error']) if fin else None
        bcell = '%s (%s)' % (fmt(best['error']), fmt(best['calls'])) if best else 'failed: ' + ', '.join(sorted(set(r['status'] for r in mr)))
        lines.append('| %s | %s | %s |' % (m, ' | '.join(cells), bcell))
    return '\n'.join(lines)


def write_tables(b):
    rows = b.rows
    problems = []
    for r in rows:
        if r['problem'] not in problems:
            problems.append(r['problem'])
    parts = {}
    for p in problems:
        parts['table:' + p] = problem_table(rows, p)
    # scaling in K
    lines = ['| scales | VSHMM rule: error, split calls | RK4 at its largest stable step: error, calls | CVODE BDF tol 1e-4: error, calls (jac) | ARKIMEX tol 1e-4: error, calls (jac) |',
             '|---|---|---|---|---|']
    for p in problems:
        m = re.match(r'chain (\d+) scales', p)
        if not m:
            continue
        def pick(method, config_start):
            for r in rows:
                if r['problem'] == p and r['method'] == method and r['config'].startswith(config_start):
                    return '%s, %s%s' % (fmt(r['error']), fmt(r['calls']), (' (%s)' % fmt(r['jac'])) if r['jac'] else '') if r['status'] == 'ok' else r['status']
            return 'not run'
        lines.append('| %s | %s | %s | %s | %s |' % (m.group(1), pick('VSHMM ladder', 'dt'), pick('RK4 largest stable', 'dt'),
                                                     pick('CVODE BDF', 'tol 0.0001'), pick('ARKIMEX (fast implicit)', 'tol 0.0001')))
    parts['table:scaling'] = '\n'.join(lines)
    # overheads
    if getattr(b, 'overheads', None):
        lines = ['| unknowns | TSRK 4 per RHS call | VSHMM per split call (cosine / exponential) | VSHMM per level evaluation (cosine / exponential) | level evaluation / RK call | set-up with stability check (its split evaluations) | set-up without |',
                 '|---|---|---|---|---|---|---|']
        for d in b.overheads:
            us = lambda x: '%.3g us' % (x * 1e6) if math.isfinite(x) else '-'
            lines.append('| %d | %s | %s / %s | %s / %s | %.2f | %s (%d) | %s |' % (
                d['n'], us(d['rk4_per_rhs_call']), us(d['vshmm_cosine_per_split_call']), us(d['vshmm_exponential_per_split_call']),
                us(d['cosine_per_level']), us(d['exponential_per_level']), d['cosine_per_level'] / d['rk4_per_rhs_call'],
                us(d['setup_with_stability_check']), d['stability_evaluations'], us(max(0.0, d['setup_without_stability_check']))))
        parts['table:overhead'] = '\n'.join(lines)
    parts['notes'] = '\n'.join('* ' + n for n in b.refnotes + b.notes)
    with open(os.path.join(b.out, 'tables.md'), 'w') as f:
        for k, v in parts.items():
            f.write('<!-- bench:%s -->\n%s\n<!-- /bench -->\n\n' % (k, v))
    return parts


def slug(s):
    return re.sub(r'[^a-z0-9]+', '_', s.lower()).strip('_')


def write_figures(b):
    if not shutil.which('gnuplot'):
        print('gnuplot not found: no figures')
        return []
    problems = []
    for r in b.rows:
        if r['problem'] not in problems:
            problems.append(r['problem'])
    made = []
    for p in problems:
        rs = [r for r in b.rows if r['problem'] == p and r['status'] == 'ok' and math.isfinite(r['error']) and r['error'] > 0]
        methods = []
        for r in rs:
            if r['method'] not in methods:
                methods.append(r['method'])
        if not rs:
            continue
        name = 'perf_' + slug(p)
        dat = os.path.join(b.out, name + '.dat')
        with open(dat, 'w') as f:
            for m in methods:
                f.write('# %s\n' % m)
                for r in sorted([r for r in rs if r['method'] == m], key=lambda r: r['ffe']):
                    f.write('%.6e %.6e %.6e\n' % (r['ffe'], max(r['wall'], 1e-6) if math.isfinite(r['wall']) else 1e-6, max(r['error'], 1e-12)))
                f.write('\n\n')
        plots_e = ', '.join('"%s" index %d using 1:3 with linespoints title "%s"' % (dat, i, m) for i, m in enumerate(methods))
        plots_w = ', '.join('"%s" index %d using 2:3 with linespoints title "%s"' % (dat, i, m) for i, m in enumerate(methods))
        for term, ext in (('pngcairo size 1300,520 font "sans,11"', 'png'), ('svg size 1300,520 font "sans,11" dynamic', 'svg')):
            gp = '''set terminal %s
set output "%s"
set multiplot layout 1,2 title "%s: error against work (log-log)"
set logscale xy
set grid
set format x "10^{%%L}"
set format y "10^{%%L}"
set ylabel "error (max over samples, relative to 1 + |q*|)"
set key bottom left font ",9"
set xlabel "full-field equivalent evaluations"
plot %s
set xlabel "wall time [s]"
unset key
plot %s
unset multiplot
''' % (term, os.path.join(b.out, name + '.' + ext), p, plots_e, plots_w)
            subprocess.run(['gnuplot'], input=gp, universal_newlines=True, stderr=subprocess.DEVNULL)
        made.append(name)
    return made


def update_docs(b, parts, figures):
    doc = os.path.join(ROOT, 'docs', 'performance.md')
    if os.path.exists(doc):
        text = open(doc).read()
        for k, v in parts.items():
            text = re.sub(r'(<!-- bench:%s -->\n)(?:(?!<!-- /bench -->)[^\n]*\n)*(<!-- /bench -->)' % re.escape(k),
                          lambda m: m.group(1) + v + '\n' + m.group(2), text, flags=re.S)
        open(doc, 'w').write(text)
    # only the PNGs the page shows (all figures, PNG and SVG, stay in the output directory)
    figdir = os.path.join(ROOT, 'docs', 'figures')
    shown = open(doc).read() if os.path.exists(doc) else ''
    for name in figures:
        src = os.path.join(b.out, name + '.png')
        if os.path.exists(src) and 'figures/%s.png' % name in shown:
            shutil.copy(src, figdir)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--quick', action='store_true', help='reduced sweep of every problem and method (a few minutes)')
    ap.add_argument('--out', help='output directory')
    ap.add_argument('--docs', action='store_true', help='update docs/performance.md and docs/figures/')
    ap.add_argument('--timeout', type=float, help='seconds per run (default 30 quick, 150 full)')
    ap.add_argument('--report', action='store_true', help='run nothing: tables and figures (and with --docs the page) from the results in the output directory')
    ap.add_argument('--keep', action='store_true', help='keep the previous results (in the output directory) of the problems not run now')
    ap.add_argument('--only', help='regular expression: run only the problems whose name matches (and "overhead", "spectral")')
    args = ap.parse_args()
    b = Bench(args)
    if args.keep or args.report:
        b.load_previous()
    t0 = time.time()
    print('benchmark (%s) into %s' % ('quick' if b.quick else 'full', b.out))
    if not b.sundials and not args.report:
        b.note('SUNDIALS not found at build time: CVODE Adams/BDF and ARKODE ERKStep/MRIStep skipped (install libsundials-dev and rebuild)')
        print('NOTE: bench_sundials not built (no SUNDIALS): CVODE and ARKODE are skipped')
    if not args.report:
        b.note('TSMPRK: the oscillators cannot be expressed (every component has a term of every scale: a component '
               'partition makes every component fast, i.e. single-rate); the chain names its splits s0..sK, not the '
               'slow/medium/fast splits TSMPRK looks for, and TSMPRK has at most 3 rates with a fixed ratio of 2 or 3; '
               'it runs on the dissipative example (component splits slow, medium, fast)')
    sel = re.compile('^$' if args.report else args.only) if (args.report or args.only) else None  # report: nothing runs
    if not sel or sel.search('overhead'):
        b.overhead()
    for prob in ([] if args.report else ode_sweeps(b, b.quick)):
        if sel and not sel.search(prob[0]):
            continue
        try:
            b.ode_problem(*prob)
        except Exception as exc:  # keep the other problems; the notes say what broke
            b.note('%s: the sweep stopped with %r' % (prob[0], exc))
    for name in SPECTRAL_SCENES:
        if sel and not sel.search('spectral ' + name):
            continue
        try:
            b.spectral(name)
        except Exception as exc:
            b.note('spectral %s: the sweep stopped with %r' % (name, exc))
    b.flush()
    b.rows, b.notes, b.refnotes, b.overheads = b.merged()
    b.prev = None
    parts = write_tables(b)
    figures = write_figures(b)
    if args.docs:
        update_docs(b, parts, figures)
    print('\ndone in %.0f s: %s/results.csv, tables.md, %d figures' % (time.time() - t0, b.out, len(figures)))


if __name__ == '__main__':
    main()
