#!/usr/bin/env python3
"""Zero-tuning VSHMM against hand-tuned VSHMM, the explicit sparse method and the DNS on sparse
spectral scenes (docs/spectral.md, "Zero tuning: measured"). Not run by make check.

    docs/figures/spectral_autotune.py BUILD_DIR [--scenes diffusion,advection,...,nonlinear] [--out FILE]

For each scene (examples/scenes/<scene>_auto.yaml):
  1. reference: DNS with RK3 at dt_ref; its convergence by dt_ref/2 and by 2N (dt_ref/4), the
     finer grid compared at the coarse grid's points;
  2. the zero-tuning run (the scene file as it is; tolerances 1e-2 and 1e-3): error against the
     reference at each output time, evaluations (rhs_evaluations, which include -ts_vshmm_adapt's
     estimates and the stability check), the detection's DNS evaluations, wall times;
  3. hand-tuned VSHMM on the clusters of each tolerance's zero-tuning run (the examples' detection
     threshold follows the tolerance): a sweep of the micro step and the savings factor;
  4. the explicit sparse method (same clusters; for the paper's scenes also the paper's clusters)
     and the DNS, RK3, at their largest stable step found by bisection: a step is stable if the
     run to the first output time ends with an error at most twice (plus 1e-3) that of a step 8x
     smaller; the found step is then run to the final time.
Runs are sequential (back to back) on one rank. The log of every run goes to --out.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

SCENES = {
    # name: (program, yaml, dt_ref of the DNS, paper's clusters or None, micro steps, savings factors of the sweep)
    "diffusion": ("diffusion", "diffusion_auto.yaml", 1e-6, "0:3,62:63+65:66,192:193,255+257", [1e-5, 2e-5, 3.5e-5, 5e-5], [10, 25, 50, 100, 200, 400, 800, 1600]),
    "advection": ("advection", "advection_auto.yaml", 1.6e-4, "0:24,40:88,114:162,246:266", [5e-4, 1e-3, 2e-3, 4e-3], [1.25, 1.5, 2, 4, 8]),
    "diffusion3": ("diffusion", "diffusion3_auto.yaml", 2e-6, None, [1e-5, 2e-5, 4e-5, 8e-5], [5, 10, 25, 50, 100, 200, 400, 800]),
    "advection2": ("advection", "advection2_auto.yaml", 2e-4, None, [2.5e-4, 1e-3, 4e-3, 8e-3], [1.1, 1.25, 1.5, 2, 4, 8]),
    "diffadv": ("diffusion", "diffadv_auto.yaml", 2e-6, None, [1e-5, 2e-5, 4e-5, 8e-5], [5, 10, 25, 50, 100, 200, 400, 800]),
    "diffsource": ("diffusion", "diffsource_auto.yaml", 1.5e-5, None, [1e-4, 2e-4, 3e-4, 4.5e-4], [2, 5, 10, 25, 50, 100, 200, 400]),
    "diffreact": ("diffusion", "diffreact_auto.yaml", 5e-6, None, [2e-5, 5e-5, 1e-4, 2e-4], [2, 5, 10, 25, 50, 100, 200, 400]),
    "diffnear": ("diffusion", "diffnear_auto.yaml", 2e-6, None, [1e-5, 2e-5, 4e-5, 8e-5], [2, 5, 10, 25, 50, 100, 200, 400]),
    "diffburgers": ("diffusion", "diffburgers_auto.yaml", 4e-6, None, [5e-5, 1e-4, 2e-4, 4e-4], [2, 5, 10, 25, 50, 100, 200, 400]),
    # our nonlinear scene: its "paper's" clusters and parameters are the hand-set scene's (nonlinear.yaml)
    "nonlinear": ("diffusion", "nonlinear_auto.yaml", 2e-5, "0:5,12:19,46:50,62:66,78:82", [1e-4, 2e-4, 4e-4, 5e-4], [1.5, 3, 10, 21, 50, 150, 400]),
}
# the label of a scene's explicit clusters and parameters (the non-_auto scene file)
GIVEN = {"nonlinear": "the hand-set scene's"}

LOG = None


def run(exe, args, cwd):
    cmd = [exe] + args
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    LOG.write("## " + " ".join(os.path.basename(c) if i == 0 else c for i, c in enumerate(cmd)) + "\n")
    keep = [l for l in p.stdout.splitlines() if re.match(r"^(output|compare|detection|ts_type|mode|  K\d|cluster)", l)]
    LOG.write("\n".join(keep) + "\n")
    if p.returncode:
        LOG.write("(exit %d) %s\n" % (p.returncode, p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ""))
    LOG.write("\n")
    LOG.flush()
    r = {"ok": p.returncode == 0, "errors": [], "evals": None, "wall": None, "det_evals": 0, "det_wall": 0.0, "clusters": [], "stdout": p.stdout}
    for l in p.stdout.splitlines():
        m = re.match(r"^compare t \S+ relative_l2_error (\S+)", l)
        if m:
            r["errors"].append(float(m.group(1)))
        m = re.match(r"^output t \S+ rhs_evaluations (\d+) .*wall_time (\S+)", l)
        if m:
            r["evals"], r["wall"] = int(m.group(1)), float(m.group(2))
        m = re.match(r"^detection dns_steps \d+ evaluations (\d+) wall_time (\S+)", l)
        if m:
            r["det_evals"], r["det_wall"] = int(m.group(1)), float(m.group(2))
        m = re.match(r"^  K\d+ = \{([^}]*)\}", l)
        if m:
            r["clusters"].append(m.group(1))
    return r


def spec_of(clusters):
    """The view's '60..68,126..130' lists as a -spectral_clusters value."""
    return ",".join("+".join(x.replace("..", ":") for x in c.split(",")) for c in clusters)


def maxerr(r):
    return max(r["errors"]) if r["ok"] and r["errors"] else float("inf")


def l2diff(fine, coarse, step):
    f = [float(l.split()[1]) for l in open(fine)]
    c = [float(l.split()[1]) for l in open(coarse)]
    e = sum((c[i] - f[step * i]) ** 2 for i in range(len(c)))
    n = sum(f[step * i] ** 2 for i in range(len(c)))
    return math.sqrt(e / n)


def fmt(x):
    return "%.2g" % x if x < 1e-3 or x >= 1e4 else ("%.3g" % x)


def bisect_stable(exe, base, tb, cwd, dt0, ref_args):
    """Largest stable RK3 step. The run to tb (the first output time) is compared with one at
    dt0/8 (dt0: the example's estimate): stable if they differ by less than 0.05 (relative L2).
    Doubling from dt0, then 5 bisections (about 3% apart). The step found is then run to the final
    time against the reference, beside a run at half that step; while its error at some output
    time exceeds twice (plus 1e-3) the half step's, or is not finite (a slowly growing mode: e.g.
    advection near the imaginary-axis limit, or a step whose error grew 30-fold from the first
    output time to the last, 1.9e-3 to 6.2e-2 on a diffusion scene with a source, accepted before
    by the former bound, an error of 0.5), the step is lowered by 3%.
    Returns the step, the smallest step found unstable, and the final run."""
    rk = ["-ts_type", "rk", "-ts_rk_type", "3"]
    first = rk + ["-output_times", "%.6g" % tb]
    run(exe, base + first + ["-ts_dt", "%.6g" % (dt0 / 8), "-grid_solution_file", "bisref"], cwd)
    ok = lambda dt: maxerr(run(exe, base + first + ["-ts_dt", "%.6g" % dt, "-compare_grid_solution", "bisref"], cwd)) <= 0.05
    lo = dt0
    while not ok(lo):
        lo /= 2
    hi = lo * 2
    while ok(hi):
        lo, hi = hi, hi * 2
    for _ in range(5):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    half = run(exe, base + ref_args + rk + ["-ts_dt", "%.6g" % (lo / 2)], cwd)
    for _ in range(40):  # 3% at a time, down to 0.3 of the step at most (the half step itself failing)
        r = run(exe, base + ref_args + rk + ["-ts_dt", "%.6g" % lo], cwd)
        if r["ok"] and half["ok"] and all(e <= 2 * f + 1e-3 for e, f in zip(r["errors"], half["errors"])):
            break
        lo, hi = lo / 1.03, lo
    return lo, hi, r


def measure(name, build, scenes_dir, work, tols):
    prog, yaml, dt_ref, paper, micro, alphas = SCENES[name]
    exe = os.path.join(build, "examples", "spectral", prog)
    y = ["-options_file_yaml", os.path.join(scenes_dir, yaml)]
    cwd = os.path.join(work, name)
    os.makedirs(cwd, exist_ok=True)
    out = {"name": name, "dt_ref": dt_ref}
    times = re.search(r"output_times: (\S+)", open(os.path.join(scenes_dir, yaml)).read()).group(1).split(",")
    N = int(re.search(r"grid_points: (\d+)", open(os.path.join(scenes_dir, yaml)).read()).group(1))
    dns = y + ["-spectral_mode", "dns", "-spectral_clusters", "none"]
    # 1. reference and its convergence
    ref = run(exe, dns + ["-ts_type", "rk", "-ts_rk_type", "3", "-ts_dt", str(dt_ref), "-grid_solution_file", "ref"], cwd)
    out["ref"] = ref
    out["conv_dt"], out["conv_N"] = [], []
    if not paper:  # the paper's references: docs/spectral.md, "The references are converged"
        half = run(exe, dns + ["-ts_type", "rk", "-ts_rk_type", "3", "-ts_dt", str(dt_ref / 2), "-compare_grid_solution", "ref"], cwd)
        out["conv_dt"] = half["errors"]
        fine = run(exe, dns + ["-spectral_grid_points", str(2 * N), "-ts_type", "rk", "-ts_rk_type", "3", "-ts_dt", str(dt_ref / 4), "-grid_solution_file", "ref2N"], cwd)
        out["conv_N"] = [l2diff(os.path.join(cwd, "ref2N_%s.txt" % t), os.path.join(cwd, "ref_%s.txt" % t), 2) for t in times] if fine["ok"] else []
    cmp = ["-compare_grid_solution", "ref"]
    # 2. zero tuning
    out["auto"], out["auto_adapt_dt"] = {}, {}
    for tol in tols:
        out["auto"][tol] = run(exe, y + cmp + ["-ts_rtol", str(tol), "-ts_atol", str(tol)], cwd)
        out["auto_adapt_dt"][tol] = run(exe, y + cmp + ["-ts_rtol", str(tol), "-ts_atol", str(tol), "-micro_step_from_stability", "false"], cwd)
    clusters = spec_of(out["auto"][tols[0]]["clusters"])
    out["clusters"] = out["auto"][tols[0]]["clusters"]
    K = len(out["clusters"])
    # 3. hand-tuned sweep on the clusters of each tolerance's zero-tuning run (the detection's
    #    threshold follows the tolerance)
    out["sweep"], out["sweep_clusters"] = {}, {}
    for tol in tols:
        cl = spec_of(out["auto"][tol]["clusters"]) if out["auto"][tol]["clusters"] else clusters
        out["sweep_clusters"][tol] = cl
        out["sweep"][tol] = []
        if tol != tols[0] and cl == out["sweep_clusters"][tols[0]]:
            out["sweep"][tol] = out["sweep"][tols[0]]
            continue
        fixed = y + cmp + ["-spectral_clusters", cl, "-ts_vshmm_adapt", "false"]
        Kt = cl.count(",") + 1
        for dt in micro:
            for a in alphas:
                sf = ",".join([str(a)] + ["1.5"] * (Kt - 2))
                r = run(exe, fixed + ["-ts_vshmm_micro_dt", str(dt), "-ts_vshmm_savings_factors", sf], cwd)
                out["sweep"][tol].append((dt, sf, r))
    if paper:
        out["paper_vshmm"] = run(exe, [a.replace("_auto", "") for a in y] + cmp, cwd)
    # 4. explicit sparse and DNS at their largest stable steps
    first = float(times[0])
    est = lambda r: float(re.search(r"time step (\S+)", [l for l in r["stdout"].splitlines() if l.startswith("ts_type")][0]).group(1))
    out["sparse"] = []
    for label, cl in [("detected clusters", clusters)] + ([("%s clusters" % GIVEN.get(name, "the paper's")[4:], paper)] if paper else []):
        base = y + ["-spectral_clusters", cl]
        dt0 = est(run(exe, base + ["-ts_type", "rk", "-ts_rk_type", "3", "-output_times", "%g" % (first / 1000)], cwd))
        out["sparse"].append((label,) + bisect_stable(exe, base, first, cwd, dt0, cmp))
    dt0 = est(run(exe, dns + ["-ts_type", "rk", "-ts_rk_type", "3", "-output_times", "%g" % (first / 1000)], cwd))
    out["dns"] = bisect_stable(exe, dns, first, cwd, dt0, cmp)
    return out


def report(o, tols):
    L = []
    errs = lambda r: ", ".join(fmt(e) for e in r["errors"]) if r["ok"] else "failed"
    L.append("### %s" % o["name"])
    L.append("")
    conv = ("refined in dt: %s; in N (2N, dt/4): %s" % (", ".join(fmt(e) for e in o["conv_dt"]), ", ".join(fmt(e) for e in o["conv_N"]))) if o["conv_dt"] else "converged (table above)"
    L.append("Reference: DNS, RK3 dt = %g, %s. Detected clusters: %s." % (o["dt_ref"], conv, "; ".join("K%d = {%s}" % (i, c) for i, c in enumerate(o["clusters"]))))
    L.append("")
    L.append("| run | relative L2 error at the output times | evaluations | wall time (s) |")
    L.append("|---|---|---|---|")
    for tol in tols:
        r = o["auto"][tol]
        L.append("| **zero tuning**, tol %g | %s | %s + detection %s | %s + detection %s |" % (tol, errs(r), r["evals"], r["det_evals"], fmt(r["wall"] or 0), fmt(r["det_wall"])))
    for tol in tols:
        r = o["auto_adapt_dt"][tol]
        L.append("| zero tuning, micro step by adapt (`-micro_step_from_stability false`), tol %g | %s | %s + detection %s | %s + detection %s |" % (tol, errs(r), r["evals"], r["det_evals"], fmt(r["wall"] or 0), fmt(r["det_wall"])))
    best = {}
    for tol in tols:
        target = maxerr(o["auto"][tol])
        cands = [(r["evals"], dt, sf, r) for dt, sf, r in o["sweep"][tol] if r["ok"] and maxerr(r) <= target]
        if cands:
            ev, dt, sf, r = min(cands, key=lambda c: c[0])
            L.append("| best hand-tuned VSHMM at the error of tol %g: dt %g, savings %s | %s | %s | %s |" % (tol, dt, sf, errs(r), r["evals"], fmt(r["wall"])))
            best[tol] = r
        else:
            ev, dt, sf, r = min(((maxerr(r), dt, sf, r) for dt, sf, r in o["sweep"][tol]), key=lambda c: c[0])
            L.append("| hand-tuned VSHMM: no run of the sweep reaches the error of tol %g; the most accurate: dt %g, savings %s | %s | %s | %s |" % (tol, dt, sf, errs(r), r["evals"], fmt(r["wall"] or 0)))
    if "paper_vshmm" in o:
        r = o["paper_vshmm"]
        L.append("| VSHMM, %s clusters and parameters | %s | %s | %s |" % (GIVEN.get(o["name"], "the paper's"), errs(r), r["evals"], fmt(r["wall"] or 0)))
    for label, lo, hi, r in o["sparse"]:
        L.append("| explicit sparse (%s), RK3 dt = %.3g (%.3g unstable) | %s | %s | %s |" % (label, lo, hi, errs(r), r["evals"], fmt(r["wall"] or 0)))
    lo, hi, r = o["dns"]
    L.append("| DNS, RK3 dt = %.3g (%.3g unstable) | %s | %s | %s |" % (lo, hi, errs(r), r["evals"], fmt(r["wall"] or 0)))
    L.append("")
    done = []
    for tol in tols:
        if o["sweep"][tol] is None or any(o["sweep"][tol] is d for d in done):
            continue
        done.append(o["sweep"][tol])
        L.append("Sweep on the clusters of tol %g (%s) (micro step, savings factors: max error, evaluations): " % (tol, o["sweep_clusters"][tol]) + "; ".join("%g, %s: %s, %s" % (dt, sf, fmt(maxerr(r)) if r["ok"] else "failed", r["evals"]) for dt, sf, r in o["sweep"][tol]) + ".")
        L.append("")
    return "\n".join(L)


def main():
    global LOG
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--scenes", default="diffusion,advection,diffusion3,advection2,diffadv")
    ap.add_argument("--tols", default="1e-2,1e-3")
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "spectral_autotune.txt"))
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    scenes_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "scenes"))
    tols = [float(t) for t in a.tols.split(",")]
    work = tempfile.mkdtemp(prefix="vshmm-autotune-")
    LOG = open(a.out + ".log", "w")
    with open(a.out, "w") as f:
        for name in a.scenes.split(","):
            print("scene", name, file=sys.stderr, flush=True)
            f.write(report(measure(name, build, scenes_dir, work, tols), tols) + "\n")
            f.flush()


if __name__ == "__main__":
    main()
