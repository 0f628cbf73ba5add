#!/usr/bin/env python3
"""Diffs two fig5_fe.csv files cell by cell: per changed column the number of cells, and for
every column but the wall times (*_seconds) each changed cell with its old and new value; then
the columns other than *_seconds and *_precursors_at_cap that changed (none expected when only
the at-cap count's definition changed).

    python3 validation/precursors/diff_fig5.py OLD/fig5_fe.csv NEW/fig5_fe.csv
"""
import csv, sys
old = list(csv.DictReader(open(sys.argv[1])))
new = list(csv.DictReader(open(sys.argv[2])))
assert len(old) == len(new), (len(old), len(new))
assert list(old[0].keys()) == list(new[0].keys()), "header changed"
changed = {}
for o, n in zip(old, new):
    assert (o['r'], o['g']) == (n['r'], n['g'])
    for k in o:
        if o[k] != n[k]:
            changed.setdefault(k, []).append((o['r'], o['g'], o[k], n[k]))
for k, v in changed.items():
    print(f"{k}: {len(v)} cells changed")
    if not k.endswith('_seconds'):
        for r, g, a, b in v:
            print(f"  r={r} g={g}: {a} -> {b}")
others = [k for k in changed if not (k.endswith('_seconds') or k.endswith('_precursors_at_cap'))]
print("columns other than *_seconds and *_precursors_at_cap changed:", others or "none")
