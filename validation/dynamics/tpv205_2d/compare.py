"""TPV205-2D: tribofe at h = 200, 100, 50 m against each other and against PyLith's 2D run.

Usage: python3 validation/dynamics/tpv205_2d/compare.py [folder]   (folder: this one)
Reads h200/, h100/, h50/ (the runs of run.sh) and reference/ (PyLith's stations, see
reference/README.md); writes table.csv, table.md and stations.svg. Standard library only.
"""
import csv
import os
import sys

HERE = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
MESHES = [200, 100, 50]
STATIONS = [-12000, -7500, -4500, 0, 4500, 7500, 12000]
THRESHOLD = 1e-3  # m/s, the field's rupture-time rate
T_END = 12.0


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def read_reference(x):
    """PyLith's columns: t, slip, slip rate, shear stress (MPa), then dip ones (zero in 2D)."""
    rows = []
    with open(os.path.join(HERE, "reference", f"pylith_{x / 1000:.1f}.txt")) as f:
        for line in f:
            if line.strip():
                rows.append([float(v) for v in line.split()])
    return {
        "t_s": [r[0] for r in rows],
        "slip_m": [r[1] for r in rows],
        "slip_rate_m_per_s": [r[2] for r in rows],
        "shear_stress_Pa": [r[3] * 1e6 for r in rows],
    }


def first_crossing(t, rate):
    """First time the rate exceeds THRESHOLD, linear between samples (the reference's rule)."""
    for k in range(1, len(t)):
        if rate[k] > THRESHOLD:
            f = (THRESHOLD - rate[k - 1]) / (rate[k] - rate[k - 1])
            return t[k - 1] + max(0.0, min(1.0, f)) * (t[k] - t[k - 1])
    return None


def at_x(xs, ts, x):
    """Linear between the two nodes about x (rupture_time.csv lists the ruptured nodes)."""
    for k in range(1, len(xs)):
        if xs[k - 1] <= x <= xs[k]:
            w = (x - xs[k - 1]) / (xs[k] - xs[k - 1])
            return (1 - w) * ts[k - 1] + w * ts[k]
    return None


def value_at(t, v, t0):
    for k in range(1, len(t)):
        if t[k - 1] <= t0 <= t[k]:
            w = (t0 - t[k - 1]) / (t[k] - t[k - 1])
            return (1 - w) * v[k - 1] + w * v[k]
    return v[-1]


def main():
    runs = {}
    for h in MESHES:
        d = os.path.join(HERE, f"h{h}")
        rt = read_csv(os.path.join(d, "rupture_time.csv"))
        st = {x: read_csv(os.path.join(d, f"station_x{x}.csv")) for x in STATIONS}
        runs[h] = (rt, st)
    ref = {x: read_reference(x) for x in STATIONS}
    rows = []
    for x in STATIONS:
        r = ref[x]
        row = {"x_m": x}
        row["ref_arrival_s"] = first_crossing(r["t_s"], r["slip_rate_m_per_s"])
        row["ref_slip_12s_m"] = value_at(r["t_s"], r["slip_m"], T_END)
        for h in MESHES:
            rt, st = runs[h]
            s = st[x]
            row[f"arrival_h{h}_s"] = at_x(rt["x_m"], rt["t_s"], x)
            # The reference's rule on the station's 0.05 s samples.
            row[f"arrival_sampled_h{h}_s"] = first_crossing(s["t_s"], s["slip_rate_m_per_s"])
            row[f"slip_12s_h{h}_m"] = value_at(s["t_s"], s["slip_m"], T_END)
        a = [row[f"arrival_h{h}_s"] for h in MESHES]
        sl = [row[f"slip_12s_h{h}_m"] for h in MESHES]
        row["d_arrival_200_100_s"] = abs(a[0] - a[1])
        row["d_arrival_100_50_s"] = abs(a[1] - a[2])
        row["d_slip_200_100_m"] = abs(sl[0] - sl[1])
        row["d_slip_100_50_m"] = abs(sl[1] - sl[2])
        row["arrival_h100_minus_ref_s"] = row["arrival_sampled_h100_s"] - row["ref_arrival_s"]
        row["slip_h100_over_ref_minus_1"] = sl[1] / row["ref_slip_12s_m"] - 1
        rows.append(row)
    keys = list(rows[0])
    with open(os.path.join(HERE, "table.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(keys)
        for row in rows:
            w.writerow([f"{row[k]:.6g}" if isinstance(row[k], float) else row[k] for k in keys])
    md = [
        "| x (km) | arrival 200 / 100 / 50 m (s) | change 200->100, 100->50 (s) | PyLith (s) | 100 m - PyLith, same sampling (s) | slip at 12 s 200 / 100 / 50 m (m) | change 200->100, 100->50 (m) | PyLith (m) | 100 m / PyLith - 1 |",
        "|---:|---|---|---:|---:|---|---|---:|---:|",
    ]
    for row in rows:
        md.append(
            "| {:g} | {:.4f} / {:.4f} / {:.4f} | {:.4f}, {:.4f} | {:.3f} | {:+.3f} | {:.4f} / {:.4f} / {:.4f} | {:.4f}, {:.4f} | {:.4f} | {:+.2%} |".format(
                row["x_m"] / 1000,
                row["arrival_h200_s"],
                row["arrival_h100_s"],
                row["arrival_h50_s"],
                row["d_arrival_200_100_s"],
                row["d_arrival_100_50_s"],
                row["ref_arrival_s"],
                row["arrival_h100_minus_ref_s"],
                row["slip_12s_h200_m"],
                row["slip_12s_h100_m"],
                row["slip_12s_h50_m"],
                row["d_slip_200_100_m"],
                row["d_slip_100_50_m"],
                row["ref_slip_12s_m"],
                row["slip_h100_over_ref_minus_1"],
            )
        )
    worst_a = max(abs(r["arrival_h100_minus_ref_s"]) for r in rows)
    worst_s = max(abs(r["slip_h100_over_ref_minus_1"]) for r in rows if abs(r["x_m"]) <= 4500)
    worst_s_all = max(abs(r["slip_h100_over_ref_minus_1"]) for r in rows)
    # The patch (|x| <= 1.5 km) fails at t = 0 on every mesh: its arrivals are 0.
    outside = [r for r in rows if abs(r["x_m"]) > 1500]
    converging = sum(r["d_arrival_100_50_s"] < r["d_arrival_200_100_s"] for r in outside)
    converging_slip = sum(r["d_slip_100_50_m"] < r["d_slip_200_100_m"] for r in rows)
    md += [
        "",
        f"worst |arrival at 100 m - PyLith| over the 7 stations: {worst_a:.3f} s",
        f"worst |slip at 100 m / PyLith - 1| at x = 0, +-4.5 km: {worst_s:.2%}; over the 7 stations: {worst_s_all:.2%}",
        f"stations outside the patch where the arrival changes less from 100 to 50 m than from 200 to 100 m: {converging} of {len(outside)}; of all 7, where the slip at 12 s does: {converging_slip}",
    ]
    with open(os.path.join(HERE, "table.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))
    svg(runs, ref)


def svg(runs, ref):
    """stations.svg: slip rate against time at each station, the three meshes and PyLith."""
    colours = {200: "#d62728", 100: "#1f77b4", 50: "#2ca02c", "ref": "#000000"}
    pw, ph, ml, mt, gap = 300, 170, 60, 55, 50
    cols = 4
    nrow = (len(STATIONS) + cols - 1) // cols
    width, height = ml + cols * (pw + gap), mt + nrow * (ph + gap) + 40
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">',
        '<rect width="100%" height="100%" fill="white"/>',
        f'<text x="{width / 2}" y="20" text-anchor="middle" font-size="15">TPV205-2D: slip rate (m/s) against time (s) at each station</text>',
    ]
    vmax = 10.0
    for i, x in enumerate(STATIONS):
        x0 = ml + (i % cols) * (pw + gap)
        y0 = mt + (i // cols) * (ph + gap)
        out.append(f'<rect x="{x0}" y="{y0}" width="{pw}" height="{ph}" fill="none" stroke="black"/>')
        out.append(f'<text x="{x0 + pw / 2}" y="{y0 - 6}" text-anchor="middle">x = {x / 1000:g} km</text>')
        for tick in range(0, 13, 2):
            px = x0 + tick / T_END * pw
            out.append(f'<line x1="{px:.1f}" y1="{y0 + ph}" x2="{px:.1f}" y2="{y0 + ph + 4}" stroke="black"/>')
            out.append(f'<text x="{px:.1f}" y="{y0 + ph + 16}" text-anchor="middle">{tick}</text>')
        for tick in range(0, 11, 5):
            py = y0 + ph - tick / vmax * ph
            out.append(f'<line x1="{x0 - 4}" y1="{py:.1f}" x2="{x0}" y2="{py:.1f}" stroke="black"/>')
            out.append(f'<text x="{x0 - 6}" y="{py + 4:.1f}" text-anchor="end">{tick}</text>')
        series = [(h, runs[h][1][x]) for h in MESHES] + [("ref", ref[x])]
        for key, s in series:
            pts = " ".join(
                f"{x0 + t / T_END * pw:.1f},{y0 + ph - min(max(v, 0.0), vmax) / vmax * ph:.1f}"
                for t, v in zip(s["t_s"], s["slip_rate_m_per_s"])
            )
            dash = ' stroke-dasharray="4 3"' if key == "ref" else ""
            out.append(f'<polyline points="{pts}" fill="none" stroke="{colours[key]}" stroke-width="1.2"{dash}/>')
    ly = height - 18
    for k, (key, name) in enumerate([(200, "h = 200 m"), (100, "h = 100 m"), (50, "h = 50 m"), ("ref", "PyLith 2D (200 m)")]):
        lx = ml + k * 170
        dash = ' stroke-dasharray="4 3"' if key == "ref" else ""
        out.append(f'<line x1="{lx}" y1="{ly}" x2="{lx + 30}" y2="{ly}" stroke="{colours[key]}" stroke-width="2"{dash}/>')
        out.append(f'<text x="{lx + 36}" y="{ly + 4}">{name}</text>')
    out.append("</svg>")
    with open(os.path.join(HERE, "stations.svg"), "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
