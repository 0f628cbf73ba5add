#!/usr/bin/env python3
"""Check the numbers quoted in README.md and docs/findings.md against the committed outputs.

Usage: python3 validation/readme_numbers.py [--root DIR] [--list]

Every number in the two documents that a run produced is registered below (NUMBERS) with
where it is quoted and how to read it from a committed output:

- where it is quoted: either a table cell, `Cell(doc, row_key, index)` (the table row whose
  first cell contains `row_key`, exactly one row in the doc; the index-th number among the
  row's value cells, in reading order), or running text, `Text(doc, regex)` (the regex, with
  one capture group around the number, must match exactly once in the doc);
- how to read it: `csv(file, column, where, agg)` (a column of a committed CSV, on the rows
  matching `where`; one row, or an aggregate: min, max, spread = max - min, count),
  `toml(file, "dotted.key.0.path")`, `rx(file, regex, agg)` (a capture group of a regex on a
  committed text file or log, the first match or an aggregate over all), or `derive(f, ...)`
  (a stated formula on such reads, e.g. a percentage);
- the comparison is at the precision quoted: "0.9495" must equal the committed value
  rounded to 4 decimals, "2e-11" to 1 significant digit, "3,582" to the unit; `scale`
  converts the committed value first (100 for a percentage), `absolute` compares magnitudes.

A doc number that no longer matches its committed value is reported with the doc, its line,
the quoted and the committed values, and the script exits 1. A number in a value cell of a
checked table that no entry registers is reported too (exit 1), so new numbers cannot slip
in unchecked. Checked tables: every table of docs/findings.md, and the tables of README.md
whose header row starts with one of README_TABLES. Value cells: every cell but the first
(the row's label) and the cells under a header named in LABEL_COLUMNS; text in `code spans`
and in link targets is not read.

Exempt (not produced by a run, so not registered; keep them out of value cells or in the
first column): the paper's and the scene's parameters and every input (L = 0.4 m, t = 2 mm,
E = 2 kPa, nu = 0.4, H = 4 cm, (r, g), mu_s, mu_d, D_c, h, eta, --weakening-steps N, the
F/N ratios, command-line values), closed forms of the inputs (kappa, Lambda_0, the model's
equations), definitions (the 5 t windows, 5 % tolerances), section and list numbering, and
ranges of inputs a study spans (t/L = 0.0025-0.02). Numbers in running text that are not
registered are not detected: keep run numbers in the tables, or register the sentence.
"""
import argparse
import csv
import math
import os
import re
import statistics
import sys
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

README = "README.md"
FINDINGS = "docs/findings.md"
# README tables that are checked cell by cell: by the first header cell.
README_TABLES = ("finding", "F/N")
# Header names of columns that hold labels, commands and files, not values.
LABEL_COLUMNS = ("command", "committed file", "read more", "where")

# A number as quoted: optional sign (not after a digit: 0.7349-0.7350 is a range), digits with
# optional thousands separators, decimals, exponent. Not inside identifiers (x_1, F1, t/16 ok).
NUM = re.compile(
    r"(?<![\w.])(?P<num>[-+]?(?:\d{1,3}(?:,\d{3})+|\d+)(?:\.\d+)?(?:e[-+]?\d+)?)(?![\w.]*\w)"
)


# ---------------------------------------------------------------------------------------------
# Readers of committed outputs


class Source:
    def __init__(self, describe, read):
        self.describe = describe
        self.read = read


def _path(root, rel):
    return os.path.join(root, rel)


def _float(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return None


def _match(row, where):
    for k, v in where.items():
        if callable(v):
            if not v(row.get(k)):
                return False
            continue
        cell = row.get(k)
        a, b = _float(cell), _float(v)
        if a is not None and b is not None:
            if a != b:
                return False
        elif str(cell) != str(v):
            return False
    return True


def _aggregate(values, agg, what):
    if agg is None:
        if len(values) != 1:
            raise ValueError(f"{what}: {len(values)} values where one was expected")
        return values[0]
    if not values:
        raise ValueError(f"{what}: no values")
    if agg == "min":
        return min(values)
    if agg == "max":
        return max(values)
    if agg == "spread":
        return max(values) - min(values)
    if agg == "median":
        return statistics.median(values)
    if agg == "count":
        return len(values)
    if agg == "first":
        return values[0]
    raise ValueError(f"unknown aggregate {agg}")


def csv_(rel, column, where=None, agg=None, value=None):
    """Column `column` of CSV `rel` on the rows matching `where`; `value(row)` instead of a
    column computes from the row."""
    where = where or {}

    def read(root):
        delimiter = "\t" if rel.endswith(".tsv") else ","
        with open(_path(root, rel), newline="") as f:
            rows = [r for r in csv.DictReader(f, delimiter=delimiter) if _match(r, where)]
        if agg == "count":
            return len(rows)
        vals = []
        for r in rows:
            v = value(r) if value else _float(r[column])
            if v is None or (isinstance(v, float) and math.isnan(v)):
                continue
            vals.append(v)
        return _aggregate(vals, agg, f"{rel} {column} {where}")

    sel = ", ".join(f"{k}={'<test>' if callable(v) else v}" for k, v in where.items())
    return Source(f"{rel}: {column}" + (f" [{sel}]" if sel else "") + (f" ({agg})" if agg else ""), read)


def toml_(rel, key):
    def read(root):
        with open(_path(root, rel), "rb") as f:
            d = tomllib.load(f)
        for part in key.split("."):
            d = d[int(part)] if isinstance(d, list) else d[part]
        return float(d)

    return Source(f"{rel}: {key}", read)


def rx(rel, pattern, agg="first", group=1):
    """Group `group` of regex `pattern` on committed text file `rel` (first match, or an
    aggregate over all matches)."""
    cre = re.compile(pattern, re.M)

    def read(root):
        with open(_path(root, rel), errors="replace") as f:
            text = f.read()
        vals = [float(m.group(group).replace(",", "")) for m in cre.finditer(text)]
        return _aggregate(vals, agg, f"{rel} /{pattern}/")

    return Source(f"{rel}: /{pattern}/" + (f" ({agg})" if agg != "first" else ""), read)


def derive(describe, f, *sources):
    def read(root):
        return f(*[s.read(root) for s in sources])

    return Source(describe + " from " + "; ".join(s.describe for s in sources), read)


# ---------------------------------------------------------------------------------------------
# Where a number is quoted


class Cell:
    def __init__(self, doc, row_key, index):
        self.doc, self.row_key, self.index = doc, row_key, index

    def __repr__(self):
        return f"{self.doc}: row '{self.row_key}', value #{self.index}"


class Text:
    def __init__(self, doc, pattern):
        self.doc, self.pattern = doc, pattern

    def __repr__(self):
        return f"{self.doc}: /{self.pattern}/"


class Entry:
    def __init__(self, where, source, scale=1.0, absolute=False):
        self.where, self.source, self.scale, self.absolute = where, source, scale, absolute


# ---------------------------------------------------------------------------------------------
# The registered numbers

CHECK = "validation/check/summary.csv"
CHECK_TXT = "validation/check/summary.txt"
CONV_TXT = "validation/convergence/study/summary.txt"
SWEEP = "validation/sweeps/t_H/sweep.csv"
PEERS = "validation/peers/results/skfem_vs_tribofe_ny2.csv"
FIG4 = "validation/precursors/fe_fig4/summary.csv"
HEIGHTS = "validation/precursors/heights/heights.csv"
SHARES = "validation/precursors/convention/shares.csv"
CONV_TABLE = "validation/precursors/convention/table.csv"
H1_LOG = "validation/dynamics/paper/paper_h1_dc4.6214e-7.log"
REP_LOG = "validation/dynamics/converge/replicate/r0.9_g0.35_h0.5_dc2.3107e-7.log"
REGIME = "validation/dynamics/paper/regime_h0.5_dc2.3107e-7_heal_all.txt"
REGIME25 = "validation/dynamics/paper/regime_h0.25_dc1.1554e-7_heal_all.csv"
TABLE = "validation/dynamics/converge/table.csv"
H125_LOG = "validation/dynamics/converge/r0.9_g0.35_h0.125_dc2.3107e-7.log"
THIN_LOG = "validation/dynamics/paper/thin_t1mm_h0.25.log"
THIN_ADV = "validation/dynamics/paper/thin_t1mm_h0.25_advances.csv"
HOSTILE = "validation/inputs/hostile.tsv"

FN = lambda v: {"FN": v}  # noqa: E731
EVENT_F = r"^event \d+ \(\w+\) at X = [^:]*: F/\(mu_s N\) ([0-9.]+) -> [0-9.]+, slipped ([-0-9.]+)\.\.([-0-9.]+) L"


def dyn(r, h=None, eta="default", ws="default"):
    """table.csv rows of the dynamic runs at r (one scene per r), mesh h (mm; None: all)."""
    w = {"r": r, "run": "dynamics", "eta": eta, "ws": ws}
    if h is not None:
        w["h_mm"] = h
    return w


def dyn_dampings(r):
    """The paper's-scene rows over three meshes (default damping) and three dampings."""
    return {"r": r, "run": "dynamics", "ws": "default"}


def model_fig4(col):
    return csv_(FIG4, col, {"source": "model"})


F = FINDINGS
R = README


def cells(doc, key, sources, **kw):
    return [Entry(Cell(doc, key, i), s, **kw) for i, s in enumerate(sources)]


NUMBERS = []
add = NUMBERS.extend

# -- the check, in README and findings ------------------------------------------------------
for fn, row in (("0", "| 0 |"), ("0.41", "| 0.41 |"), ("0.82", "| 0.82 |")):
    srcs = [
        csv_(CHECK, "slope_interior", FN(fn)),
        csv_(CHECK, "slope_model", FN(fn)),
        csv_(CHECK, "tau_center", FN(fn)),
        csv_(CHECK, "edge_p_left_t", FN(fn)),
        csv_(CHECK, "edge_p_right_t", FN(fn)),
    ]
    if fn != "0":
        srcs += [csv_(CHECK, "edge_tau_left_t", FN(fn)), csv_(CHECK, "edge_tau_right_t", FN(fn))]
    add(cells(R, row, srcs))

slope_below = derive(
    "100 (1 - slope_interior/slope_model)",
    lambda a, b: 100 * (1 - a / b),
    csv_(CHECK, "slope_interior", FN("0.82")),
    csv_(CHECK, "slope_model", FN("0.82")),
)
add([
    Entry(Text(R, r"The interior slope is (1\.8) % below the model's"), slope_below),
    Entry(Text(R, r"rigid plate down by 0\.05 t \(N = ([\d.]+) N/m"), toml_("validation/check/run.toml", "results.cases.0.n_force_n_per_m")),
])
add(cells(F, "interior pressure slope at F/N = 0.82", [csv_(CHECK, "slope_interior", FN("0.82")), csv_(CHECK, "slope_model", FN("0.82"))]))
add(cells(F, "the interior slope below the model's", [slope_below]))
add(cells(F, "edge zones on the paper's mesh at F/N = 0.82", [
    csv_(CHECK, c, FN("0.82")) for c in ("edge_p_left_t", "edge_p_right_t", "edge_tau_left_t", "edge_tau_right_t")
]))
CONV_LINE = r"^\s+0\.82\s+[-0-9.]+\s+[-0-9.]+\s+[-0-9.]+\s+[-0-9.]+ \|\s+([0-9.]+)/([0-9.]+)\s+([0-9.]+)/([0-9.]+)"
add(cells(F, "the same, converged (graded qua8", [rx(CHECK_TXT, CONV_LINE, "first", g) for g in (1, 2, 3, 4)]))
add(cells(F, "normal force N from pressing the plate", [csv_(CHECK, "N", FN("0.82"))]))
STRIP = r"strip clamped on both faces.*k = ([0-9.]+), falls to 5 % within ([0-9.]+) t"
add(cells(F, "slowest compression mode of the clamped strip", [rx(CONV_TXT, STRIP, "first", 1), rx(CONV_TXT, STRIP, "first", 2)]))
nu04 = {"poisson": lambda v: abs(float(v) - 0.4) < 1e-12, "FN": lambda v: float(v) > 0}
add(cells(F, "corrected slope (thin_layer), worst relative error", [
    csv_(SWEEP, "slope_ratio_corrected", nu04, "max", value=lambda r: abs(1 - float(r["slope_ratio_corrected"]))),
    csv_(SWEEP, "slope_ratio", nu04, "max", value=lambda r: 100 * abs(1 - float(r["slope_ratio"]))),
]))
add(cells(F, "scikit-fem on the same mesh", [csv_(PEERS, "max_dp", {}, "max")]))

# -- quasi-static precursors ------------------------------------------------------------------
for key, src in (("| model |", "model"), ("| FE, rule paper |", "paper"), ("| FE, rule overdamped |", "overdamped")):
    add(cells(F, key, [csv_(FIG4, c, {"source": src}) for c in (
        "precursors_advancing_5t", "F1_over_mu_s_N", "x1_over_L", "Fmax_over_mu_s_N")]))
g_from = lambda lo: {"g": lambda v: float(v) >= lo - 1e-9}  # noqa: E731
add(cells(F, "torque sets the first precursor", [csv_(HEIGHTS, "F1_rel_dev", g_from(0.0875), "max", value=lambda r: 100 * abs(float(r["F1_rel_dev"])))]))
add(cells(F, "x_1 against the model's, largest difference", [
    csv_(HEIGHTS, "x1_over_L", g_from(0.175), "max", value=lambda r: abs(float(r["x1_over_L"]) - float(r["model_x1_over_L"])))]))
add(cells(F, "the FE's first-cycle peak over H/L", [
    csv_(HEIGHTS, "Fmax_over_mu_s_N", {}, "min"), csv_(HEIGHTS, "Fmax_over_mu_s_N", {}, "max"),
    csv_(HEIGHTS, "model_Fmax_over_mu_s_N", {}, "min"), csv_(HEIGHTS, "model_Fmax_over_mu_s_N", {}, "max")]))
add(cells(F, "peak at the thin-layer limit against the model's F_max", [
    rx(f"validation/precursors/thin_layer_r{rg}.txt", r"^F_max: .*offset from the model ([-0-9.]+) %")
    for rg in ("0.95_g0.2", "0.9_g0.35", "0.8_g0.5", "0.7_g0.3", "0.5_g0.6")]))
conv = lambda res: {"r": "0.9", "g": "0.35", "t_m": "0.002", "residual": res, "backslip": "allowed"}  # noqa: E731
add(cells(F, "the `paper` rule's residual convention", [
    csv_(CONV_TABLE, "peak_last_fe", conv("relaxed")), csv_(CONV_TABLE, "peak_last_fe", conv("pre-event")),
    csv_(CONV_TABLE, "Fmax_model", conv("relaxed"))]))
share = lambda r, g: csv_(SHARES, "share_residual", {"r": r, "g": g, "t_m": "0.002"})  # noqa: E731
add(cells(F, "share of the peak deficit the pre-event residual explains", [share("0.9", "0.35")], scale=100))
add(cells(F, "the same at (0.8, 0.5), (0.7, 0.3), (0.95, 0.2)", [share("0.8", "0.5"), share("0.7", "0.3"), share("0.95", "0.2")], scale=100))
add(cells(F, "share forbidding back-slip explains", [csv_(SHARES, "share_backslip", {}, "max")], scale=100))

# -- dynamics on the paper's scene ------------------------------------------------------------
add(cells(F, "kappa = 1.02, h = 1 mm", [
    rx(H1_LOG, r"^slip-weakening .*\((\d+) instabilities\)"),
    rx(H1_LOG, r"^dynamics: n = \d+ \(advancing; of (\d+) precursors"),
    rx(H1_LOG, r"steady sliding at mu_d reached stably at X = ([0-9.e-]+) m")]))
PAPER_IT = r"^paper's iteration .*: n = (\d+), F_1 = ([0-9.]+), x_1 = ([-0-9.]+), F_max = ([0-9.]+)"
FRONT = r"^dynamics: front advances n = (\d+), first at F = ([0-9.]+), front x = ([-0-9.]+)"
add(cells(F, "F_1, x_1: the first front advance", [
    rx(REP_LOG, FRONT, "first", 2), rx(REP_LOG, FRONT, "first", 3),
    rx(REP_LOG, PAPER_IT, "first", 2), rx(REP_LOG, PAPER_IT, "first", 3)]))
add(cells(F, "front advances before the crossing (model n)", [
    rx(REP_LOG, FRONT, "first", 1), rx(REP_LOG, PAPER_IT, "first", 1),
    rx(REP_LOG, r"^dynamics: n = (\d+) \(advancing")]))
add(cells(F, "force at the front crossing (not converged", [rx(REP_LOG, r"last peak F = ([0-9.]+)")]))

add(cells(F, "instabilities of the run", [rx(REGIME, r"^(\d+) instabilities; nucleation sites")]))
add(cells(F, "arrest against the thin-layer Griffith law", [
    rx(REGIME, r"^\|arrest - Griffith prediction\| / L over \d+: median ([0-9.]+)"),
    rx(REGIME, r"^\|arrest - zero G_c prediction\| / L over \d+: median ([0-9.]+)")]))
add(cells(F, "instabilities nucleating at an earlier arrested tip", [
    rx(REGIME, r"'previous-tip': (\d+)"), rx(REGIME, r"'trailing-edge': (\d+)")]))
add(cells(F, "kappa = 0.25 (h = 0.25 mm): the first arrest", [csv_(REGIME25, "region_last_over_L", {}, "first")]))

add(cells(F, "2.5 t ahead of the tip: change of p", [csv_("validation/dynamics/assumption5/table.csv", "dp_2_5t_median", {"r": "0.9"}), csv_("validation/dynamics/assumption5/table.csv", "dp_2_5t_90", {"r": "0.9"})]))
add(cells(F, "2.5 t ahead: change of tau", [csv_("validation/dynamics/assumption5/table.csv", "dtau_2_5t_median", {"r": "0.9"}), csv_("validation/dynamics/assumption5/table.csv", "dtau_2_5t_90", {"r": "0.9"})]))
add(cells(F, "abs(arrest - Griffith arrest from the pre-event field)", [csv_("validation/dynamics/assumption5/table.csv", "griffith_err_median_over_L", {"r": "0.9"}), csv_("validation/dynamics/assumption5/table.csv", "mu_d_err_median_over_L", {"r": "0.9"})]))
add(cells(F, "abs(arrest - Griffith arrest with the whole body's G(l))", [csv_("validation/dynamics/assumption5/table.csv", "fracture_err_median_over_L", {"r": "0.9"}), csv_("validation/dynamics/assumption5/table.csv", "first_fracture_over_L", {"r": "0.9"})]))
add(cells(F, "the Griffith arrest error, median", [csv_("validation/dynamics/assumption5/table.csv", "griffith_err_median_over_L", {"r": "0.8"}), csv_("validation/dynamics/assumption5/table.csv", "griffith_err_median_over_L", {"r": "0.7"})]))
add(cells(F, "force-drop timing (secondary)", [csv_(TABLE, "drop_moving", dyn("0.9", h)) for h in ("0.5", "0.25", "0.125")]))
add(cells(F, "paper's scene: F_1 over three meshes and three dampings", [
    csv_(TABLE, "f1_front", dyn_dampings("0.9"), "min"), csv_(TABLE, "f1_front", dyn_dampings("0.9"), "max")]))
add(cells(F, "paper's scene: x_1 over three meshes and three dampings", [
    csv_(TABLE, "x1_front", dyn_dampings("0.9"), "min"), csv_(TABLE, "x1_front", dyn_dampings("0.9"), "max")]))
LOG7 = "validation/dynamics/converge/r0.7_g0.5_h{}_dc1.274e-6.log"
add(cells(F, "(0.7, 0.5): the first instability's onset force at h", [rx(LOG7.format(h), EVENT_F, "first", 1) for h in ("0.5", "0.25", "0.125")]))
add(cells(F, "(0.7, 0.5): where it starts slipping, near end", [rx(LOG7.format(h), EVENT_F, "first", 2) for h in ("0.5", "0.25", "0.125")]))
add(cells(F, "paper's scene: spread of the front envelope", [
    csv_(TABLE, f"tip_curve_over_L_at_F_{f}", dyn("0.9"), "spread") for f in ("0.8", "0.85", "0.9")]))
peak9 = lambda agg: csv_(TABLE, "f_peak", dyn_dampings("0.9"), agg)  # noqa: E731
add(cells(F, "paper's scene: largest force before the crossing, over three meshes", [
    peak9("min"), peak9("max"),
    derive("(min + max)/2", lambda a, b: (a + b) / 2, peak9("min"), peak9("max")),
    derive("(max - min)/2", lambda a, b: (b - a) / 2, peak9("min"), peak9("max"))]))
peak_below = derive("100 (1 - (min + max)/2 / model F_max)", lambda a, b, m: 100 * (1 - (a + b) / 2 / m),
                    peak9("min"), peak9("max"), model_fig4("Fmax_over_mu_s_N"))
add(cells(F, "the same against the model's F_max", [peak_below]))
add(cells(F, "paper's scene, not converged: front advances", [
    csv_(TABLE, "n_front", dyn("0.9", h)) for h in ("0.5", "0.25", "0.125")] + [
    csv_(TABLE, "n_front", dyn("0.9", "0.5", eta)) for eta in ("1.5065e-4", "7.5326e-5")]))
add(cells(F, "paper's scene, not converged: the crossing force", [
    csv_(TABLE, "f_cross", dyn_dampings("0.9"), "min"), csv_(TABLE, "f_cross", dyn_dampings("0.9"), "max")]))
add(cells(F, "(0.7, 0.5): first front advance", [csv_(TABLE, "f1_front", dyn("0.7", h)) for h in ("0.5", "0.25", "0.125")]))
add(cells(F, "(0.7, 0.5): spread of the envelope", [
    csv_(TABLE, f"tip_curve_over_L_at_F_{f}", dyn("0.7"), "spread") for f in ("0.75", "0.8")]))
add(cells(F, "(0.7, 0.5): largest force before the crossing at h", [csv_(TABLE, "f_peak", dyn("0.7", h)) for h in ("0.5", "0.25", "0.125")]))
add(cells(F, "(0.7, 0.5): front advances", [csv_(TABLE, "n_front", dyn("0.7", h)) for h in ("0.5", "0.25", "0.125")]))
add(cells(F, "(0.8, 0.2): first front advance", [csv_(TABLE, "f1_front", dyn("0.8", "0.5"))]))
add(cells(F, "(0.8, 0.2): largest force before the crossing", [csv_(TABLE, "f_peak", dyn("0.8", h)) for h in ("0.5", "0.25", "0.125")]))
add(cells(F, "(0.8, 0.2): front advances", [csv_(TABLE, "n_front", dyn("0.8", h)) for h in ("0.5", "0.25", "0.125")]))
cpu9 = [csv_(TABLE, "cpu_s", dyn("0.9", h)) for h in ("0.5", "0.25", "0.125")]
add(cells(F, "cost, paper's scene: CPU seconds", cpu9 + [
    derive("CPU(h/2)/CPU(h)", lambda a, b: b / a, cpu9[0], cpu9[1]),
    derive("CPU(h/2)/CPU(h)", lambda a, b: b / a, cpu9[1], cpu9[2])]))
WALL = r"wall time ([0-9.]+) s \(setup [0-9.]+ s, static loading ([0-9.]+) s"
add(cells(F, "share of the h = 0.125 mm run's wall time", [
    derive("100 static/wall", lambda s, w: 100 * s / w, rx(H125_LOG, WALL, "first", 2), rx(H125_LOG, WALL, "first", 1))]))

WS = "validation/dynamics/converge/r{}_h0.5_dc{}_ws{}.log"
ws7 = lambda n: WS.format("0.7_g0.5", "1.274e-6", n)  # noqa: E731
ws9 = lambda n: WS.format("0.9_g0.35", "2.3107e-7", n)  # noqa: E731
add(cells(F, "(0.7, 0.5), by weakening step: the first instability's onset force", [rx(ws7(20), EVENT_F, "first", 1), rx(ws7(5120), EVENT_F, "first", 1)]))
add(cells(F, "(0.7, 0.5): where it slips, far end", [rx(ws7(20), EVENT_F, "first", 3), rx(ws7(5120), EVENT_F, "first", 3)]))
ws_rows = {"r": "0.7", "run": "dynamics", "ws": lambda v: v not in ("default", "")}
add(cells(F, "(0.7, 0.5): largest force before the crossing over N", [
    csv_(TABLE, "f_peak", ws_rows, "min"), csv_(TABLE, "f_peak", ws_rows, "max")]))
add(cells(F, "paper's scene: shift of the first instability's onset force", [
    derive("F(N = 20) - F(N = 1280)", lambda a, b: a - b, rx(ws9(20), EVENT_F, "first", 1), rx(ws9(1280), EVENT_F, "first", 1))]))


def _elapsed(s):
    parts = [float(p) for p in s.split(":")]
    return sum(p * 60 ** i for i, p in enumerate(reversed(parts)))


class _Elapsed(Source):
    def __init__(self, rel):
        inner = re.compile(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([0-9:.]+)")

        def read(root):
            with open(_path(root, rel), errors="replace") as f:
                return _elapsed(inner.search(f.read()).group(1))

        super().__init__(f"{rel}: Elapsed (wall clock) in s", read)


add(cells(F, "first cycle to the crossing: wall, CPU seconds", [_Elapsed(THIN_LOG), rx(THIN_LOG, r"User time \(seconds\): ([0-9.]+)")]))
add(cells(F, "first front advance: F, front x/L", [csv_(THIN_ADV, "F_over_mu_s_N", {"advance": "1"}), csv_(THIN_ADV, "front_over_L", {"advance": "1"})]))
add(cells(F, "it nucleates inside the trailing edge by", [
    csv_(THIN_ADV, "x_nucleation_over_L", {"advance": "1"}, value=lambda r: (float(r["x_nucleation_over_L"]) + 0.5) * 400)]))
add(cells(F, "the one precursor definition (nucleus within 5 t", [rx(THIN_LOG, r"^dynamics: n = \d+ .*F_1 = ([0-9.]+)")]))
add(cells(F, "front advances before the crossing (model 10); the crossing force", [
    rx(THIN_LOG, FRONT, "first", 1), rx(THIN_LOG, r"last peak F = ([0-9.]+)")]))

# -- README's findings table: the same reads as docs/findings.md's rows -----------------------
add(cells(R, "The bonded check holds in the interior", [slope_below]))
add(cells(R, "The corrected model (`analytical::thin_layer`) fixes the slope", [
    csv_(SWEEP, "slope_ratio_corrected", nu04, "max", value=lambda r: abs(1 - float(r["slope_ratio_corrected"]))),
    csv_(SWEEP, "slope_ratio", nu04, "max", value=lambda r: 100 * abs(1 - float(r["slope_ratio"])))]))
add(cells(R, "Edge zones are the clamped strip's slowest decay mode", [rx(CONV_TXT, STRIP, "first", 1), rx(CONV_TXT, STRIP, "first", 2)]))
add(cells(R, "Torque sets the first precursor", [csv_(HEIGHTS, "F1_rel_dev", g_from(0.0875), "max", value=lambda r: 100 * abs(float(r["F1_rel_dev"])))]))
add(cells(R, "The stick-slip peak stays below the model's F_max", [
    rx("validation/precursors/thin_layer_r0.95_g0.2.txt", r"^F_max: .*offset from the model ([-0-9.]+) %"),
    rx("validation/precursors/thin_layer_r0.5_g0.6.txt", r"^F_max: .*offset from the model ([-0-9.]+) %")]))
add(cells(R, "relaxed residual explains part of that deficit", [share("0.9", "0.35")], scale=100))
add(cells(R, "Dynamics at kappa = 1.02", [
    rx(H1_LOG, r"^dynamics: n = \d+ \(advancing; of (\d+) precursors"), rx(H1_LOG, r"^slip-weakening .*\((\d+) instabilities\)")]))
add(cells(R, "Dynamics at kappa = 0.51: the first precursor", [
    rx(REP_LOG, FRONT, "first", 2), rx(REP_LOG, FRONT, "first", 3),
    rx(REP_LOG, PAPER_IT, "first", 2), rx(REP_LOG, PAPER_IT, "first", 3)]))
add(cells(R, "The largest force before the front crossing", [
    derive("(min + max)/2", lambda a, b: (a + b) / 2, peak9("min"), peak9("max")),
    derive("(max - min)/2", lambda a, b: (b - a) / 2, peak9("min"), peak9("max")),
    model_fig4("Fmax_over_mu_s_N")]))
add(cells(R, "The count of front advances does not converge", [
    csv_(TABLE, "n_front", dyn("0.9", h)) for h in ("0.5", "0.25", "0.125")] + [model_fig4("precursors_advancing_5t")]))
add(cells(R, "Fronts stop short", [
    rx(REGIME, r"^\|arrest - Griffith prediction\| / L over \d+: median ([0-9.]+)"),
    rx(REGIME, r"^\|arrest - zero G_c prediction\| / L over \d+: median ([0-9.]+)")]))
REF = "validation/dynamics/refine/paper/refinement.csv"
add(cells(R, "A refinement series at fixed physics", [
    csv_(REF, "value_at_h_5e-4_m", {"quantity": "first_advance_F_over_mu_s_N"}),
    csv_(REF, "value_at_h_2.5e-4_m", {"quantity": "first_advance_F_over_mu_s_N"}),
    csv_(REF, "value_at_h_5e-4_m", {"quantity": "largest_F_before_crossing_over_mu_s_N"}),
    csv_(REF, "value_at_h_2.5e-4_m", {"quantity": "largest_F_before_crossing_over_mu_s_N"})]))
add(cells(R, "The control case H = 0", [
    csv_("validation/dynamics/control_h0/summary.csv", "largest_F_before_crossing_over_mu_s_N"),
    rx("validation/dynamics/control_h0/h0.txt", r"F_max = ([0-9.]+)")]))
T205 = "validation/dynamics/tpv205_2d/table.csv"
add(cells(R, "TPV205-2D, the field's 2D rupture benchmark", [
    csv_(T205, None, agg="max", value=lambda r: abs(float(r["arrival_h100_minus_ref_s"]))),
    csv_(T205, None, {"x_m": lambda x: abs(float(x)) <= 4500}, "max",
         value=lambda r: 100 * abs(float(r["slip_h100_over_ref_minus_1"])))]))
A5 = "validation/dynamics/assumption5/table.csv"
a5 = lambda r: {"r": r}  # noqa: E731
add(cells(R, "Assumption 5 (the field ahead", [
    csv_(A5, "dp_2_5t_median", a5("0.9")), csv_(A5, "dtau_2_5t_median", a5("0.9")),
    csv_(A5, "griffith_err_median_over_L", a5("0.9"))]))
add(cells(R, "the model's F_1 fails", [
    csv_(TABLE, "f1_front", dyn("0.7", "0.5")),
    rx("validation/dynamics/converge/r0.7_g0.5_h0.5_dc1.274e-6.log", PAPER_IT, "first", 2)]))

add(cells(F, "hostile inputs rerun", [
    csv_(HOSTILE, "verdict", {}, "count"), csv_(HOSTILE, "verdict", {"verdict": "ok"}, "count")]))


# ---------------------------------------------------------------------------------------------
# Reading the docs


def _strip_unread(cell):
    """Drop `code spans`, link targets and HTML comments: their numbers are not quoted values."""
    cell = re.sub(r"`[^`]*`", lambda m: " " * len(m.group(0)), cell)
    cell = re.sub(r"\]\([^)]*\)", lambda m: " " * len(m.group(0)), cell)
    cell = re.sub(r"<!--.*?-->", lambda m: " " * len(m.group(0)), cell)
    return cell


def numbers_in(text):
    """(start, end, quoted) of every number in `text` (already stripped)."""
    return [(m.start("num"), m.end("num"), m.group("num")) for m in NUM.finditer(text)]


def split_row(line):
    """The cells of a table row with their offsets in the line."""
    cells_, start = [], line.index("|") + 1
    for part in line[start:].split("|")[:-1]:
        cells_.append((start, part))
        start += len(part) + 1
    return cells_


def tables(lines):
    """Yield (header cells, [(line number, line)]) for every markdown table."""
    i = 0
    while i < len(lines):
        if lines[i].lstrip().startswith("|") and i + 1 < len(lines) and re.match(r"^\s*\|[-:| ]+\|\s*$", lines[i + 1]):
            header = [c.strip() for _, c in split_row(lines[i])]
            rows, j = [], i + 2
            while j < len(lines) and lines[j].lstrip().startswith("|"):
                rows.append((j + 1, lines[j]))
                j += 1
            yield header, rows
            i = j
        else:
            i += 1


def value_numbers(header, line):
    """Numbers in the value cells of a row: [(start, end, quoted)] with offsets in the line."""
    out = []
    for col, (off, cell) in enumerate(split_row(line)):
        name = header[col].lower() if col < len(header) else ""
        if col == 0 or name in LABEL_COLUMNS:
            continue
        for s, e, q in numbers_in(_strip_unread(cell)):
            out.append((off + s, off + e, q))
    return out


def checked_tables(doc, lines):
    for header, rows in tables(lines):
        if doc == FINDINGS or (header and header[0] in README_TABLES):
            yield header, rows


def _find_row(doc, lines, key):
    hits = []
    for header, rows in tables(lines):
        for n, line in rows:
            first = split_row(line)[0][1]
            if key in first or key.strip() == line[: len(key.strip())]:
                hits.append((header, n, line))
    return hits


def precision(quoted):
    """Half a unit in the last quoted place."""
    q = quoted.replace(",", "").lstrip("+-")
    mant, _, exp = q.partition("e")
    decimals = len(mant.partition(".")[2])
    return 0.5 * 10.0 ** (-decimals + (int(exp) if exp else 0))


def parse(quoted):
    return float(quoted.replace(",", ""))


def slug(heading):
    """GitHub's anchor for a markdown heading."""
    h = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return h.replace(" ", "-")


def check_links(root, doc, lines):
    """Relative links of `doc` must name an existing file, and an existing heading if they
    carry an anchor."""
    problems = []
    for n, line in enumerate(lines, 1):
        for m in re.finditer(r"\]\(([^)\s]+)\)", line):
            target = m.group(1)
            if re.match(r"^[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(root, os.path.dirname(doc), path)) if path else _path(root, doc)
            if not os.path.exists(full):
                problems.append(f"{doc}:{n}: link to a missing file: {target}")
                continue
            if anchor and full.endswith(".md"):
                with open(full) as f:
                    heads = {slug(h.lstrip("#")) for h in f.read().split("\n") if re.match(r"^#{1,6} ", h)}
                if anchor not in heads:
                    problems.append(f"{doc}:{n}: link to a missing heading: {target}")
    return problems


def run(root, show=False):
    docs = {}
    for d in (README, FINDINGS):
        with open(_path(root, d)) as f:
            docs[d] = f.read().split("\n")
    problems, checked, covered = [], 0, {d: set() for d in docs}

    for e in NUMBERS:
        w = e.where
        lines = docs[w.doc]
        if isinstance(w, Cell):
            hits = _find_row(w.doc, lines, w.row_key)
            if len(hits) != 1:
                problems.append(f"{w.doc}: table row '{w.row_key}' found {len(hits)} times (want 1)")
                continue
            header, n, line = hits[0]
            nums = value_numbers(header, line)
            if w.index >= len(nums):
                problems.append(f"{w.doc}:{n}: row '{w.row_key}' has {len(nums)} numbers, entry wants #{w.index + 1}")
                continue
            s, _, quoted = nums[w.index]
            covered[w.doc].add((n, s))
        else:
            text = "\n".join(lines)
            ms = list(re.finditer(w.pattern, text))
            if len(ms) != 1:
                problems.append(f"{w.doc}: /{w.pattern}/ matches {len(ms)} times (want 1)")
                continue
            m = ms[0]
            n = text.count("\n", 0, m.start(1)) + 1
            col = m.start(1) - (text.rfind("\n", 0, m.start(1)) + 1)
            quoted = m.group(1)
            covered[w.doc].add((n, col))
        try:
            committed = e.source.read(root) * e.scale
        except Exception as err:  # a missing or changed committed file is a failure too
            problems.append(f"{w.doc}:{n}: '{quoted}' cannot be read from {e.source.describe}: {err}")
            continue
        value = parse(quoted)
        if e.absolute:
            value, committed = abs(value), abs(committed)
        tol = precision(quoted) * (1 + 1e-9) + 1e-12 * abs(committed)
        checked += 1
        ok = abs(value - committed) <= tol
        if show:
            print(f"{'ok   ' if ok else 'STALE'} {w.doc}:{n}: {quoted} vs committed {committed:.6g}  <- {e.source.describe}")
        if not ok:
            problems.append(
                f"{w.doc}:{n}: stale number '{quoted}': the committed value is {committed:.6g} "
                f"(to the quoted precision: +-{precision(quoted):g}), read from {e.source.describe}")

    for d, lines in docs.items():
        problems += check_links(root, d, lines)
    unregistered = 0
    for d, lines in docs.items():
        for header, rows in checked_tables(d, lines):
            for n, line in rows:
                for s, _, q in value_numbers(header, line):
                    if (n, s) not in covered[d]:
                        unregistered += 1
                        problems.append(f"{d}:{n}: number '{q}' in a checked table is not registered in "
                                        f"validation/readme_numbers.py (add an entry reading it from a committed output)")
    return checked, problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=ROOT, help="the checkout (default: this script's)")
    ap.add_argument("--list", action="store_true", help="print every number with its committed value")
    a = ap.parse_args()
    checked, problems = run(a.root, a.list)
    stale = sum(1 for p in problems if "stale number" in p)
    for p in problems:
        print(p, file=sys.stderr)
    print(f"{checked} numbers checked, {stale} stale" + (f", {len(problems) - stale} other problems" if len(problems) > stale else ""))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
