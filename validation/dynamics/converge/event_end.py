#!/usr/bin/env python3
"""Per-event cost of the two event-end rules (docs/speed.md, "Event end").

Usage: event_end.py ROOT...   each ROOT holding run folders r<R>_g<G>_h<H>_dc<DC> and their
logs as run.sh writes them (run with --event-end energy into one ROOT, slip into another).
Prints, per run: dynamic events, explicit steps (total, median and largest per event), the
dynamic phase's wall time per event, and the whole process's CPU (user + sys, /usr/bin/time -v).
F_1, x_1, the envelope and the peak: table.py on the same ROOTs.
"""
import csv
import os
import re
import statistics
import sys

for root in sys.argv[1:]:
    for name in sorted(os.listdir(root)):
        d = os.path.join(root, name)
        if not os.path.isdir(d) or not os.path.exists(os.path.join(d, "dyn_events.csv")):
            continue
        with open(os.path.join(d, "dyn_events.csv")) as f:
            steps = [int(e["steps"]) for e in csv.DictReader(f)]
        log = open(d + ".log").read()
        cpu = sum(float(v) for v in re.findall(r"(?:User|System) time \(seconds\): ([\d.]+)", log))
        dyn = float(re.search(r"dynamic events ([\d.]+) s", log).group(1))
        with open(os.path.join(d, "run.toml")) as f:
            end = re.search(r'event_end = "(\w+)"', f.read())
        print(f"{root}/{name}: event_end {end.group(1) if end else '?'}, {len(steps)} dynamic events, "
              f"{sum(steps)} steps (median {statistics.median(steps):.0f}, largest {max(steps)} per event), "
              f"dynamic phase {dyn:.1f} s wall ({dyn / len(steps):.3f} s per event), process CPU {cpu:.1f} s")
