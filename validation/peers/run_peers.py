#!/usr/bin/env python3
"""Time the peers (and tribofe) on the strip family L/t = 200, square elements.

For each ny in --sizes (nx = 200 ny, DOFs = 2 (nx+1)(ny+1)) it runs, one after
another and each as its own process under GNU time (wall time of the whole
process from the script's clock, peak RSS from GNU time; --repeat N keeps the fastest):
  skfem-cholmod  skfem_check.py --solver cholmod   (reference for the checks)
  skfem-splu     skfem_check.py --solver splu      (SciPy SuperLU, COLAMD)
  calculix       ccx_model.py write; ccx; ccx_model.py post  (one shell)
  tribofe        tribofe check --h <t/ny> --out <tmp> --no-fields --no-converged
Every code solves the two unit cases with one factorisation, combines them into
F/N = 0, 0.41, 0.82 and writes the interface profiles; run_peers compares each
code's profiles with skfem-cholmod's (max abs diff of p/(N/L), tau/(N/L)).

Outputs (atomic): results/peers_<date>.csv, results/peers_<date>.md,
results/scaling.svg.

  python3 run_peers.py --install --sizes 5,16,50,100 --repeat 2 [--skip calculix] [--tribofe PATH]
"""
from __future__ import annotations

import argparse
import datetime as dt
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import peerlib as pl  # noqa: E402

CODES = ["skfem-cholmod", "skfem-splu", "calculix", "tribofe"]
REF_CODE = "skfem-cholmod"
TOL = 1e-6           # agreement required in p/(N/L), tau/(N/L)
# CalculiX's .dat prints 7 significant digits, so its tractions carry a
# rounding error of ~5e-7 relative; allow that on top of TOL.
CCX_REL = 1e-6
# Peak RSS (GiB) of the memory-hungry peers at 1.02M DOFs, measured here, and how it grows
# with DOFs (fill of a 2D factorisation ~ n log n: exponent ~1.1; 1.2 to stay on the safe side).
PEAK_GIB_1M = {"calculix": 15.0, "skfem-splu": 4.4}
PEAK_EXPONENT = 1.2


def machine():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"nproc={os.cpu_count()}, CPU: {cpu}, {platform.system()} {platform.release()}"


def mem_available_gib():
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) / 2**20
    return math.inf


def versions(tribofe):
    v = {}
    py = sys.executable
    out = subprocess.run([py, "-c", "import numpy,scipy,skfem,matplotlib;"
                          "print(numpy.__version__,scipy.__version__,skfem.__version__,"
                          "matplotlib.__version__)"], capture_output=True, text=True)
    if out.returncode == 0:
        n, s, k, m = out.stdout.split()
        v["python"] = platform.python_version()
        v.update(numpy=n, scipy=s, **{"scikit-fem": k, "matplotlib": m})
    out = subprocess.run([py, "-c", "import sksparse;print(sksparse.__version__)"],
                         capture_output=True, text=True)
    v["scikit-sparse"] = out.stdout.strip() if out.returncode == 0 else "missing"
    if shutil.which("ccx"):
        out = subprocess.run(["ccx", "-v"], capture_output=True, text=True)
        m = re.search(r"Version\s+(\S+)", out.stdout + out.stderr)
        v["calculix"] = m.group(1) if m else "?"
    else:
        v["calculix"] = "missing"
    if tribofe and os.path.isfile(tribofe):
        out = subprocess.run([tribofe, "--version"], capture_output=True, text=True)
        v["tribofe"] = out.stdout.strip() or "?"
    else:
        v["tribofe"] = "missing"
    return v


def timed(cmd, log, timeout):
    """Run cmd under GNU time -v; return (wall_s, peak_rss_mib) or raise."""
    tfile = log + ".time"
    full = ["/usr/bin/time", "-v", "-o", tfile] + cmd
    with open(log, "w") as f:
        try:
            # Wall time from here (GNU time prints 10 ms steps); GNU time's own start-up
            # (~1 ms) is included, the same for every code.
            t0 = time.perf_counter()
            rc = subprocess.run(full, stdout=f, stderr=subprocess.STDOUT,
                                timeout=timeout).returncode
            wall = time.perf_counter() - t0
        except subprocess.TimeoutExpired:
            raise RuntimeError(f"timed out after {timeout} s")
    if rc != 0:
        with open(log) as f:
            tail = "".join(f.readlines()[-8:])
        raise RuntimeError(f"exit code {rc}; log {log}:\n{tail}")
    txt = open(tfile).read()
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", txt).group(1))
    return wall, rss / 1024


def command(code, ny, outdir, work, tribofe):
    py = sys.executable
    if code.startswith("skfem"):
        return [py, os.path.join(HERE, "skfem_check.py"), "--ny", str(ny),
                "--solver", code.split("-")[1], "--out", outdir, "--quiet"]
    if code == "calculix":
        q = lambda s: "'" + s + "'"  # noqa: E731  (paths are ours: no quotes inside)
        m = q(os.path.join(HERE, "ccx_model.py"))
        script = (f"set -e; {q(py)} {m} write --ny {ny} --dir {q(work)}; "
                  f"cd {q(work)}; OMP_NUM_THREADS=1 ccx -i check > ccx.log 2>&1; "
                  f"{q(py)} {m} post --ny {ny} --dir {q(work)} --out {q(outdir)} --quiet")
        return ["bash", "-c", script]
    h = pl.T / ny
    # The same work as the peers: 3 load cases and interface tractions (no field files).
    return [tribofe, "check", "--h", repr(h), "--out", outdir, "--no-fields", "--no-converged"]


def fit_exponent(dofs, t):
    import numpy as np
    if len(dofs) < 2:
        return math.nan
    return float(np.polyfit(np.log(dofs), np.log(t), 1)[0])


def plot(rows, path, title):
    """Time and peak memory against DOFs, log-log, one line per code; each peer's point at
    the largest size tribofe ran is labelled with its ratio to tribofe."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    ok = [x for x in rows if not math.isnan(x["wall_s"])]
    tf = {x["ny"]: x for x in ok if x["code"] == "tribofe"}
    for ax, key, ylabel in ((axes[0], "wall_s", "wall time of the whole process [s]"),
                            (axes[1], "peak_rss_mib", "peak resident memory [MiB]")):
        for code in CODES:
            r = [x for x in ok if x["code"] == code]
            if not r:
                continue
            d = [x["dofs"] for x in r]
            v = [x[key] for x in r]
            lab = code
            if key == "wall_s" and len(r) >= 2:
                lab += f" (slope {fit_exponent(d, v):.2f})"
            ax.loglog(d, v, "o-", label=lab)
            if code != "tribofe":
                top = max((x for x in r if x["ny"] in tf), key=lambda x: x["dofs"], default=None)
                if top is not None:
                    ratio = top[key] / tf[top["ny"]][key]
                    ax.annotate(f"{ratio:.1f}x", (top["dofs"], top[key]), fontsize=8,
                                xytext=(4, 0), textcoords="offset points", va="center")
        ax.set_xlabel("DOFs (2 x nodes)")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[1].set_title("labels: peer / tribofe at the largest size both ran", fontsize=8)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    tmp = path + ".tmp.svg"
    fig.savefig(tmp, format="svg")
    os.replace(tmp, path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="5,16,50,100", help="comma-separated ny values")
    ap.add_argument("--install", action="store_true",
                    help="first run install.sh (apt + pip: CalculiX, scikit-fem, scikit-sparse)")
    ap.add_argument("--skip", default="", help=f"comma-separated codes to skip: {CODES}")
    ap.add_argument("--tribofe", default=os.path.join(REPO, "target", "release", "tribofe"),
                    help="tribofe binary (default: <repo>/target/release/tribofe)")
    ap.add_argument("--timeout", type=float, default=1800, help="per run [s]")
    ap.add_argument("--repeat", type=int, default=1,
                    help="runs per code and size; the fastest is reported")
    ap.add_argument("--results", default=os.path.join(HERE, "results"))
    ap.add_argument("--append", action="store_true",
                    help="merge into today's peers_<date>.csv (new rows replace "
                         "rows of the same code and ny)")
    ap.add_argument("--force-memory", action="store_true",
                    help="run CalculiX and SuperLU even if MemAvailable looks too small")
    a = ap.parse_args(argv)
    if a.install:
        subprocess.run(["bash", os.path.join(HERE, "install.sh")], check=True)

    try:
        sizes = [int(s) for s in a.sizes.split(",") if s.strip()]
    except ValueError:
        pl.die(f"--sizes must be comma-separated integers, got {a.sizes!r}")
    skip = {s.strip() for s in a.skip.split(",") if s.strip()}
    # code@ny skips one code at one size only (e.g. calculix@50).
    skip_at = {s for s in skip if "@" in s}
    skip -= skip_at
    # 'skfem' skips both scikit-fem variants.
    if "skfem" in skip:
        skip |= {"skfem-cholmod", "skfem-splu"}
    bad = (skip | {s.split("@")[0] for s in skip_at}) - set(CODES) - {"skfem"}
    if bad:
        pl.die(f"--skip: unknown code(s) {sorted(bad)}; known: {CODES}")
    for ny in sizes:
        pl.mesh_size(ny)
    if not os.path.exists("/usr/bin/time"):
        pl.die("/usr/bin/time (GNU time) missing: run install.sh")
    notes = []
    tribofe = os.path.abspath(a.tribofe)
    if "tribofe" not in skip and not os.access(tribofe, os.X_OK):
        print(f"NOTE: tribofe binary {tribofe} not found/executable: skipping tribofe "
              f"(build it with `cargo build --release` or pass --tribofe PATH)")
        notes.append(f"tribofe not run: binary {tribofe} missing")
        skip.add("tribofe")
    if "calculix" not in skip and not shutil.which("ccx"):
        print("NOTE: ccx not found: skipping CalculiX (run install.sh)")
        notes.append("calculix not run: ccx missing")
        skip.add("calculix")
    codes = [c for c in CODES if c not in skip]
    if not codes:
        pl.die("nothing to run")

    global REF_CODE
    if ver_ok := subprocess.run([sys.executable, "-c", "import sksparse.cholmod"],
                                capture_output=True).returncode == 0:
        REF_CODE = "skfem-cholmod"
    else:
        REF_CODE = "skfem-splu"
        notes.append("scikit-sparse missing: reference is skfem-splu; skfem-cholmod skipped")
        codes = [c for c in codes if c != "skfem-cholmod"]
    del ver_ok
    ver = versions(tribofe)
    mach = machine()
    date = dt.date.today().isoformat()
    print(f"run_peers {date}: {mach}")
    print("versions: " + ", ".join(f"{k} {v}" for k, v in ver.items()))

    rows = []
    tmproot = tempfile.mkdtemp(prefix="run_peers.")
    try:
        for ny in sizes:
            h, nx = pl.mesh_size(ny)
            dofs = 2 * (nx + 1) * (ny + 1)
            # The reference is always scikit-fem + CHOLMOD (SuperLU if
            # scikit-sparse is missing); if it is not timed in this run, it
            # is still run (untimed) so that every row is checked against it.
            ref_code = REF_CODE
            ref_dir = os.path.join(tmproot, f"{ref_code}_ny{ny}")
            if ref_code not in codes or f"{ref_code}@{ny}" in skip_at:
                print(f"[{ref_code} ny={ny}] reference run (untimed) ...", flush=True)
                r = subprocess.run(command(ref_code, ny, ref_dir, tmproot, tribofe),
                                   capture_output=True, text=True)
                if r.returncode != 0:
                    pl.die(f"reference {ref_code} ny={ny} failed:\n{r.stderr[-2000:]}")
            for code in codes:
                outdir = os.path.join(tmproot, f"{code}_ny{ny}")
                work = os.path.join(tmproot, f"work_{code}_ny{ny}")
                os.makedirs(work, exist_ok=True)
                row = dict(code=code, ny=ny, nx=nx, dofs=dofs, wall_s=math.nan,
                           peak_rss_mib=math.nan, max_dp=math.nan, max_dtau=math.nan)
                if f"{code}@{ny}" in skip_at:
                    notes.append(f"{code} ny={ny} skipped on request (--skip {code}@{ny})")
                    continue
                if code in PEAK_GIB_1M and not a.force_memory:
                    need = PEAK_GIB_1M[code] * (dofs / 1.02e6) ** PEAK_EXPONENT
                    have = mem_available_gib()
                    if need > 0.8 * have:
                        msg = (f"{code} ny={ny} skipped: needs ~{need:.1f} GiB, "
                               f"MemAvailable {have:.1f} GiB (use --force-memory)")
                        print("NOTE: " + msg)
                        notes.append(msg)
                        continue
                row["load1"] = os.getloadavg()[0]
                print(f"[{code} ny={ny} nx={nx} dofs={dofs}] load {row['load1']:.1f} ...",
                      end=" ", flush=True)
                try:
                    # Best of --repeat runs: each code's first run may meet memory the
                    # previous code (up to 15 GiB) just gave back, whose first touch costs
                    # more on this VM; the repeat sees the machine as the code leaves it.
                    runs = [timed(command(code, ny, outdir, work, tribofe),
                                  os.path.join(work, "run.log"), a.timeout)
                            for _ in range(a.repeat)]
                    row["wall_s"], row["peak_rss_mib"] = min(runs)
                except RuntimeError as e:
                    ccxlog = os.path.join(work, "ccx.log")
                    if os.path.isfile(ccxlog):
                        e = RuntimeError(f"{e}\nccx.log tail:\n"
                                         + "".join(open(ccxlog).readlines()[-6:]))
                    print(f"FAILED: {e}")
                    notes.append(f"{code} ny={ny} failed: {str(e).splitlines()[0]}")
                    rows.append(row)
                    continue
                if code == ref_code:
                    row["max_dp"] = row["max_dtau"] = 0.0
                else:
                    # Reference profiles re-read from the reference code's CSVs.
                    ref = {}
                    for r in pl.RATIOS:
                        x, p, t = pl.read_profile(os.path.join(
                            ref_dir, f"profile_FN{pl.rust_fmt(r)}.csv"))
                        ref[r] = dict(xl=x, p=p, tau=t, N=1.0, F=0.0)
                    cmp = pl.compare_profiles(ref, outdir, code)
                    row["max_dp"] = max(c["max_dp"] for c in cmp)
                    row["max_dtau"] = max(c["max_dtau"] for c in cmp)
                    if code == "calculix":
                        pmax = max(abs(ref[r]["p"]).max() for r in pl.RATIOS)
                        tol = TOL + CCX_REL * pmax
                    else:
                        tol = TOL
                    ok = row["max_dp"] <= tol and row["max_dtau"] <= tol
                    if not ok:
                        notes.append(f"{code} ny={ny}: profiles differ from {ref_code} "
                                     f"by more than {tol:.1e}")
                print(f"{row['wall_s']:.2f} s, {row['peak_rss_mib']:.0f} MiB, "
                      f"max|dp| {row['max_dp']:.2e}, max|dtau| {row['max_dtau']:.2e}")
                rows.append(row)
                shutil.rmtree(work, ignore_errors=True)
    finally:
        shutil.rmtree(tmproot, ignore_errors=True)

    cols = ["code", "ny", "nx", "dofs", "wall_s", "peak_rss_mib", "max_dp", "max_dtau"]
    csv_path = os.path.join(a.results, f"peers_{date}.csv")
    new_keys = {(r["code"], r["ny"]) for r in rows}
    if a.append and os.path.isfile(csv_path):
        import csv
        old = []
        with open(csv_path, newline="") as f:
            for r in csv.DictReader(f):
                r = {k: (r[k] if k == "code" else
                         int(r[k]) if k in ("ny", "nx", "dofs") else float(r[k]))
                     for k in cols}
                if (r["code"], r["ny"]) not in new_keys:
                    old.append(r)
        rows = sorted(old + rows, key=lambda r: (r["ny"], CODES.index(r["code"])))
        codes = [c for c in CODES if any(r["code"] == c for r in rows)]
    pl.write_csv_atomic(csv_path, cols, [{k: r[k] for k in cols} for r in rows])
    title = f"peers {date}, {mach}"
    md = [f"# Peer timings {date}", "",
          f"Machine: {mach}", "",
          "Versions: " + ", ".join(f"{k} {v}" for k, v in ver.items()), "",
          "Strip L/t = 200, square QUA4 elements, 3 load cases (2 unit solves, one "
          "factorisation), interface reactions. Wall time and peak RSS of the whole "
          f"process (GNU time; fastest of {a.repeat} run(s) per code and size). max_dp, max_dtau: max abs difference of p/(N/L), "
          f"tau/(N/L) vs {REF_CODE} on the same mesh (dimensionless); required "
          f"<= {TOL:g} (CalculiX: + {CCX_REL:g} x max|p|, its .dat has 7 significant "
          "digits). calculix = write .inp (Python) + ccx (SPOOLES, 1 thread) + parse "
          ".dat (Python) in one shell; skfem-* = one Python process.", "",
          "load1 = 1-min load average just before the run (2 cores; other users' "
          "jobs share the machine, so timings at load > 1 are inflated).", "",
          "| code | ny | nx | DOFs | wall [s] | peak RSS [MiB] | max dp | max dtau | load1 |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        md.append(f"| {r['code']} | {r['ny']} | {r['nx']} | {r['dofs']} | "
                  f"{r['wall_s']:.3f} | {r['peak_rss_mib']:.0f} | "
                  f"{r['max_dp']:.1e} | {r['max_dtau']:.1e} | "
                  + (f"{r['load1']:.1f} |" if "load1" in r else "see earlier run |"))
    # Ratios to tribofe at each size: how many times longer (and more memory) each peer takes.
    tf = {r["ny"]: r for r in rows if r["code"] == "tribofe" and not math.isnan(r["wall_s"])}
    peers = [c for c in codes if c != "tribofe"]
    if tf and peers:
        md += ["", "Ratios to tribofe at the same size (peer wall time / tribofe wall time; "
               "peak RSS likewise):", "",
               "| DOFs | " + " | ".join(peers) + " |",
               "|---:|" + "---:|" * len(peers)]
        for ny, t in sorted(tf.items()):
            cells = []
            for c in peers:
                r = next((x for x in rows if x["code"] == c and x["ny"] == ny
                          and not math.isnan(x["wall_s"])), None)
                cells.append("-" if r is None else
                             f"{r['wall_s'] / t['wall_s']:.1f}x time, "
                             f"{r['peak_rss_mib'] / t['peak_rss_mib']:.1f}x memory")
            md.append(f"| {t['dofs']} | " + " | ".join(cells) + " |")
    md += ["", "Fitted exponents (wall ~ DOFs^k, least squares on log-log):", ""]
    for code in codes:
        r = [x for x in rows if x["code"] == code and not math.isnan(x["wall_s"])]
        if len(r) >= 2:
            k = fit_exponent([x["dofs"] for x in r], [x["wall_s"] for x in r])
            md.append(f"- {code}: k = {k:.2f} ({len(r)} sizes)")
    md_path = os.path.join(a.results, f"peers_{date}.md")
    if a.append and os.path.isfile(md_path):
        # Keep the earlier run's notes (minus those about what this run redid).
        old_md = open(md_path).read().split("\nNotes:\n", 1)
        if len(old_md) == 2:
            for line in old_md[1].splitlines():
                n = line[2:] if line.startswith("- ") else None
                if not n or n in notes:
                    continue
                m = re.match(r"(\S+) ny=(\d+) ", n)
                if m and (m.group(1), int(m.group(2))) in new_keys:
                    continue
                notes.insert(0, n)
    if notes:
        md += ["", "Notes:", ""] + [f"- {n}" for n in notes]
    pl.write_text_atomic(md_path, "\n".join(md) + "\n")
    plot(rows, os.path.join(a.results, "scaling.svg"), title)
    print("\n".join(md))
    print(f"\nwrote {csv_path}, {md_path}, {os.path.join(a.results, 'scaling.svg')}")


if __name__ == "__main__":
    main()
