#!/usr/bin/env python3
"""Independent check of tribofe's writers with meshio (pip install meshio numpy).

Reads the .vtu that `cargo test --test it writers_io::` leaves in target/tmp/io-check/, and
compares points, cells (type by type, in order) and every point/cell array with the JSON dump
the same test writes. Also checks the .pvd collection and, with meshio's Gmsh reader, the
points and node views of result.msh. Exits non-zero on any mismatch.

    cargo test --release --test it writers_io:: && python3 validation/io/check_vtu.py target/tmp/io-check
"""
import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np

VTK_NAMES = {5: "triangle", 22: "triangle6", 9: "quad", 23: "quad8", 28: "quad9"}


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def check_vtu(d: Path, ref: dict):
    m = meshio.read(d / "mesh.vtu")
    points = np.array(ref["points"], dtype=float)
    if m.points.shape != points.shape or not np.array_equal(m.points, points):
        fail(f"points differ: {m.points.shape} vs {points.shape}")
    # meshio groups consecutive cells of one type into blocks; flatten back in order.
    got = [(b.type, list(map(int, c))) for b in m.cells for c in b.data]
    want = [(VTK_NAMES[t], nodes) for t, nodes in ref["cells"]]
    if got != want:
        fail(f"cells differ ({len(got)} read, {len(want)} written)")
    for name, f in ref["point_data"].items():
        a = np.asarray(m.point_data[name], dtype=float).reshape(len(points), -1)
        b = np.array(f["values"], dtype=float).reshape(len(points), f["components"])
        if not np.array_equal(a, b):
            fail(f"point array {name} differs")
    for name, f in ref["cell_data"].items():
        a = np.concatenate([np.asarray(x, dtype=float).reshape(len(x), -1) for x in m.cell_data[name]])
        b = np.array(f["values"], dtype=float).reshape(len(want), f["components"])
        if not np.array_equal(a, b):
            fail(f"cell array {name} differs")
    kinds = np.concatenate(m.cell_data["element_kind"])
    if len(kinds) != len(want):
        fail("element_kind has the wrong length")
    print(f"vtu ok: {len(points)} points, {len(want)} cells of {sorted({t for t, _ in want})}, "
          f"{len(ref['point_data'])} point and {len(ref['cell_data'])} cell fields")


def check_pvd(d: Path):
    root = ET.parse(d / "cases.pvd").getroot()
    sets = root.findall("./Collection/DataSet")
    if [float(s.get("timestep")) for s in sets] != [0.0, 1.0]:
        fail("pvd timesteps")
    for s in sets:
        meshio.read(d / s.get("file"))
    print(f"pvd ok: {len(sets)} data sets")


def check_msh(d: Path, ref: dict):
    m = meshio.read(d / "result.msh")
    points = np.array(ref["points"], dtype=float)
    if not np.array_equal(m.points[:, :2], points[:, :2]):
        fail("msh points differ")
    for name, f in ref["point_data"].items():
        a = np.asarray(m.point_data[name], dtype=float).reshape(len(points), -1)
        b = np.array(f["values"], dtype=float).reshape(len(points), f["components"])
        if not np.array_equal(a, b):
            fail(f"msh node view {name} differs")
    print(f"msh ok: {len(points)} points, node views {sorted(ref['point_data'])}")


def main():
    d = Path(sys.argv[1] if len(sys.argv) > 1 else "target/tmp/io-check")
    ref = json.loads((d / "mesh.json").read_text())
    check_vtu(d, ref)
    check_pvd(d)
    check_msh(d, ref)
    print("all io checks passed")


if __name__ == "__main__":
    main()
