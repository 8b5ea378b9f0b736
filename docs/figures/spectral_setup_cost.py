#!/usr/bin/env python3
"""Set-up work against the run on the sparse spectral scenes (docs/spectral.md, "Set-up cost").
Not run by make check.

    docs/figures/spectral_setup_cost.py BUILD_DIR [--runs 3] [--out FILE]

Each scene file runs as it is with -log_view -ts_view, --runs times back to back on one rank. The
examples put their work in two -log_view stages: "Spectral set-up" (VSHMMSpectralSetUp(): fields,
FFTW plans, the cluster detection (event SpecDetect); the stable-step estimates (SpecEigen) and
the micro step's power iteration (SpecRHS: 50 evaluations)) and "Solve" (the TSSolve calls; TSVSHMM's set-up, its stability
check, runs in the first one: Solve minus TSStep). Evaluations: the detection's (on every mode,
from the "detection" line), the stability check's split evaluations (-ts_view) and the run's
(rhs_evaluations of the last output line, which include the stability check). Times are the
range over the runs.
"""
import argparse
import os
import re
import subprocess

SCENES = [
    # (label, program, scene file[, extra options])
    ("paper diffusion (explicit clusters)", "diffusion", "diffusion.yaml"),
    ("paper diffusion, zero tuning", "diffusion", "diffusion_auto.yaml"),
    ("paper advection (explicit clusters)", "advection", "advection.yaml"),
    ("paper advection, zero tuning", "advection", "advection_auto.yaml"),
    ("diffusion3, zero tuning", "diffusion", "diffusion3_auto.yaml"),
    ("advection2, zero tuning", "advection", "advection2_auto.yaml"),
    ("diffadv, zero tuning", "diffusion", "diffadv_auto.yaml"),
    ("nonlinear (explicit clusters)", "diffusion", "nonlinear.yaml"),
    ("paper diffusion, zero tuning, tol 1e-3", "diffusion", "diffusion_auto.yaml", ["-ts_rtol", "1e-3", "-ts_atol", "1e-3"]),
    ("diffusion3, zero tuning, tol 1e-3", "diffusion", "diffusion3_auto.yaml", ["-ts_rtol", "1e-3", "-ts_atol", "1e-3"]),
    ("diffadv, zero tuning, tol 1e-3", "diffusion", "diffadv_auto.yaml", ["-ts_rtol", "1e-3", "-ts_atol", "1e-3"]),
]


def events(text, stage):
    """{event: (count, time)} of one -log_view stage (the first table: events, not objects)."""
    out, on = {}, False
    for l in text.splitlines():
        if l.startswith("--- Event Stage"):
            if on:
                break
            on = stage in l
            continue
        if on:
            m = re.match(r"^(\S+)\s+(\d+) \S+ (\S+)", l)
            if m:
                out[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return out


def measure(exe, yaml, extra):
    p = subprocess.run([exe, "-options_file_yaml", yaml, "-log_view", "-ts_view"] + extra, capture_output=True, text=True)
    if p.returncode:
        raise RuntimeError("%s %s failed: %s" % (exe, yaml, p.stderr.strip()[-400:]))
    t = p.stdout
    stage = lambda name: float(re.search(r"^\s*\d+:\s+%s: (\S+)" % re.escape(name), t, re.M).group(1))
    s1, s2 = events(t, "Spectral set-up"), events(t, "Solve")
    det = re.search(r"^detection dns_steps \d+ evaluations (\d+)", t, re.M)
    outs = re.findall(r"^output t \S+ rhs_evaluations (\d+)", t, re.M)
    stab = re.search(r"stability check: at set-up; \d+ checks, (\d+) split RHS evaluations", t)
    return {
        "setup": stage("Spectral set-up"),
        "detect": s1.get("SpecDetect", (0, 0.0))[1],
        "eigen": s1.get("SpecEigen", (0, 0.0))[1] + s1.get("SpecRHS", (0, 0.0))[1],
        "eigen_evals": s1.get("SpecRHS", (0, 0))[0],
        "solve": stage("Solve"),
        "tsvshmm_setup": stage("Solve") - s2.get("TSStep", (0, 0.0))[1],
        "det_evals": int(det.group(1)) if det else 0,
        "stab_evals": int(stab.group(1)) if stab else 0,
        "evals": int(outs[-1]) if outs else 0,
    }


def rng(v, scale=1e3):
    lo, hi = min(v) * scale, max(v) * scale
    f = lambda x: "%.2g" % x if x < 10 else "%.0f" % x
    return f(lo) if f(lo) == f(hi) else "%s-%s" % (f(lo), f(hi))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "spectral_setup_cost.txt"))
    a = ap.parse_args()
    scenes_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "scenes"))
    L = ["| scene | set-up stage (ms) | of which detection (ms; evaluations on every mode) | of which stable-step estimates and the micro step's power iteration (ms; evaluations) | solve stage (ms) | of which TSVSHMM set-up (ms; stability check split evaluations) | run evaluations | set-up / (set-up + solve) |", "|---|---|---|---|---|---|---|---|"]
    for label, prog, yaml, *extra in SCENES:
        exe = os.path.join(os.path.abspath(a.build), "examples", "spectral", prog)
        r = [measure(exe, os.path.join(scenes_dir, yaml), extra[0] if extra else []) for _ in range(a.runs)]
        g = lambda k: [x[k] for x in r]
        share = [x["setup"] / (x["setup"] + x["solve"]) for x in r]
        L.append("| %s (`%s`) | %s | %s; %d | %s; %d | %s | %s; %d | %d | %s%% |" % (label, yaml, rng(g("setup")), rng(g("detect")), r[0]["det_evals"], rng(g("eigen")), r[0]["eigen_evals"], rng(g("solve")), rng(g("tsvshmm_setup")), r[0]["stab_evals"], r[0]["evals"], rng(share, 100)))
    with open(a.out, "w") as f:
        f.write("\n".join(L) + "\n")
    print("\n".join(L))


if __name__ == "__main__":
    main()
