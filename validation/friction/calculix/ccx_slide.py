#!/usr/bin/env python3
"""CalculiX cross-check of tribofe's frictional interface (issue 17), `coulomb` law.

Writes a CalculiX deck for the paper's scene, runs ccx single-threaded, and turns its
output into tribofe-format CSVs (loading.csv, states.csv) plus run.json:

  ccx_slide.py --out DIR [--mu 0.5] [--penalty 1e9] [--nx 400 --ny 2] [--length 0.4]
               [--thickness 0.002] [--height 0.04] [--young 2e3] [--poisson 0.4]
               [--normal-force 40] [--x-max auto] [--increments 200] [--workdir D] [--keep]

Scene (same kinematics as tribofe src/scene/mod.rs, rigid plate):
- block [-L/2, L/2] x [0, t], CPE4 on a regular nx x ny grid;
- rigid flat: one row of CPE4 below y = 0 with every node fixed; its top face is the
  master surface, the block's bottom faces the slave surface (node-to-surface penalty
  contact, Coulomb friction mu: *SURFACE BEHAVIOR linear with slope K = --penalty,
  *FRICTION stick slope lambda = K);
- the block's top nodes tied to the plate by linear *EQUATIONs,
  u = U - theta (y - H), v = V + theta x, with (U, V) the translational DOFs of a node P at
  (0, H) and theta DOF 1 of an auxiliary node Q (face-to-face contact and *RIGID BODY were
  seen to fail with CPE4, hence node-to-surface and equations);
- step 1: normal force N on P (U = 0 held, V and theta free); step 2: U (the plate's
  horizontal displacement X at height H) ramped to X_max in --increments equal increments,
  N held.

Plane strain: CalculiX expands each CPE4 into a C3D8 whose thickness is the *SOLID SECTION
value, set to 1 m here, so every force in the deck and in the output is per metre of
width (N/m), as in tribofe. The contact slope K is a pressure per penetration (Pa/m).

Per increment: F = sum of the top nodes' RF_x (CalculiX reports no RF on the element-less
plate node; the plate's action on the block appears at the tied nodes), N likewise; p and tau
from CalculiX's contact stresses (*CONTACT PRINT CSTR; the bottom nodes' RF is zero because it
includes the contact elements), tau taken positive along +x on the flat; sum(p w) and
sum(tau w) with w the tributary length (h, h/2 at the ends) are written as checks; slip = u of the bottom node (the flat does not move; it
includes the stick compliance tau/lambda), state: open if p <= 1e-9 p_mean, slip if
|tau| >= 0.999 mu p, else stick.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

SLIP_RULE = 0.999  # a node slips when |tau| >= SLIP_RULE * mu * p (the rule)


def die(msg: str, code: int = 2):
    print(f"error: {msg}", file=sys.stderr)
    sys.exit(code)


class Scene:
    def __init__(self, a):
        self.L, self.t, self.H = a.length, a.thickness, a.height
        self.nx, self.ny = a.nx, a.ny
        self.E, self.nu, self.mu = a.young, a.poisson, a.mu
        self.K = a.penalty
        self.lam = a.stick_slope if a.stick_slope else a.penalty
        self.N = a.normal_force
        self.h = self.L / self.nx
        self.hy = self.t / self.ny
        nb = (self.nx + 1) * (self.ny + 1)
        self.nblock = nb
        self.nfound0 = nb  # foundation node ids: nb + 1 + i + j (nx + 1), j = 0 (y = -hy), 1 (y = 0)
        if a.x_max is None:
            # Whole-interface sliding starts near the bonded X at F = mu N (shear of the
            # layer + the tilt's lever arm); go 30 % past it.
            G = self.E / (2 * (1 + self.nu))
            M = self.E * (1 - self.nu) / ((1 + self.nu) * (1 - 2 * self.nu))
            F = self.mu * self.N
            x_b = F * self.t / (self.L * G) + 12 * F * self.H * (self.H - self.t) * self.t / (self.L**3 * M)
            self.x_max = 1.3 * x_b
        else:
            self.x_max = a.x_max
        self.inc = a.increments
        # The flat reaches nm elements past each end so that the ends, which move outward
        # under N (Poisson) and along X, always project onto it.
        self.nm = 2 + math.ceil(2 * self.x_max / self.h)
        self.nf = self.nx + 2 * self.nm + 1  # flat nodes per row
        self.P = nb + 2 * self.nf + 1
        self.Q = self.P + 1

    def nid(self, i, j):
        return 1 + i + j * (self.nx + 1)

    def fid(self, i, j):
        """Flat node i in -nm..nx+nm, row j = 0 (y = -hy) or 1 (y = 0)."""
        return self.nfound0 + 1 + (i + self.nm) + j * self.nf

    def x(self, i):
        return (i - self.nx / 2) * self.h

    def deck(self) -> str:
        nx, ny = self.nx, self.ny
        out = ["*HEADING", f"tribofe slide cross-check: {nx} x {ny} CPE4, coulomb mu={self.mu}", "*NODE"]
        for j in range(ny + 1):
            for i in range(nx + 1):
                out.append(f"{self.nid(i, j)},{self.x(i):.14g},{j * self.hy:.14g}")
        for j in range(2):
            for i in range(-self.nm, nx + self.nm + 1):
                out.append(f"{self.fid(i, j)},{self.x(i):.14g},{(j - 1) * self.hy:.14g}")
        out.append(f"{self.P},0,{self.H:.15g}")
        out.append(f"{self.Q},0,{self.H:.15g}")
        out.append("*ELEMENT,TYPE=CPE4,ELSET=BLOCK")
        e = 1
        for j in range(ny):
            for i in range(nx):
                n1, n2 = self.nid(i, j), self.nid(i + 1, j)
                out.append(f"{e},{n1},{n2},{n2 + nx + 1},{n1 + nx + 1}")
                e += 1
        out.append("*ELEMENT,TYPE=CPE4,ELSET=FLAT")
        flat0 = e
        for i in range(-self.nm, nx + self.nm):
            n1, n2 = self.fid(i, 0), self.fid(i + 1, 0)
            out.append(f"{e},{n1},{n2},{n2 + self.nf},{n1 + self.nf}")
            e += 1

        def nset(name, ids):
            out.append(f"*NSET,NSET={name}")
            ids = list(ids)
            for k in range(0, len(ids), 16):
                out.append(",".join(str(n) for n in ids[k:k + 16]))

        def elset(name, ids):
            out.append(f"*ELSET,ELSET={name}")
            ids = list(ids)
            for k in range(0, len(ids), 16):
                out.append(",".join(str(n) for n in ids[k:k + 16]))

        nset("BOTTOM", (self.nid(i, 0) for i in range(nx + 1)))
        nset("TOP", (self.nid(i, ny) for i in range(nx + 1)))
        nset("FLATN", (self.fid(i, j) for j in range(2) for i in range(-self.nm, nx + self.nm + 1)))
        nset("PLATE", [self.P])
        nset("ROTN", [self.Q])
        elset("EBOT", range(1, nx + 1))
        elset("EFLAT", range(flat0, e))
        # CPE4 faces: S1 = nodes 1-2 (bottom edge), S3 = nodes 3-4 (top edge).
        out += ["*SURFACE,NAME=SLAVE", "EBOT,S1", "*SURFACE,NAME=MASTER", "EFLAT,S3"]
        out += ["*MATERIAL,NAME=SOFT", "*ELASTIC", f"{self.E:.15g},{self.nu:.15g}",
                "*SOLID SECTION,ELSET=BLOCK,MATERIAL=SOFT", "1.",
                "*SOLID SECTION,ELSET=FLAT,MATERIAL=SOFT", "1."]
        out += ["*SURFACE INTERACTION,NAME=SI",
                "*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=LINEAR",
                # sigma_inf: the small tension at large clearance, keeps open nodes regular.
                f"{self.K:.6g},{1e-6 * self.N / self.L:.6g}",
                "*FRICTION", f"{self.mu:.15g},{self.lam:.6g}",
                "*CONTACT PAIR,INTERACTION=SI,TYPE=NODE TO SURFACE", "SLAVE,MASTER"]
        out.append("*EQUATION")
        for i in range(nx + 1):
            n = self.nid(i, ny)
            # u_n - U - (H - t) theta = 0 ; v_n - V - x theta = 0
            out += ["3", f"{n},1,1.,{self.P},1,-1.,{self.Q},1,{-(self.H - self.t):.14g}"]
            x = self.x(i)
            if x == 0.0:
                out += ["2", f"{n},2,1.,{self.P},2,-1."]
            else:
                out += ["3", f"{n},2,1.,{self.P},2,-1.,{self.Q},1,{-x:.14g}"]
        out += ["*BOUNDARY", "FLATN,1,2,0.", f"{self.P},3,3,0.", f"{self.Q},2,3,0."]
        prints = ["*NODE PRINT,NSET=BOTTOM", "U,RF", "*NODE PRINT,NSET=TOP,TOTALS=ONLY", "RF",
                  "*NODE PRINT,NSET=PLATE", "U", "*NODE PRINT,NSET=ROTN", "U",
                  "*CONTACT PRINT", "CSTR"]
        # Step 1: N alone, the drive holding U = 0.
        out += ["*STEP,NLGEOM=NO,INC=1000", "*STATIC", "0.1,1.,1e-5,0.25",
                "*BOUNDARY", f"{self.P},1,1,0.",
                "*CLOAD", f"{self.P},2,{-self.N:.15g}"] + prints + ["*END STEP"]
        d = 1.0 / self.inc
        out += ["*STEP,NLGEOM=NO,INC=100000", "*STATIC", f"{d:.10g},1.,{d * 1e-4:.6g},{d:.10g}",
                "*BOUNDARY", f"{self.P},1,1,{self.x_max:.15g}"] + prints + ["*END STEP"]
        return "\n".join(out) + "\n"


HDR = re.compile(r"^\s*(forces|displacements) \(\w+,\w+,\w+\) for set (\w+) and time\s+(\S+)")
CST = re.compile(r"^\s*contact stress \(slave node,press,tang1,tang2\) for all contact elements and time\s+(\S+)")
TOT = re.compile(r"^\s*total force \(fx,fy,fz\) for set (\w+) and time\s+(\S+)")


def parse_dat(path):
    """Blocks in file order: list of (kind, set, time, {node: (a, b, c)} or (fx, fy, fz))."""
    blocks, cur = [], None
    with open(path) as f:
        for line in f:
            m = HDR.match(line)
            if m:
                cur = {}
                blocks.append((m.group(1), m.group(2).upper(), float(m.group(3)), cur))
                continue
            m = CST.match(line)
            if m:
                cur = {}
                blocks.append(("cstress", "ALL", float(m.group(1)), cur))
                continue
            m = TOT.match(line)
            if m:
                cur = "total"
                blocks.append(("total", m.group(1).upper(), float(m.group(2)), None))
                continue
            parts = line.split()
            if cur == "total" and len(parts) == 3:
                k, s, tm, _ = blocks[-1]
                blocks[-1] = (k, s, tm, tuple(float(v) for v in parts))
                cur = None
            elif isinstance(cur, dict) and len(parts) == 4:
                try:
                    cur[int(parts[0])] = tuple(float(v) for v in parts[1:])
                except ValueError:
                    cur = None
            elif parts:
                cur = None
    return blocks


def increments(blocks):
    """Group the blocks into increments: each starts at a BOTTOM displacement block."""
    incs, cur = [], None
    for kind, name, tm, data in blocks:
        if kind == "displacements" and name == "BOTTOM":
            cur = {"time": tm}
            incs.append(cur)
        if cur is not None:
            cur[(kind, name)] = data
    return incs


def post(sc: Scene, dat: str):
    blocks = parse_dat(dat)
    incs = increments(blocks)
    if not incs:
        die(f"{dat}: no increment output (see the .sta/.log of the run)")
    bottom = [sc.nid(i, 0) for i in range(sc.nx + 1)]
    xs = np.array([sc.x(i) for i in range(sc.nx + 1)])
    w = np.full(sc.nx + 1, sc.h)
    w[0] = w[-1] = sc.h / 2
    loading, states = [], []
    for k, inc in enumerate(incs):
        # ccx prints the total time: step 1 covers (0, 1], step 2 (1, 2].
        step = 1 if inc["time"] <= 1 + 1e-9 else 2
        u = inc.get(("displacements", "BOTTOM"))
        cs = inc.get(("cstress", "ALL"))
        tot = inc.get(("total", "TOP"))
        up = inc.get(("displacements", "PLATE"))
        uq = inc.get(("displacements", "ROTN"))
        if not (u and tot and up and uq) or cs is None:
            die(f"{dat}: incomplete output at increment {k} (time {inc['time']})")
        U = np.array([u[n] for n in bottom])
        # ccx expands 2D node n into 3D nodes Q + 3 (n - 1) + 1..3 (front, middle, back); the
        # contact stress is printed for the front and back nodes: average them. A node not
        # printed has no contact element active: p = tau = 0.
        acc = np.zeros((sc.nx + 1, 2))
        cnt = np.zeros(sc.nx + 1)
        for nid3, (pr, t1, _t2) in cs.items():
            n2 = (nid3 - sc.Q - 1) // 3 + 1
            i = n2 - 1
            if 0 <= i <= sc.nx and n2 == sc.nid(i, 0):
                acc[i] += (pr, t1)
                cnt[i] += 1
        with np.errstate(invalid="ignore", divide="ignore"):
            pt = np.where(cnt[:, None] > 0, acc / np.maximum(cnt, 1)[:, None], 0.0)
        # tang1 is the block's shear traction on the flat along +x (checked: sum tau w = F).
        p, tau = pt[:, 0], pt[:, 1]
        F, Nn = tot[0], -tot[1]
        pmean = Nn / sc.L
        slip = U[:, 0]
        st = np.where(p <= 1e-9 * pmean, "open",
                      np.where(np.abs(tau) >= SLIP_RULE * sc.mu * p, "slip", "stick"))
        ev = len(loading)
        loading.append({"event": ev, "step": step, "time": inc["time"],
                        "X_m": up[sc.P][0], "F_N_per_m": F, "N_N_per_m": Nn,
                        "theta_rad": uq[sc.Q][0], "V_m": up[sc.P][1],
                        "F_over_mu_N": F / (sc.mu * Nn) if Nn > 0 else float("nan"),
                        "n_stick": int((st == "stick").sum()), "n_slip": int((st == "slip").sum()),
                        "n_open": int((st == "open").sum()),
                        "sum_p_w_N_per_m": float((p * w).sum()), "sum_tau_w_N_per_m": float((tau * w).sum())})
        for i in range(sc.nx + 1):
            states.append({"event": ev, "x_over_L": xs[i] / sc.L, "p_over_pmean": p[i] / pmean,
                           "tau_over_pmean": tau[i] / pmean, "slip_m": slip[i], "state": st[i]})
    return loading, states


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        wr.writeheader()
        for r in rows:
            wr.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in r.items()})


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="directory for loading.csv, states.csv, run.json")
    ap.add_argument("--mu", type=float, default=0.5)
    ap.add_argument("--penalty", type=float, default=1e9, help="contact slope K, Pa/m")
    ap.add_argument("--stick-slope", type=float, default=None, help="friction stick slope, Pa/m (default K)")
    ap.add_argument("--nx", type=int, default=400)
    ap.add_argument("--ny", type=int, default=2)
    ap.add_argument("--length", type=float, default=0.4)
    ap.add_argument("--thickness", type=float, default=0.002)
    ap.add_argument("--height", type=float, default=0.04)
    ap.add_argument("--young", type=float, default=2e3)
    ap.add_argument("--poisson", type=float, default=0.4)
    ap.add_argument("--normal-force", type=float, default=40.0, help="N, N per metre of width")
    ap.add_argument("--x-max", type=float, default=None, help="final X, m (default 1.3 x bonded X at F = mu N)")
    ap.add_argument("--increments", type=int, default=200, help="equal increments of X in step 2")
    ap.add_argument("--workdir", help="where the deck and raw CalculiX output go (default: temporary)")
    ap.add_argument("--keep", action="store_true", help="keep the temporary work directory")
    ap.add_argument("--write-only", action="store_true", help="write the deck and stop")
    a = ap.parse_args(argv)
    for name in ("mu", "penalty", "length", "thickness", "height", "young", "normal_force"):
        v = getattr(a, name)
        if not (math.isfinite(v) and v > 0):
            die(f"--{name.replace('_', '-')} must be a positive number, got {v}")
    if not (0 <= a.poisson < 0.5):
        die(f"--poisson must be in [0, 0.5), got {a.poisson}")
    if a.nx < 2 or a.nx % 2 or a.ny < 1:
        die(f"--nx must be even and >= 2 (a node at x = 0), --ny >= 1; got {a.nx}, {a.ny}")
    if a.increments < 1:
        die(f"--increments must be >= 1, got {a.increments}")
    if a.height <= a.thickness:
        die(f"--height ({a.height}) must exceed --thickness ({a.thickness})")
    sc = Scene(a)
    work = a.workdir or tempfile.mkdtemp(prefix="ccx_slide.")
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, "slide.inp"), "w") as f:
        f.write(sc.deck())
    if a.write_only:
        print(f"wrote {work}/slide.inp")
        return
    if shutil.which("ccx") is None:
        die("ccx not found: run validation/friction/calculix/install.sh")
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1",
               CCX_NPROC_RESULTS="1", CCX_NPROC_STIFFNESS="1")
    t0 = time.perf_counter()
    with open(os.path.join(work, "ccx.log"), "w") as log:
        r = subprocess.run(["ccx", "-i", "slide"], cwd=work, env=env, stdout=log, stderr=subprocess.STDOUT)
    wall = time.perf_counter() - t0
    dat = os.path.join(work, "slide.dat")
    logtxt = open(os.path.join(work, "ccx.log")).read()
    if r.returncode != 0 or "Job finished" not in logtxt or not os.path.isfile(dat):
        die(f"ccx failed (exit {r.returncode}); see {work}/ccx.log and slide.sta", 1)
    loading, states = post(sc, dat)
    os.makedirs(a.out, exist_ok=True)
    write_csv(os.path.join(a.out, "loading.csv"), loading)
    write_csv(os.path.join(a.out, "states.csv"), states)
    sta = open(os.path.join(work, "slide.sta")).read() if os.path.isfile(os.path.join(work, "slide.sta")) else ""
    iters = sum(int(l.split()[3]) for l in sta.splitlines()[2:] if len(l.split()) >= 4 and l.split()[0].isdigit())
    meta = {"ccx_version": re.search(r"Version\s+(\S+)", logtxt).group(1).rstrip(",") if re.search(r"Version\s+(\S+)", logtxt) else "?",
            "wall_s": wall, "threads": 1, "increments": len(loading), "iterations": iters,
            "mu": sc.mu, "penalty_Pa_per_m": sc.K, "stick_slope_Pa_per_m": sc.lam,
            "nx": sc.nx, "ny": sc.ny, "L_m": sc.L, "t_m": sc.t, "H_m": sc.H, "E_Pa": sc.E, "nu": sc.nu,
            "N_N_per_m": sc.N, "x_max_m": sc.x_max, "slip_rule": SLIP_RULE,
            "command": " ".join([os.path.basename(sys.argv[0])] + (argv if argv is not None else sys.argv[1:]))}
    with open(os.path.join(a.out, "run.json"), "w") as f:
        json.dump(meta, f, indent=1)
    last = loading[-1]
    print(f"ccx {meta['ccx_version']}: {len(loading)} increments, {iters} iterations, {wall:.1f} s wall "
          f"(1 thread); last X = {last['X_m']:.4g} m, F/(mu N) = {last['F_over_mu_N']:.5f}")
    if not a.workdir and not a.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
