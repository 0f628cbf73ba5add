#!/usr/bin/env python3
"""Every field file `check` and `slide --fields` write, read by independent readers.

Runs the given tribofe binary on small scenes (into a temporary folder), then:
- meshio reads every .vtu and .msh (the .msh with element views once failed with
  `Incompatible cell data`);
- VTK's own XML reader (vtkXMLUnstructuredGridReader, the one ParaView uses) reads every .vtu
  with no error and the same point and cell counts and values as meshio;
- Gmsh's Python API opens every .msh (gmsh.open) and finds one view per field;
- the .vtu and .msh of one state hold the same values, `check --n-force` scales the fields
  linearly, and `slide`'s fields.pvd is indexed by the drive X (m) of loading.csv with the
  state's `event` as a field.
Exits non-zero on any failure.

    pip install meshio numpy vtk gmsh
    cargo build --release && python3 validation/io/check_fields.py target/release/tribofe
"""
import csv
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import gmsh
import meshio
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def run(exe, *args):
    p = subprocess.run([exe, *args], capture_output=True, text=True)
    if p.returncode != 0:
        fail(f"{' '.join(args)}: exit {p.returncode}\n{p.stderr}")


def vtk_read(path: Path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(path))
    seen = []
    r.AddObserver("ErrorEvent", lambda o, e: seen.append(e))
    r.Update()
    g = r.GetOutput()
    if seen or r.GetErrorCode() != 0 or g is None or g.GetNumberOfPoints() == 0:
        fail(f"{path.name}: VTK's reader failed ({seen}, code {r.GetErrorCode()})")
    pd = {g.GetPointData().GetArrayName(i): vtk_to_numpy(g.GetPointData().GetArray(i))
          for i in range(g.GetPointData().GetNumberOfArrays())}
    cd = {g.GetCellData().GetArrayName(i): vtk_to_numpy(g.GetCellData().GetArray(i))
          for i in range(g.GetCellData().GetNumberOfArrays())}
    return g, pd, cd


def check_vtu(path: Path):
    m = meshio.read(path)
    g, pd, cd = vtk_read(path)
    if g.GetNumberOfPoints() != len(m.points) or g.GetNumberOfCells() != sum(len(b.data) for b in m.cells):
        fail(f"{path.name}: VTK and meshio disagree on the sizes")
    if not np.array_equal(vtk_to_numpy(g.GetPoints().GetData()), m.points):
        fail(f"{path.name}: points differ between VTK and meshio")
    for name, a in pd.items():
        if not np.array_equal(a.reshape(len(m.points), -1), np.asarray(m.point_data[name]).reshape(len(m.points), -1)):
            fail(f"{path.name}: point array {name} differs between VTK and meshio")
    for name, a in cd.items():
        b = np.concatenate([np.asarray(x).reshape(len(x), -1) for x in m.cell_data[name]])
        if not np.array_equal(a.reshape(len(b), -1), b):
            fail(f"{path.name}: cell array {name} differs between VTK and meshio")
    head = path.read_bytes()[:8192]
    if b'<AppendedData encoding="raw">' not in head or b'format="binary"' in head:
        fail(f"{path.name}: not raw appended")
    return m


def check_msh(path: Path, want_views):
    m = meshio.read(path)  # raised `Incompatible cell data` before the fix
    gmsh.initialize(["-nopopup"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(path))
        views = [gmsh.option.getString(f"View[{gmsh.view.getIndex(t)}].Name") for t in gmsh.view.getTags()]
        n_nodes = len(gmsh.model.mesh.getNodes()[0])
    finally:
        gmsh.finalize()
    if sorted(views) != sorted(want_views):
        fail(f"{path.name}: Gmsh found views {views}, expected {want_views}")
    if n_nodes != len(m.points):
        fail(f"{path.name}: Gmsh read {n_nodes} nodes, meshio {len(m.points)}")
    return m


def same_values(a: meshio.Mesh, b: meshio.Mesh, what: str):
    if not np.array_equal(a.points[:, :2], b.points[:, :2]):
        fail(f"{what}: points differ")
    for name, v in a.point_data.items():
        if name in b.point_data and not np.array_equal(np.asarray(v).reshape(len(a.points), -1),
                                                       np.asarray(b.point_data[name]).reshape(len(a.points), -1)):
            fail(f"{what}: point field {name} differs between .vtu and .msh")


def main():
    exe = str(Path(sys.argv[1] if len(sys.argv) > 1 else "target/release/tribofe").resolve())
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        # check: both formats, and the same scene at twice the normal force.
        run(exe, "check", "--h", "0.001", "--no-converged", "--fields", "both", "--out", str(tmp / "c"))
        run(exe, "check", "--h", "0.001", "--no-converged", "--n-force", "171.0", "--out", str(tmp / "c2"))
        views = ["displacement_m", "stress_Pa", "von_mises_Pa", "stress_mean_Pa"]
        vtus = sorted((tmp / "c").glob("fields_FN*.vtu"))
        if len(vtus) != 3:
            fail(f"check wrote {len(vtus)} .vtu, expected 3")
        n = {}
        for v in vtus:
            mv = check_vtu(v)
            mm = check_msh(v.with_suffix(".msh"), views)
            same_values(mv, mm, v.stem)
            with open(tmp / "c" / "summary.csv") as f:
                n = {float(r["FN"]): float(r["N"]) for r in csv.DictReader(f)}
            m2 = check_vtu(tmp / "c2" / v.name)
            fn = float(v.stem[len("fields_FN"):])
            k = 171.0 / n[fn]
            for name in ["displacement_m", "stress_Pa"]:
                a, b = np.asarray(mv.point_data[name]), np.asarray(m2.point_data[name])
                if not np.allclose(b, k * a, rtol=1e-12, atol=1e-12 * np.abs(b).max()):
                    fail(f"{v.name}: {name} does not scale by n_force / N = {k}")
        if sorted(p.name for p in (tmp / "c2").glob("fields*")) != ["fields.pvd"] + [v.name for v in vtus]:
            fail("check's default wrote other than .vtu + .pvd")
        print(f"check ok: {len(vtus)} .vtu (meshio = VTK) and .msh (meshio, Gmsh views {views}); --n-force scales")

        # slide: five states, both formats; fields.pvd indexed by X with the event as a field.
        run(exe, "slide", "--length", "0.05", "--h", "0.001", "--law", "static-kinetic", "--fields", "5",
            "--field-format", "both", "--out", str(tmp / "s"))
        with open(tmp / "s" / "loading.csv") as f:
            x_of = {int(r["event"]): float(r["X_m"]) for r in csv.DictReader(f)}
        sets = ET.parse(tmp / "s" / "fields.pvd").getroot().findall("./Collection/DataSet")
        if len(sets) != 5:
            fail(f"slide fields.pvd lists {len(sets)} data sets, expected 5")
        steps = [float(s.get("timestep")) for s in sets]
        if any(b <= a for a, b in zip(steps, steps[1:])):
            fail(f"slide fields.pvd timesteps not increasing: {steps}")
        for s, x in zip(sets, steps):
            path = tmp / "s" / s.get("file")
            mv = check_vtu(path)
            ev = np.unique(mv.point_data["event"])
            # loading.csv prints X to 13 digits, the .pvd to 17.
            if len(ev) != 1 or int(ev[0]) != int(path.stem.split("_")[1]) or abs(x_of[int(ev[0])] - x) > 1e-11 * abs(x):
                fail(f"{path.name}: event {ev} / X {x} do not match loading.csv")
            states = set(np.unique(mv.point_data["interface_state"]).tolist())
            if not states <= {-1.0, 0.0, 1.0, 2.0}:
                fail(f"{path.name}: interface_state codes {states}")
            mm = check_msh(path.with_suffix(".msh"),
                           ["displacement_m", "stress_Pa", "von_mises_Pa", "interface_state", "event"])
            same_values(mv, mm, path.stem)
        print(f"slide ok: {len(sets)} states, pvd timesteps = X of loading.csv {steps[0]:.3e} .. {steps[-1]:.3e} m")
    print("all field-file checks passed")


if __name__ == "__main__":
    main()
