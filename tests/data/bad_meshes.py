#!/usr/bin/env python3
"""Writes the bad block meshes of tests/bounds.rs (MSH 2.2 ASCII, no Gmsh needed).

A 20 x 2 QUA4 block, x in [-0.01, 0.01] m, y in [0, 0.002] m (h = 1 mm), groups
`interface` (y = 0), `top` (y = t) and `block`; run with --length 0.02 --thickness 0.002.

  crack.msh              the two halves x < 0 and x > 0 meshed with their own nodes at
                         x = 0 (unmerged seam): two pieces
  crack_partial.msh      the seam unmerged from y = 0 to y = t/2 only (one piece, two
                         coincident nodes at (0, 0) and at (0, t/2))
  diagonal_interface.msh the interface group one 2-node line from corner to corner
  good.msh               the same block, consistent (the control)

Usage: python3 tests/data/bad_meshes.py [DIR]   (default: the folder of this script)
"""
import os
import sys

L, T, NX, NY = 0.02, 0.002, 20, 2


def block(split_rows):
    """Nodes and quads; the nodes at x = 0 in rows < split_rows are doubled (right copy)."""
    nodes, idx = [], {}
    for j in range(NY + 1):
        for i in range(NX + 1):
            nodes.append((-L / 2 + L * i / NX, T * j / NY))
            idx[(i, j, 0)] = len(nodes)
    mid = NX // 2
    for j in range(NY + 1):
        # Row j's node at x = 0 is doubled when an element on either side of it is split.
        if j < split_rows or (j == split_rows and split_rows > 0):
            if j < split_rows or split_rows == NY + 1:
                nodes.append((0.0, T * j / NY))
                idx[(mid, j, 1)] = len(nodes)
    quads = []
    for j in range(NY):
        for i in range(NX):
            def n(a, b):
                # Elements right of the seam use the copy where there is one.
                if a == mid and i >= mid and (mid, b, 1) in idx:
                    return idx[(mid, b, 1)]
                return idx[(a, b, 0)]
            quads.append((n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1)))
    return nodes, quads


def line(nodes_of, j):
    return [(nodes_of(i, j), nodes_of(i + 1, j)) for i in range(NX)]


def write(path, nodes, quads, interface, top):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n3\n1 1 "interface"\n1 2 "top"\n2 3 "block"\n$EndPhysicalNames\n')
        f.write(f"$Nodes\n{len(nodes)}\n")
        for k, (x, y) in enumerate(nodes, 1):
            f.write(f"{k} {x!r} {y!r} 0\n")
        f.write("$EndNodes\n")
        els = [(1, 1, e) for e in interface] + [(1, 2, e) for e in top] + [(3, 3, q) for q in quads]
        f.write(f"$Elements\n{len(els)}\n")
        for k, (typ, phys, ns) in enumerate(els, 1):
            f.write(f"{k} {typ} 2 {phys} {phys} {' '.join(map(str, ns))}\n")
        f.write("$EndElements\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, split in [("good", 0), ("crack", NY + 1), ("crack_partial", 2)]:
        nodes, quads = block(split)
        # Boundary lines follow the elements' own nodes (the copy on the right of the seam).
        bottom = [(quads[i][0], quads[i][1]) for i in range(NX)]
        top = [(quads[(NY - 1) * NX + i][3], quads[(NY - 1) * NX + i][2]) for i in range(NX)]
        write(os.path.join(out, f"{name}.msh"), nodes, quads, bottom, top)
        if name == "good":
            corner = [(quads[0][0], quads[NX - 1][1])]
            write(os.path.join(out, "diagonal_interface.msh"), nodes, quads, corner, top)


main()
