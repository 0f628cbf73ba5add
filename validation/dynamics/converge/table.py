#!/usr/bin/env python3
"""The convergence table of the dynamic first cycle (README.md here).

Usage: table.py OUT_ROOT [--csv FILE]

Reads every run folder OUT_ROOT/r<R>_g<G>_h<H>_dc<DC>[_eta<ETA>][_ws<N>] that run.sh wrote, with its
log next to it, and prints one markdown row per run, grouped by (r, g): the front-advance
count and its first advance (F, front x), the front x at given forces (on the staircase of
advances, and on the curve through them), the one precursor definition's n, F_1, x_1, the
largest force before the front crossing, the crossing, the median share of each
instability's force drop made while its front still moved (assumption 5: 0), and the time.
Below each group: the spread (largest minus smallest) over the meshes at the default damping.
"""
import csv
import os
import re
import statistics
import subprocess
import sys
import tempfile

TAG = re.compile(r"r([\d.]+)_g([\d.]+)_h([\d.]+)(?:_dc([\d.e+-]+?)(?:_eta([\d.e+-]+))?(?:_ws(\d+))?|_qs_(\w+))$")


STATIC = {"slip", "stick", "open", "close", "normal-load", "edge-preslip", "end", "creep", "sample"}


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def model_fronts(r, g):
    """The model's precursors (F_i, x_i) at (r, g), from `tribofe precursors model`."""
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([os.environ.get("BIN", "./target/release/tribofe"), "precursors", "model", "--r", r, "--g", g,
                        "--out", d, "--force"], check=True, capture_output=True)
        return [(float(e["F"]), float(e["x"])) for e in rows(f"{d}/events.csv") if e["stick_slip"] == "0"]


def front_lag(adv, model):
    """The run's front (its last advance at or below F_i, the trailing edge before the first) minus
    the model's x_i, at each model precursor whose F_i the run's advances reach: median, largest |.|."""
    lag = []
    for f, x in model:
        if not adv or f > float(adv[-1]["F_over_mu_s_N"]):
            break
        front = max([float(a["front_over_L"]) for a in adv if float(a["F_over_mu_s_N"]) <= f] or [-0.5])
        lag.append(front - x)
    if not lag:
        return float("nan"), float("nan")
    return statistics.median(lag), max(lag, key=abs)


ENVELOPE_F = (0.75, 0.80, 0.85, 0.90)


def front_at(adv, f):
    """The front x/L after the last advance with onset force <= f (mu_s N); nan past the run's last advance's force."""
    if not adv or f > float(adv[-1]["F_over_mu_s_N"]) + 0.01:
        return float("nan")
    return max([float(a["front_over_L"]) for a in adv if float(a["F_over_mu_s_N"]) <= f] or [-0.5])


def tip_curve(adv, f):
    """The front x/L at force f on the curve through the advances' points (F, front), linear
    between the first consecutive pair that brackets f; nan outside. Unlike the staircase
    (front_at), it does not jump by a whole step as a mesh moves a step across f."""
    pts = [(float(a["F_over_mu_s_N"]), float(a["front_over_L"])) for a in adv]
    for (fa, xa), (fb, xb) in zip(pts, pts[1:]):
        if fa <= f <= fb and fb > fa:
            return xa + (f - fa) / (fb - fa) * (xb - xa)
    return float("nan")


def one(root, name):
    d = os.path.join(root, name)
    log = open(d + ".log").read()
    if not os.path.exists(os.path.join(d, "advances.csv")):
        return None
    m = TAG.match(name)
    r, g, h, dc, eta, ws, rule = m.groups()
    ev = rows(os.path.join(d, "events.csv"))
    cross = next((e for e in ev if e["kind"] in ("crossing", "sliding")), None)
    upto = ev[: ev.index(cross) + 1] if cross else ev
    adv = rows(os.path.join(d, "advances.csv"))
    dyn = os.path.join(d, "dyn_events.csv")
    dy = [e for e in rows(dyn) if e["instability"] == "1"] if os.path.exists(dyn) else []
    model = re.search(r"n = (\d+), F_1 = ([\d.]+), x_1 = ([-\d.]+), F_max = ([\d.]+)", log)
    fe = re.search(r"(?:dynamics|FE): n = (\d+) \(advancing.*?F_1 = ([-\d.]+), x_1 = ([-\d.]+)", log)
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", log)
    user = re.search(r"User time \(seconds\): ([\d.]+)", log)
    kappa = re.search(r"kappa = .*? = ([\d.]+)", log)
    wall_s = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall.group(1).split(":")))) if wall else float("nan")
    return dict(
        r=r, g=g, h_mm=float(h), dc=dc or "", run=f"quasi-static {rule}" if rule else "dynamics", eta=eta or ("" if rule else "default"),
        ws=ws or ("" if rule else "default"), kappa=kappa.group(1) if kappa else "?",
        n_front=len(adv),
        f1_front=float(adv[0]["F_over_mu_s_N"]) if adv else float("nan"),
        x1_front=float(adv[0]["front_over_L"]) if adv else float("nan"),
        last_front=float(adv[-1]["front_over_L"]) if adv else float("nan"),
        n=int(fe.group(1)) if fe else -1,
        f1=fe.group(2) if fe else "-", x1=fe.group(3) if fe else "-",
        f_peak=max(float(e["F_over_mu_s_N"]) for e in upto),
        f_cross=float(cross["F_over_mu_s_N"]) if cross else float("nan"),
        x_cross=float(cross["X_m"]) if cross else float("nan"),
        # renamed force_drop_at_arrest_over_event_drop (not a share: it exceeds 1); old runs keep the old name
        drop_moving=statistics.median([float(e[k]) for e in dy for k in ("force_drop_at_arrest_over_event_drop", "drop_while_moving") if e.get(k)] or [float("nan")]),
        instabilities=len(dy) if dy else sum(e["kind"] not in STATIC for e in upto), events=len(ev),
        model=model.groups() if model else None,
        lag=front_lag(adv, model_fronts(r, g)),
        envelope=[front_at(adv, f) for f in ENVELOPE_F],
        tips=[tip_curve(adv, f) for f in ENVELOPE_F],
        wall_s=wall_s, cpu_s=float(user.group(1)) if user else float("nan"),
    )


def main():
    root = sys.argv[1]
    names = sorted(n for n in os.listdir(root) if TAG.match(n) and os.path.isdir(os.path.join(root, n)))
    runs = [x for x in (one(root, n) for n in names) if x]
    out = []
    groups = {}
    for x in runs:
        groups.setdefault((x["r"], x["g"]), []).append(x)
    head = ("| run | h (mm) | damping eta (s) | coefficient updates per D_c | front advances n | first advance F/(mu_s N) | its front x/L | last front x/L "
            "| one definition n, F_1, x_1 | largest F/(mu_s N) before the crossing | cycle end (crossing or whole slip) F/(mu_s N), X (m) "
            f"| front x/L at F/(mu_s N) = {', '.join(map(str, ENVELOPE_F))} | the same on the advances' curve (linear between them) | front - model x_i at the model's F_i: median, largest | median drop while moving | instabilities | wall, CPU (s) |")
    for (r, g), xs in groups.items():
        xs.sort(key=lambda x: (x["run"], (x["eta"], x["ws"]) != ("default", "default"), -x["h_mm"], x["eta"], x["ws"].zfill(6)))
        md = xs[0]["model"]
        dx = next((x for x in xs if x["run"] == "dynamics"), xs[0])
        print(f"\n### (r, g) = ({r}, {g}); dynamics at kappa = {dx['kappa']}, D_c = {dx['dc']} m")
        if md:
            print(f"model: n = {md[0]}, F_1 = {md[1]}, x_1 = {md[2]}, F_max = {md[3]}\n")
        print(head)
        print("|" + "---|" * (head.count("|") - 1))
        for x in xs:
            print(f"| {x['run']} | {x['h_mm']} | {x['eta']} | {x['ws']} | {x['n_front']} | {x['f1_front']:.4f} | {x['x1_front']:.4f} | {x['last_front']:.4f} "
                  f"| {x['n']}, {x['f1']}, {x['x1']} | {x['f_peak']:.4f} | {x['f_cross']:.4f}, {x['x_cross']:.3e} "
                  f"| {', '.join(f'{v:+.3f}' for v in x['envelope'])} | {', '.join(f'{v:+.3f}' for v in x['tips'])} | {x['lag'][0]:+.3f}, {x['lag'][1]:+.3f} | {x['drop_moving']:.2f} | {x['instabilities']} | {x['wall_s']:.0f}, {x['cpu_s']:.0f} |")
            out.append({k: v for k, v in x.items() if k not in ("model", "lag", "envelope", "tips")}
                       | {"lag_median_over_L": x["lag"][0], "lag_largest_over_L": x["lag"][1]}
                       | {f"front_over_L_at_F_{f}": v for f, v in zip(ENVELOPE_F, x["envelope"])}
                       | {f"tip_curve_over_L_at_F_{f}": v for f, v in zip(ENVELOPE_F, x["tips"])})
        for kind in sorted({x["run"] for x in xs}):
            mesh = [x for x in xs if x["run"] == kind and x["eta"] in ("default", "") and x["ws"] in ("default", "")]
            if len(mesh) < 2:
                continue
            sp = lambda k: max(x[k] for x in mesh) - min(x[k] for x in mesh)  # noqa: E731
            print(f"\n{kind}: spread over h = {', '.join(str(x['h_mm']) for x in mesh)} mm: n_front {sp('n_front')}, "
                  f"first advance F {sp('f1_front'):.4f}, its front {sp('x1_front'):.4f} L, "
                  f"largest F {sp('f_peak'):.4f}, crossing F {sp('f_cross'):.4f}")
    if "--csv" in sys.argv:
        with open(sys.argv[sys.argv.index("--csv") + 1], "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(out[0]))
            w.writeheader()
            w.writerows(out)


if __name__ == "__main__":
    main()
