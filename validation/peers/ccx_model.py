#!/usr/bin/env python3
"""Write the CalculiX input for the tribofe check problem and post-process it.

  ccx_model.py write --ny 2 --dir D [--tie rigid|equation]   -> D/check.inp
  ccx_model.py post  --ny 2 --dir D [--out P] [--ref DIR] [--tribofe-out DIR]

Mesh: the same regular grid as tribofe/scikit-fem, CPE4 (plane strain, 2x2
Gauss). CalculiX expands every CPE4 into a C3D8 of thickness given on the
*SOLID SECTION line (set to 1 m here, so forces are per metre of width like
the 2D codes) and ties the expanded nodes back to the 2D nodes; reactions are
reported on the 2D nodes.

Rigid plate: default --tie rigid uses *RIGID BODY,NSET=TOP,REF NODE=P,
ROT NODE=Q (P at (0, H); CalculiX linearises the rigid-body MPC in a linear
step; DOF 3 of Q is the rotation about z, DOFs 1-2 of Q and 3 of P are fixed).
--tie equation writes the exact linear ties u_i - U - (H - t) theta = 0,
v_i - V - x_i theta = 0 as *EQUATION instead, with U, V in the translational
DOFs of P and theta in DOF 1 of Q (tribofe's kinematics written out); both
give the same reactions to solver precision.

Two *STEP blocks give the unit cases A (U=0, V=-1e-4) and B (U=1e-4, V=0).
"""
from __future__ import annotations

import argparse
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import peerlib as pl  # noqa: E402

import numpy as np  # noqa: E402


def node_id(i, j, nx):
    return 1 + i + j * (nx + 1)


def write_inp(ny: int, path: str, tie: str):
    h, nx = pl.mesh_size(ny)
    nn = (nx + 1) * (ny + 1)
    P, Q = nn + 1, nn + 2
    lines = ["*HEADING", f"tribofe check peer: {nx} x {ny} CPE4, tie={tie}", "*NODE"]
    for j in range(ny + 1):
        for i in range(nx + 1):
            # CalculiX reads at most 20 characters per field: keep it short,
            # and make the centre node exactly x = 0.
            lines.append(f"{node_id(i, j, nx)},{(i - nx/2)*h:.14g},{j*h:.14g}")
    lines.append(f"{P},0,{pl.H:.15g}")
    lines.append(f"{Q},0,{pl.H:.15g}")
    lines.append("*ELEMENT,TYPE=CPE4,ELSET=EALL")
    e = 1
    for j in range(ny):
        for i in range(nx):
            n1, n2 = node_id(i, j, nx), node_id(i + 1, j, nx)
            lines.append(f"{e},{n1},{n2},{n2 + nx + 1},{n1 + nx + 1}")
            e += 1

    def nset(name, ids):
        lines.append(f"*NSET,NSET={name}")
        ids = list(ids)
        for k in range(0, len(ids), 16):
            lines.append(",".join(str(n) for n in ids[k:k + 16]))

    nset("BOTTOM", (node_id(i, 0, nx) for i in range(nx + 1)))
    nset("TOP", (node_id(i, ny, nx) for i in range(nx + 1)))
    nset("PLATE", [P])
    nset("ROTN", [Q])
    lines += ["*MATERIAL,NAME=BLOCK", "*ELASTIC", f"{pl.E:.15g},{pl.NU:.15g}",
              # Second line = thickness of the plane-strain slice: 1 m.
              "*SOLID SECTION,ELSET=EALL,MATERIAL=BLOCK", "1."]
    if tie == "rigid":
        lines.append(f"*RIGID BODY,NSET=TOP,REF NODE={P},ROT NODE={Q}")
    else:
        lines.append("*EQUATION")
        for i in range(nx + 1):
            n = node_id(i, ny, nx)
            lines += ["3", f"{n},1,1.,{P},1,-1.,{Q},1,{-(pl.H - pl.T):.14g}"]
            x = (i - nx / 2) * h
            if x == 0.0:
                lines += ["2", f"{n},2,1.,{P},2,-1."]
            else:
                lines += ["3", f"{n},2,1.,{P},2,-1.,{Q},1,{-x:.14g}"]

    def bcs(U, V):
        b = ["*BOUNDARY,OP=NEW", "BOTTOM,1,2,0.", f"{P},1,1,{U:.15g}",
             f"{P},2,2,{V:.15g}", f"{P},3,3,0."]
        # Q's unused DOFs (rigid: rotations about x, y) must be fixed.
        b += [f"{Q},1,2,0."] if tie == "rigid" else [f"{Q},2,3,0."]
        return b

    for U, V in ((0.0, -pl.DISP), (pl.DISP, 0.0)):
        lines += ["*STEP", "*STATIC"] + bcs(U, V) + [
            "*NODE PRINT,NSET=BOTTOM", "RF",
            "*NODE PRINT,NSET=TOP", "RF",
            "*NODE PRINT,NSET=ROTN", "U", "*END STEP"]
    pl.write_text_atomic(path, "\n".join(lines) + "\n")
    return nx, nn


BLOCK_RE = re.compile(r"^\s*(forces|displacements) \(\w+,\w+,\w+\) for set (\w+) "
                      r"and time\s+(\S+)")


def parse_dat(path: str):
    """Return a list (one per step) of {(kind, set): {node: (a, b, c)}}."""
    if not os.path.isfile(path):
        pl.die(f"missing CalculiX output {path} (did ccx run?)")
    steps, cur, key = [], None, None
    seen = set()
    with open(path) as f:
        for line in f:
            m = BLOCK_RE.match(line)
            if m:
                key = (m.group(1), m.group(2).upper())
                if cur is None or key in seen:
                    cur, seen = {}, set()
                    steps.append(cur)
                seen.add(key)
                cur[key] = {}
                continue
            parts = line.split()
            if key and len(parts) == 4:
                try:
                    cur[key][int(parts[0])] = tuple(float(v) for v in parts[1:])
                except ValueError:
                    key = None
            elif parts:
                key = None
    return steps


def unit_from_dat(path: str, ny: int, tie: str):
    h, nx = pl.mesh_size(ny)
    nn = (nx + 1) * (ny + 1)
    P, Q = nn + 1, nn + 2
    steps = parse_dat(path)
    if len(steps) != 2:
        pl.die(f"{path}: expected 2 steps of output, found {len(steps)}")
    bottom = [node_id(i, 0, nx) for i in range(nx + 1)]
    unit = {"xb": (np.arange(nx + 1) - nx / 2) * h, "nx": nx, "ny": ny,
            "ndof": 2 * nn}
    for case, st in zip("AB", steps):
        rf = st.get(("forces", "BOTTOM"))
        rt = st.get(("forces", "TOP"))
        uq = st.get(("displacements", "ROTN"))
        if not rf or not rt or len(rf) != nx + 1 or len(rt) != nx + 1:
            pl.die(f"{path}: incomplete RF output for step {case}")
        R = np.array([rf[n] for n in bottom])
        # CalculiX's RF is the element internal force at a node, so RF of the
        # element-less plate node P is 0; the plate's action on the block
        # shows up at the tied top nodes instead: sum RF(top) = (F, -N).
        Rt = np.array(list(rt.values())).sum(axis=0)
        unit[case] = {"Rx": R[:, 0], "Ry": R[:, 1], "N": -Rt[1], "F": Rt[0],
                      "Rz_bottom_sum": R[:, 2].sum(),
                      "theta": uq[Q][2 if tie == "rigid" else 0] if uq else np.nan}
    return unit


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cmd", choices=["write", "post"])
    ap.add_argument("--ny", type=int, default=2)
    ap.add_argument("--dir", required=True, help="work directory (check.inp/.dat)")
    ap.add_argument("--tie", choices=["rigid", "equation"], default="rigid")
    ap.add_argument("--out", help="directory for profile_FN*.csv and summary.csv")
    ap.add_argument("--ref", help="reference profile dir (scikit-fem) to compare with")
    ap.add_argument("--tribofe-out", help="tribofe --out directory to compare with")
    ap.add_argument("--cmp-csv", help="write the comparison rows to this CSV")
    ap.add_argument("--quiet", action="store_true")
    a = ap.parse_args(argv)

    if a.cmd == "write":
        os.makedirs(a.dir, exist_ok=True)
        nx, nn = write_inp(a.ny, os.path.join(a.dir, "check.inp"), a.tie)
        print(f"wrote {a.dir}/check.inp: {nx} x {a.ny} CPE4, {nn} nodes, tie={a.tie}")
        return
    unit = unit_from_dat(os.path.join(a.dir, "check.dat"), a.ny, a.tie)
    prof = pl.profiles(unit)
    rows = pl.summary(prof)
    out = a.out or os.path.join(a.dir, "profiles")
    pl.write_profiles(prof, out)
    pl.write_csv_atomic(os.path.join(out, "summary.csv"), pl.SUMMARY_COLS, rows)
    print(f"theta: case A {unit['A']['theta']:.6e}, case B {unit['B']['theta']:.6e} rad; "
          f"N_A = {unit['A']['N']:.6g} N/m, F_B = {unit['B']['F']:.6g} N/m; "
          f"sum Rz(bottom) A/B = {unit['A']['Rz_bottom_sum']:.3g}/"
          f"{unit['B']['Rz_bottom_sum']:.3g}")
    if not a.quiet:
        pl.print_summary(rows, f"CalculiX CPE4, {unit['nx']} x {a.ny}, tie={a.tie}")
    cmp_rows = []
    if a.ref:
        # Here the reference file's values are compared to CalculiX (label ccx).
        cmp_rows += pl.compare_profiles(prof, a.ref, "skfem",
                                        os.path.join(a.ref, "summary.csv"))
    if a.tribofe_out:
        cmp_rows += pl.compare_profiles(prof, a.tribofe_out, "tribofe",
                                        os.path.join(a.tribofe_out, "summary.csv"))
    if cmp_rows:
        pl.print_compare(cmp_rows, "CalculiX")
        if a.cmp_csv:
            pl.write_csv_atomic(a.cmp_csv, pl.COMPARE_COLS, cmp_rows)
            print(f"wrote {a.cmp_csv}")


if __name__ == "__main__":
    main()
