#!/usr/bin/env python3
"""Where the fronts of a `slide --dynamics` run on the paper's scene start and stop.

Usage: regime.py OUT_DIR KAPPA_MEAN [--summary FILE.csv] [--model MODEL_EVENTS_CSV]

Reads OUT_DIR/events.csv, dyn_events.csv and states.csv (streamed: it may be many GB) and,
for every instability (dynamic event in which some node weakened fully), writes one row:
where it nucleated relative to the trailing edge, the leading corner and the tips of the
earlier arrested fronts; where it arrested against two predictions read off the interface
state just before it (the row of the previous event, same active set, X within one event):

- zero fracture energy (the paper's model, assumption 4): the front runs on while the
  prestress tau0 >= mu_d p and stops at the first node ahead where tau0 < mu_d p;
- thin-layer Griffith with G_c = (mu_s - mu_d) p D_c / 2: a front running through a layer of
  thickness t under a held rigid top releases G = t (tau0 - mu_d p)^2 / (2 G_shear) per unit
  advance, so it stops at the first node where tau0 - mu_d p < (mu_s - mu_d) p sqrt(kappa(x)),
  kappa(x) = kappa_mean p_mean / p(x) (kappa >= 1: no front can run at all).

Scene constants (the paper's: (r, g) = (0.9, 0.35), L = 0.4 m, t = 2 mm, H = 4 cm) are below.
"""
import csv
import math
import random
import sys

L, T, H = 0.4, 0.002, 0.04
R, GG = 0.9, 0.35
MU_D = GG * L / (6 * H)
MU_S = MU_D / R


def arg(name, default=None):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


def stream_states(path, wanted):
    """{event: (x, p, tau)} for the state rows whose event is in `wanted`."""
    out = {}
    with open(path) as f:
        f.readline()
        cur, rows = None, None
        for line in f:
            k = int(line[: line.index(",")])
            if k != cur:
                if cur in wanted:
                    out[cur] = rows
                cur, rows = k, ([], [], []) if k in wanted else None
            if rows is not None:
                c = line.split(",")
                rows[0].append(float(c[1]))
                rows[1].append(float(c[2]))
                rows[2].append(float(c[3]))
        if cur in wanted:
            out[cur] = rows
    return out


def arrest(x, p, tau, start, kappa_mean, gc):
    """First node index ahead of `start` (increasing x) where the front must stop."""
    for i in range(start, len(x)):
        if p[i] <= 0.0:
            continue
        excess = tau[i] - MU_D * p[i]
        need = (MU_S - MU_D) * math.sqrt(kappa_mean * p[i]) if gc else 0.0
        if excess < need:
            return i
    return len(x) - 1


def main():
    out, kappa = sys.argv[1], float(sys.argv[2])
    ev = {int(r["event"]): r for r in csv.DictReader(open(f"{out}/events.csv"))}
    dy = [r for r in csv.DictReader(open(f"{out}/dyn_events.csv")) if r["instability"] == "1"]
    # an instability whose run of slip > D_c/100 is empty has no region: reported, not analysed
    empty = [r["event"] for r in dy if not r["region_first_over_L"]]
    if empty:
        print(f"instabilities without a slipped region (skipped): events {', '.join(empty)}")
    dy = [r for r in dy if r["region_first_over_L"]]
    wanted = {int(r["event"]) - 1 for r in dy}
    old = {}
    try:
        st = stream_states(f"{out}/states.csv", wanted)
    except FileNotFoundError:
        # states.csv deleted after a first analysis: the predictions from that run's summary
        st = {}
        old = {int(r["event"]): r for r in csv.DictReader(open(arg("--summary")))}
        print("states.csv absent: the arrest predictions are read back from the summary")
    tol = 5 * T / L  # the one definition's 5 t, in units of L
    tips = []  # arrest tips of the earlier instabilities (their far end, x/L)
    front = -0.5  # farthest point slipped so far in the cycle
    runs = []  # union of the slipped regions so far, as sorted disjoint intervals
    rows = []
    rng = random.Random(1)
    for d in dy:
        k = int(d["event"])
        e = ev[k]
        xn = float(e["x_nucleation_over_L"])
        a, b = float(d["region_first_over_L"]), float(d["region_last_over_L"])
        near_tip = min((abs(xn - q) for q in tips), default=math.inf)
        # the same distance for a nucleus placed at random on the interface (the null case)
        xr = rng.uniform(-0.5, 0.5)
        near_random = min((abs(xr - q) for q in tips), default=math.inf)
        connected = -0.5 + 0.0
        for lo, hi in runs:
            if lo <= connected + 1e-9:
                connected = max(connected, hi)
        if xn + 0.5 <= tol:
            site = "trailing-edge"
        elif 0.5 - xn <= tol:
            site = "leading-corner"
        elif near_tip <= tol:
            site = "previous-tip"
        else:
            site = "elsewhere"
        pred0 = predg = math.nan
        if k - 1 in st:
            x, p, tau = st[k - 1]
            n0 = min(range(len(x)), key=lambda i: abs(x[i] - xn))
            pred0 = x[arrest(x, p, tau, n0, kappa, False)]
            predg = x[arrest(x, p, tau, n0, kappa, True)]
        if k in old:
            pred0 = float(old[k]["arrest_zero_gc_over_L"])
            predg = float(old[k]["arrest_griffith_over_L"])
        rows.append(dict(event=k, kind=d["kind"], X_m=d["X_m"], F_onset_over_mu_s_N=d["F_onset_over_mu_s_N"],
                         F_after_over_mu_s_N=d["F_after_over_mu_s_N"], x_nucleation_over_L=xn,
                         region_first_over_L=a, region_last_over_L=b, site=site,
                         nucleus_to_nearest_earlier_tip_over_t=near_tip * L / T if tips else "",
                         random_to_nearest_earlier_tip_over_t=near_random * L / T if tips else "",
                         front_before_over_L=front, connected_before_over_L=connected, arrest_zero_gc_over_L=pred0, arrest_griffith_over_L=predg))
        tips.append(b)
        front = max(front, b)
        runs = sorted(runs + [(a, b)])
    path = arg("--summary")
    if path:
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    sites = {}
    for r in rows:
        sites[r["site"]] = sites.get(r["site"], 0) + 1
    print(f"{len(rows)} instabilities; nucleation sites: {sites}")
    ahead = [r for r in rows if r["x_nucleation_over_L"] > r["front_before_over_L"] + tol]
    print(f"nucleating > 5 t ahead of every earlier slip (fresh interface): {len(ahead)}")
    near = sorted(r["nucleus_to_nearest_earlier_tip_over_t"] for r in rows[1:])
    rand = sorted(r["random_to_nearest_earlier_tip_over_t"] for r in rows[1:])
    if near:
        med = lambda v: v[len(v) // 2]
        print(f"nucleus to the nearest earlier arrest tip / t: median {med(near):.2f} (random nucleus: {med(rand):.2f}); "
              f"within 2 t: {sum(v <= 2 for v in near)} of {len(near)} (random: {sum(v <= 2 for v in rand)})")
        n30 = sorted(r["nucleus_to_nearest_earlier_tip_over_t"] for r in rows[1:31])
        r30 = sorted(r["random_to_nearest_earlier_tip_over_t"] for r in rows[1:31])
        print(f"instabilities 2 to 31 (the tips still sparse): nucleus to the nearest earlier tip / t median "
              f"{med(n30):.2f}, largest {n30[-1]:.2f} (random nucleus: median {med(r30):.2f}); within 2 t: "
              f"{sum(v <= 2 for v in n30)} of {len(n30)} (random: {sum(v <= 2 for v in r30)})")
    cross = next((r for r in rows if r["connected_before_over_L"] >= 0.5 - 1e-9), None)
    lo = [r for r in csv.DictReader(open(f"{out}/loading.csv")) if r["phase"] == "drive"]
    fmax = lambda xlim: max((float(r["F_over_N"]) / MU_S, float(r["X_m"])) for r in lo if float(r["X_m"]) <= xlim)
    if cross is not None:
        # the event that completed the run is the one before `cross` in the list
        k = rows.index(cross) - 1
        c = rows[k]
        f, x = fmax(float(c["X_m"]))
        print(f"front crossing (instabilities' slipped regions joined from -L/2 to +L/2): event {c['event']} at "
              f"X = {float(c['X_m']):.4e} m, F onset {float(c['F_onset_over_mu_s_N']):.4f}; largest F/(mu_s N) up to it "
              f"{f:.4f} at X = {x:.4e} m")
        pre = [r for r in rows[: k + 1] if r["site"] == "trailing-edge"]
        fs = ", ".join("%.3f" % float(r["F_onset_over_mu_s_N"]) for r in pre)
        xs = ", ".join("%+.3f" % r["region_last_over_L"] for r in pre)
        print(f"trailing-edge instabilities before it: {len(pre)}, F onset {fs}; arrests {xs}")
    f, x = fmax(math.inf)
    print(f"largest F/(mu_s N) of the whole run {f:.4f} at X = {x:.4e} m")
    first = rows[0]
    print(f"first: F {float(first['F_onset_over_mu_s_N']):.4f}, nucleus {first['x_nucleation_over_L']:+.4f}, "
          f"arrest {first['region_last_over_L']:+.4f}; predicted zero G_c {first['arrest_zero_gc_over_L']:+.4f}, "
          f"Griffith {first['arrest_griffith_over_L']:+.4f}")
    ok = [r for r in rows if not math.isnan(r["arrest_griffith_over_L"])]
    for lab, key in (("zero G_c", "arrest_zero_gc_over_L"), ("Griffith", "arrest_griffith_over_L")):
        err = sorted(abs(r["region_last_over_L"] - r[key]) for r in ok)
        sig = sorted(r["region_last_over_L"] - r[key] for r in ok)
        sig30 = sorted(r["region_last_over_L"] - r[key] for r in ok[:30])
        if err:
            print(f"|arrest - {lab} prediction| / L over {len(err)}: median {err[len(err) // 2]:.4f}, "
                  f"90 % {err[int(0.9 * (len(err) - 1))]:.4f}; signed median {sig[len(sig) // 2]:+.4f} "
                  f"(first 30: {sig30[len(sig30) // 2]:+.4f})")
    model = arg("--model")
    if model:
        m = list(csv.DictReader(open(model)))
        print("front against the model: at each model F_i, the model's front before precursor i (x_{i-1}) and the")
        print("dynamic slip connected to the trailing edge before the first instability with onset above F_i:")
        prev_x = -0.5
        for q in m:
            if q["stick_slip"] == "1":
                break
            fi = float(q["F"])
            # the slipped-since-the-cycle-began region connected to the trailing edge, before
            # the first instability whose onset force exceeds F_i
            reach = -0.5
            for r in rows:
                if float(r["F_onset_over_mu_s_N"]) > fi:
                    reach = r["connected_before_over_L"]
                    break
            else:
                reach = None
            print(f"  F_{q['i']} {fi:.4f}: model front {prev_x:+.4f}, dynamics "
                  f"{'never reached this F' if reach is None else f'{reach:+.4f}'}")
            prev_x = float(q["x"])


if __name__ == "__main__":
    main()
