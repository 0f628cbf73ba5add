"""The Python package against the command built from the same library.

Tolerances: the command writes CSV numbers with 12 or more significant digits, so values read
back agree with the package's float64 arrays to ~1e-12 relative; 1e-10 (relative, with an
absolute floor of 1e-12 N/L for values that are zero in theory) leaves room for printing only.
"""

import csv
import re
import threading
from pathlib import Path

import numpy as np
import pytest

import tribofe
from conftest import assert_interrupt_stops, run_cli


def read_csv(path: Path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [r[k] for r in rows] for k in rows[0]}


def floats(col):
    return np.array([float(v) for v in col])


def assert_table_is_the_csv(name, table, path, digits, units=None, measured=()):
    """`table` (a DataFrame or dict of arrays) has every column of the CSV at `path`, in its
    order; integer cells are int64 and equal; numbers, rounded to the CSV's `digits`
    significant digits, equal the cells to 1e-10 relative (an empty cell is NaN); text equal.
    With `units`, every column has one. Columns in `measured` (wall times) are only named."""
    cli = read_csv(path)
    assert list(table.keys()) == list(cli.keys()), name
    for col, cells in cli.items():
        if col in measured:
            continue
        got = np.asarray(table[col])
        if cells and all(c.lstrip("-").isdigit() for c in cells):
            assert got.dtype == np.int64, (name, col, got.dtype)
            np.testing.assert_array_equal(got, [int(c) for c in cells], err_msg=f"{name}.{col}")
        elif got.dtype.kind == "f":
            want = np.array([float(c) if c else np.nan for c in cells])
            printed = np.array([float(f"{v:.{digits - 1}e}") if np.isfinite(v) else v for v in got])
            np.testing.assert_allclose(printed, want, rtol=1e-10, atol=0, equal_nan=True, err_msg=f"{name}.{col}")
        else:
            assert list(got) == cells, (name, col)
    if units is not None:
        assert [c for c, _ in units] == list(cli.keys()), name


def test_check_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "check"
    r = run_cli(tribofe_bin, "check", "--out", str(out), "--no-converged", "--no-fields")
    assert r.returncode == 0, r.stderr
    res = tribofe.check()
    assert [c.fn_ratio for c in res.cases] == [0.0, 0.41, 0.82]
    for case in res.cases:
        name = "0" if case.fn_ratio == 0 else f"{case.fn_ratio:g}"
        cli = read_csv(out / f"profile_FN{name}.csv")
        for col in ("x_over_L", "p_over_pmean", "tau_over_pmean", "p_model", "tau_model", "p_corrected"):
            np.testing.assert_allclose(getattr(case, col), floats(cli[col]), rtol=1e-10, atol=1e-12, err_msg=col)
    # The paper's check itself (README): interior slope at F/N = 0.82 is 0.96604 against 0.984.
    assert abs(res.cases[2].metrics["slope_interior"] - 0.96604) < 5e-6
    assert res.balance_error < 1e-12


def test_solve_equals_the_command(tribofe_bin, tmp_path):
    import tomllib

    # Uniaxial stress: rollers at the bottom and left, a uniform pressure of 10 Pa on the top.
    # The exact field is linear, so every element reproduces it: sigma_yy = -10 Pa at every
    # node, the bottom carries Fy = 10 Pa x lx, and the top sinks by (1 - nu^2)/E x 10 Pa x ly
    # (plane strain).
    args = ["--bottom", "roller", "--left", "roller", "--top", "t=0,-10", "--nx", "10", "--ny", "2"]
    out = tmp_path / "solve"
    r = run_cli(tribofe_bin, "solve", *args, "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.solve(bottom="roller", left="roller", top="t=0,-10", nx=10, ny=2)
    assert isinstance(res, tribofe.SolveResult)
    with open(out / "run.toml", "rb") as f:
        cli = tomllib.load(f)["results"]
    assert res.unknowns == cli["unknowns"]
    for side, fxy in res.reactions_N_per_m.items():
        np.testing.assert_allclose(fxy, cli[f"reaction_{side}_n_per_m"], rtol=1e-12, atol=1e-12, err_msg=side)
    d = tribofe.defaults()["solve"]
    lx, ly, e, nu = d["lx"], d["ly"], d["young"], d["poisson"]
    assert abs(res.reactions_N_per_m["bottom"][1] - 10 * lx) < 1e-9 * 10 * lx
    np.testing.assert_allclose(res.applied_N_per_m, (0.0, -10 * lx), rtol=1e-12)
    np.testing.assert_allclose(np.add(res.total_reaction_N_per_m, res.applied_N_per_m), 0.0, atol=1e-9)
    np.testing.assert_allclose(res.stress_Pa[:, 1], -10.0, rtol=1e-9)
    top = np.abs(res.nodes_m[:, 1] - ly) < 1e-12
    np.testing.assert_allclose(res.displacement_m[top, 1], -(1 - nu**2) / e * 10 * ly, rtol=1e-9)
    assert list(res.reactions["side"]) == ["bottom", "right", "top", "left"]
    # A bad side condition and a bad element are refused by keyword, the accepted forms listed.
    with pytest.raises(tribofe.InputError) as e:
        tribofe.solve(left="glue")
    assert str(e.value).startswith("invalid left=") and "roller" in str(e.value), str(e.value)
    with pytest.raises(tribofe.InputError, match="element="):
        tribofe.solve(element="qua5")
    with pytest.raises(tribofe.InputError, match="nx="):
        tribofe.solve(nx=0)


def test_slide_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "slide"
    args = ["--law", "static-kinetic", "--r", "0.9", "--g", "0.35", "--cycles", "1"]
    r = run_cli(tribofe_bin, "slide", *args, "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.slide(law="static-kinetic", r=0.9, g=0.35, cycles=1, progress=False)
    # Every column of loading.csv and events.csv (13 significant digits), codes as int64.
    assert_table_is_the_csv("loading", res.loading, out / "loading.csv", 13, res.units["loading"])
    assert_table_is_the_csv("events", res.events, out / "events.csv", 13, res.units["events"])
    assert res.loading.attrs["units"]["X_m"] == "m" and res.loading["n_slip"].dtype == np.int64
    events = read_csv(out / "events.csv")
    # States as (states x nodes) arrays: every state balances the normal force N = 1 N/m.
    p = res.states["p_force_N_per_m"]
    assert p.shape == (len(events["kind"]), len(res.x_over_L))
    drive = np.asarray(res.loading["N_N_per_m"]) > 0
    np.testing.assert_allclose(p[drive].sum(axis=1), np.asarray(res.loading["N_N_per_m"])[drive], rtol=1e-9)
    assert set(np.unique(res.states["state_code"])) <= {0.0, 1.0, 2.0}


def test_plane_stress_is_plane_strain_with_the_mapped_moduli():
    # Plane stress with (E, nu) has the in-plane law of plane strain with
    # E' = E (1 + 2 nu)/(1 + nu)^2, nu' = nu/(1 + nu): the profiles agree to round-off.
    base = tribofe.Scene(h=0.001)
    e, nu = base.young, base.poisson
    stress = tribofe.check(base.replace(state="plane-stress", width=0.005))
    strain = tribofe.check(
        base.replace(young=e * (1 + 2 * nu) / (1 + nu) ** 2, poisson=nu / (1 + nu))
    )
    for a, b in zip(stress.cases, strain.cases):
        for name in ("p_over_pmean", "tau_over_pmean", "p_corrected"):
            np.testing.assert_allclose(getattr(a, name), getattr(b, name), rtol=0, atol=1e-10)
    with pytest.raises(tribofe.errors.InputError, match="width="):
        tribofe.Scene(state="plane-stress")


def test_check_fields_on_request():
    res = tribofe.check(fields=True)
    f = res.fields
    assert f["nodes_m"].shape == (res.n_nodes, 2)
    assert len(f["displacement_m"]) == 3 and f["displacement_m"][2].shape == (res.n_nodes, 2)
    # The base is bonded (u = v = 0 at y = 0), and the nodal sigma_yy on the base, averaged
    # with the tributary widths, is the mean pressure -N/L (1 % for the extrapolation error).
    base = np.abs(f["nodes_m"][:, 1]) < 1e-12
    assert np.all(f["displacement_m"][2][base] == 0.0)
    case = res.cases[0]
    x = f["nodes_m"][base, 0]
    order = np.argsort(x)
    syy = f["stress_Pa"][0][base, 1][order]
    mean = np.trapezoid(syy, x[order]) / (x.max() - x.min())
    assert abs(mean + case.N_N_per_m / 0.4) < 0.01 * case.N_N_per_m / 0.4
    assert tribofe.check().fields is None


def test_rupture_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "rupture"
    r = run_cli(tribofe_bin, "rupture", "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.dynamics.rupture(progress=False)
    cli = read_csv(out / "arrival.csv")
    x = np.asarray(res.x_m)
    t = np.asarray(res.t_arrival_s)
    # arrival.csv holds the nodes with x >= 0 that the front reached (the centre node sits at
    # ~1e-16 m from the mesher's sums, so "x >= 0" is taken with a tolerance of 1e-9 h).
    mask = (x >= -1e-12) & np.isfinite(t)
    np.testing.assert_allclose(x[mask], floats(cli["x_m"]), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(t[mask], floats(cli["t_arrival_s"]), rtol=1e-11)
    summary = read_csv(out / "summary.csv")
    assert abs(res.force_drop_N_per_m - float(summary["force_drop_n_per_m"][0])) <= 1e-11 * res.force_drop_N_per_m
    # The energy ledger closes to round-off (docs/dynamics-verification.md: 5.5e-15 of the work).
    e = res.energy
    assert abs(e["balance_residual_j_per_m"]) < 1e-10 * e["background_work_j_per_m"]
    # energy is energy.csv's row, every column under its name.
    energy = read_csv(out / "energy.csv")
    assert list(e) == list(energy)
    for k, v in e.items():
        assert abs(v - float(energy[k][0])) <= 1e-12 * max(abs(v), 1e-300)
    # rupture_time.csv: every node whose slip rate crossed the threshold, and summary.csv's steps.
    rt = read_csv(out / "rupture_time.csv")
    ok = np.isfinite(res.rupture_time_s)
    assert ok.sum() > 10
    np.testing.assert_allclose(res.x_m[ok], floats(rt["x_m"]), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(res.rupture_time_s[ok], floats(rt["t_s"]), rtol=1e-11)
    assert res.steps == int(summary["steps"][0])
    frames = res.to_pandas()
    assert list(frames) == ["nodes", "summary", "energy"] and len(frames["nodes"]) == len(res.x_m)
    with pytest.raises(tribofe.InputError, match="contact"):
        tribofe.dynamics.rupture(contact="glue", progress=False)
    # A ramped patch edge is the command's --patch-taper: the same arrivals, and refused when
    # wider than the patch.
    ramp = tmp_path / "ramp"
    assert run_cli(tribofe_bin, "rupture", "--patch-taper", "0.004", "--t-end", "0.02", "--out", str(ramp)).returncode == 0
    res = tribofe.dynamics.rupture(patch_taper=0.004, t_end=0.02, progress=False)
    x, t = np.asarray(res.x_m), np.asarray(res.t_arrival_s)
    mask = (x >= -1e-12) & np.isfinite(t)
    assert mask.sum() > 10
    np.testing.assert_allclose(t[mask], floats(read_csv(ramp / "arrival.csv")["t_arrival_s"]), rtol=1e-11)
    with pytest.raises(tribofe.InputError, match="patch_taper="):
        tribofe.dynamics.rupture(patch_taper=0.05, progress=False)


def test_paper_model(tribofe_bin, tmp_path):
    m = tribofe.precursors.model(0.9, 0.35)
    assert isinstance(m, tribofe.ModelResult)
    # The paper's iteration: n = 10, F_1 = 1 - g/(r + g)... = 0.72, F_max = 1/(1 + (g/r)(1 - r)).
    assert m.n == 10
    assert abs(m.F_1 - 0.72) < 1e-12
    assert abs(m.F_max - 1 / (1 + (0.35 / 0.9) * 0.1)) < 1e-12
    assert len(m.events["event"]) == 11 and np.asarray(m.events["event"]).dtype == np.int64
    # The events equal `tribofe precursors model`'s events.csv row for row (its first n + 1).
    out = tmp_path / "pm"
    assert run_cli(tribofe_bin, "precursors", "model", "--r", "0.9", "--g", "0.35", "--out", str(out)).returncode == 0
    # events.csv and the Python table are one table (the shortest decimals: 17 digits), for
    # as many events as the command wrote (it runs the peaks to convergence).
    rows = len(read_csv(out / "events.csv")["event"])
    assert rows > 11
    whole = tribofe.precursors.model(0.9, 0.35, events=rows)
    assert_table_is_the_csv("events", whole.events, out / "events.csv", 17, whole.units)
    assert list(m.to_pandas().columns)[:2] == ["event", "F_over_mu_s_N"]


def test_fe_precursor_studies(tribofe_bin, tmp_path):
    # The FE fig. 4 on the paper's scene: README's headline n = 17 (rule paper) and 4
    # (overdamped) front-advancing precursors, F_1 = 0.7319 mu_s N for both (the force at the
    # onset of the first long slip), counted by the library's one precursor definition.
    res = tribofe.precursors.fe_fig4(r=0.9, g=0.35)
    assert isinstance(res, tribofe.FeFig4Result) and list(res.runs) == ["paper", "overdamped"]
    by_rule = {rule: run.comparison for rule, run in res.runs.items()}
    assert by_rule["paper"]["n_fe_advancing"] == 17
    assert by_rule["overdamped"]["n_fe_advancing"] == 4
    assert abs(by_rule["paper"]["F_1_fe"] - 0.7319) < 5e-5
    assert abs(by_rule["overdamped"]["F_1_fe"] - 0.7319) < 5e-5
    assert res.definition.startswith("precursor: ")
    # Front advances: the paper rule restarts every front at the trailing edge, so they are
    # its advancing precursors; the overdamped rule's re-slips may join the front from inside.
    assert by_rule["paper"]["n_front"] == 17
    assert by_rule["paper"]["x_1_front"] == by_rule["paper"]["x_1_fe"]
    assert by_rule["overdamped"]["n_front"] >= 4
    assert len(res.runs["paper"].x_arrest_fe_over_L) == 17
    # summary: the command's summary.csv, the library's one table (a model row, then a row
    # per rule), every column, counts int64.
    out = tmp_path / "fe"
    assert run_cli(tribofe_bin, "precursors", "fe", "--r", "0.9", "--g", "0.35", "--out", str(out)).returncode == 0
    assert_table_is_the_csv("summary", res.summary, out / "summary.csv", 17, res.units)
    table = res.summary
    assert list(table["source"]) == ["model", "paper", "overdamped"]
    np.testing.assert_array_equal(table["precursors_advancing_5t"], [10, 17, 4])
    np.testing.assert_array_equal(table["front_advances"][1:], [by_rule["paper"]["n_front"], by_rule["overdamped"]["n_front"]])
    with pytest.warns(DeprecationWarning):
        np.testing.assert_array_equal(res.comparison["n_fe_advancing"], [17, 4])
    frames = res.to_pandas()
    assert set(frames) == {"summary", "paper_loading", "paper_events", "overdamped_loading", "overdamped_events"}
    # fig. 5 equals `tribofe precursors fe-map`'s fig5_fe.csv cell for cell (the paper rule).
    out = tmp_path / "fm"
    assert run_cli(tribofe_bin, "precursors", "fe-map", "--resolution", "3", "--out", str(out)).returncode == 0
    cells = tribofe.precursors.fe_fig5(resolution=3, progress=False)
    assert isinstance(cells, tribofe.FeFig5Result)
    t = cells.table
    # fig5_fe.csv and the Python table are one table: every column, the counts int64; the
    # wall times are measured, so only named.
    seconds = [c for c in t if c.endswith("_seconds")]
    assert seconds == ["paper_seconds", "overdamped_seconds"]
    assert_table_is_the_csv("fig5_fe", t, out / "fig5_fe.csv", 17, cells.units, measured=seconds)
    assert len(cells) == 9 and set(t["paper_status"]) <= {"done", "capped", "refused"}
    assert np.asarray(t["model_precursors"]).dtype == np.int64
    # The model's n in each cell equals the paper's iteration.
    for r, g, n in zip(t["r"], t["g"], t["model_precursors"]):
        assert n == tribofe.precursors.model(r, g).n


def test_n_map_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "map"
    assert run_cli(tribofe_bin, "precursors", "map", "--resolution", "12", "--out", str(out)).returncode == 0
    res = tribofe.precursors.map(resolution=12)
    assert isinstance(res, tribofe.NMapResult) and len(res) == 144
    assert_table_is_the_csv("n_map", res.table, out / "n_map.csv", 17, res.units)
    # The paper's fig. 5: no precursor below the line g = (1 - r)/2 and at least one above
    # (no cell centre of a 12 x 12 grid lies on it).
    r, g, n = (np.asarray(res.table[k]) for k in ("r", "g", "n"))
    np.testing.assert_array_equal(n == 0, g < (1 - r) / 2)
    with pytest.raises(tribofe.InputError, match="resolution=1"):
        tribofe.precursors.map(resolution=1)


def test_precursor_series_equal_the_command(tribofe_bin, tmp_path):
    # thin-layer, heights and dc: each table is the command's CSV for the same options, every
    # column (the wall time measured, so only named), counts int64.
    runs = [
        ("thin-layer", ["--t-over-l", "0.02,0.01"], "thin_layer.csv",
         lambda: tribofe.precursors.thin_layer([0.02, 0.01])),
        ("heights", ["--h-over-l", "0.05,0.1", "--length", "0.1"], "heights.csv",
         lambda: tribofe.precursors.heights([0.05, 0.1], tribofe.Scene(length=0.1))),
        ("dc", ["--dc", "1e-7", "--length", "0.1"], "dc.csv",
         lambda: tribofe.precursors.dc([1e-7], tribofe.Scene(length=0.1))),
    ]
    got = {}
    for cmd, args, csv_name, call in runs:
        out = tmp_path / cmd
        r = run_cli(tribofe_bin, "precursors", cmd, *args, "--out", str(out))
        assert r.returncode == 0, r.stderr
        res = call()
        assert isinstance(res, tribofe.SeriesResult)
        assert_table_is_the_csv(cmd, res.table, out / csv_name, 17, res.units, measured=("seconds",))
        assert np.asarray(res.table["precursors_advancing_5t"]).dtype == np.int64
        got[cmd] = res
    # The model's columns are the paper's iteration at (0.9, 0.35): n = 10, F_1 = 0.72.
    tl = got["thin-layer"].table
    np.testing.assert_array_equal(tl["model_precursors"], [10, 10])
    np.testing.assert_allclose(tl["model_F1_over_mu_s_N"], 0.72, rtol=1e-12)
    # heights keeps mu_d fixed, so g = 6 mu_d H/L on every row (to round-off).
    h = got["heights"]
    np.testing.assert_allclose(h.table["g"], 6 * h.mu_d * np.asarray(h.table["H_over_L"]), rtol=1e-12)
    # dc: the paper rule's row (D_c = 0) first, then each D_c.
    np.testing.assert_array_equal(got["dc"].table["Dc_m"], [0.0, 1e-7])
    assert dict(got["dc"].units)["Dc_m"] == "m"


def test_interrupt_stops_a_precursor_series_within_a_second(tmp_path):
    # The D_c = 1e-6 m run on the small scene takes several seconds (slip weakening, one
    # cycle): SIGINT 2 s in stops it at its next solve.
    assert_interrupt_stops(tmp_path, "tribofe.precursors.dc([1e-6], tribofe.Scene(length=0.1))", 2.0)


def test_bonded_comparison_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "bonded"
    assert run_cli(tribofe_bin, "precursors", "bonded", "--out", str(out)).returncode == 0
    res = tribofe.precursors.bonded()
    assert isinstance(res, tribofe.BondedResult)
    assert_table_is_the_csv("fe_events", res.table, out / "fe_events.csv", 17, res.units)
    t = res.table
    # Each run ends at its one stick-slip event, after its precursors (n of them).
    for model, n in (("fe", res.n_fe), ("linear", res.n_linear)):
        ss = np.asarray(t["stick_slip"])[np.asarray(t["model"]) == model]
        assert n is not None and ss[n] == 1 and not ss[:n].any(), model
    # The linear run is the paper's iteration on cells: its F_1 is the model's 0.72 to the
    # cells' resolution (h/L = 1/400).
    assert abs(res.F_1_linear - 0.72) < 1 / 400
    with pytest.raises(tribofe.InputError, match="events="):
        tribofe.precursors.bonded(events=100_001)


def test_bonded_sweep_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "bonded_sweep"
    r = run_cli(tribofe_bin, "precursors", "bonded", "--sweep", "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.precursors.bonded(sweep=True)
    # fe_sweep.csv's every column (shortest round-trip decimals: 17 digits compare them
    # exactly), counts int64 where every geometry has one, NaN for an empty cell; the quoted
    # reason a geometry is outside the model as its text.
    assert_table_is_the_csv("fe_sweep", res.sweep, out / "fe_sweep.csv", 17, res.sweep_units)
    assert_table_is_the_csv("fe_events", res.table, out / "fe_events.csv", 17, res.units)
    sw = res.sweep
    h0, t0 = 0.04 / 0.4, 0.002 / 0.4
    np.testing.assert_allclose(sw["H_over_L"], np.repeat([h0 / 4, h0 / 2, h0, 2 * h0], 4), rtol=1e-15)
    np.testing.assert_allclose(sw["t_over_L"], np.tile([t0 / 2, t0, 2 * t0, 4 * t0], 4), rtol=1e-15)
    # Theory: on the paper's linear fields every geometry that runs is the paper's iteration
    # at (0.9, 0.35): n = 10 precursors and F_1 = 0.72 mu_s N to the cells' resolution (h/L =
    # 1/400); a geometry whose FE pressure opens the contact has no figures.
    model = tribofe.precursors.model(0.9, 0.35)
    ran = np.array([w == "" for w in sw["outside_model"]])
    assert ran.any() and (~ran).any()
    np.testing.assert_array_equal(np.asarray(sw["n_linear"])[ran], model.n)
    assert np.all(np.abs(np.asarray(sw["F1_linear"])[ran] - model.F_1) < 1 / 400)
    assert np.isnan(np.asarray(sw["F1_fe"], dtype=float)[~ran]).all()
    assert all("the contact opens" in w for w in np.asarray(sw["outside_model"])[~ran])
    assert tribofe.precursors.bonded().sweep is None


def test_calls_refuse_scene_keys_that_cannot_act():
    # A scene key the call sets itself is refused, named as the Scene keyword.
    for call, key in [
        (lambda: tribofe.precursors.thin_layer([0.02], tribofe.Scene(h=0.0002)), "h"),
        (lambda: tribofe.precursors.thin_layer([0.02], tribofe.Scene(thickness=0.004)), "thickness"),
        (lambda: tribofe.precursors.heights([0.1], tribofe.Scene(fn_ratios=[0.5])), "fn_ratios"),
        (lambda: tribofe.precursors.dc([1e-7], tribofe.Scene(tol=0.1)), "tol"),
        (lambda: tribofe.edges(tribofe.Scene(height=0.02)), "height"),
        (lambda: tribofe.edges(tribofe.Scene(n_thick=4)), "n_thick"),
    ]:
        with pytest.raises(tribofe.InputError) as e:
            call()
        assert str(e.value).startswith(f"invalid Scene({key}=): cannot act here"), str(e.value)
        assert "--" not in str(e.value), str(e.value)


def test_side_push_slide_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "side_push"
    scene = ["--length", "0.1", "--thickness", "0.02", "--h", "0.002", "--rig", "side-push",
             "--push-height", "0.005", "--push-width", "0.006", "--push-stiffness", "1e9"]
    r = run_cli(tribofe_bin, "slide", *scene, "--law", "static-kinetic", "--cycles", "1", "--out", str(out))
    assert r.returncode == 0, r.stderr
    s = tribofe.Scene(length=0.1, thickness=0.02, h=0.002, rig="side-push", push_height=0.005, push_width=0.006,
                      push_stiffness=1e9)
    res = tribofe.slide(s, law="static-kinetic", cycles=1)
    # Every column of loading.csv and events.csv (13 significant digits), codes int64.
    assert_table_is_the_csv("loading", res.loading, out / "loading.csv", 13, res.units["loading"])
    assert_table_is_the_csv("events", res.events, out / "events.csv", 13, res.units["events"])
    # Theory: the push balances the base's friction; at full sliding F/N is mu_s's static
    # value reached by the last event, below it before (the pushed edge loads first).
    f_over_n = np.asarray(res.loading["F_over_N"])
    assert f_over_n.max() <= res.mu_s * (1 + 1e-9) and f_over_n[1] < res.mu_s
    # The banded operator is refused in Python's terms: the keyword and the value to give.
    with pytest.raises(tribofe.InputError) as e:
        tribofe.slide(s, law="static-kinetic", operator="banded")
    msg = str(e.value)
    assert msg.startswith("invalid operator=: banded") and 'operator="dense"' in msg and "--" not in msg, msg


def test_dynamic_side_push_slide_equals_the_command(tribofe_bin, tmp_path):
    # The thin side-pushed block of tests/it/side_push.rs to X = 3e-5 m, slip weakening.
    out = tmp_path / "side_push_dyn"
    scene = ["--length", "0.1", "--thickness", "0.004", "--h", "0.0005", "--rig", "side-push",
             "--push-height", "0.002", "--push-width", "0.002"]
    law = ["--law", "slip-weakening", "--mu-s", "0.6", "--mu-d", "0.2", "--dc", "6e-6", "--x-max", "3e-5"]
    r = run_cli(tribofe_bin, "slide", *scene, "--dynamics", *law, "--out", str(out))
    assert r.returncode == 0, r.stderr
    s = tribofe.Scene(length=0.1, thickness=0.004, h=0.0005, rig="side-push", push_height=0.002, push_width=0.002)
    res = tribofe.dynamics.slide(s, law="slip-weakening", mu_s=0.6, mu_d=0.2, dc=6e-6, x_max=3e-5)
    for name, table, digits in [("loading", res.loading, 13), ("events", res.events, 13),
                                ("dyn_events", res.dyn_events, 10)]:
        assert_table_is_the_csv(name, table, out / f"{name}.csv", digits, res.units[name])
    # Theory: the push loads the pushed edge first, so the first instability's slipped run
    # starts at x = -L/2 (the Rust test's finding, here through Python).
    first = [i for i, v in enumerate(res.dyn_events["instability"]) if v][0]
    assert res.dyn_events["region_first_over_L"][first] == -0.5


def test_precursor_studies_name_the_keyword():
    with pytest.raises(tribofe.InputError, match="t_over_l="):
        tribofe.precursors.thin_layer([0.5])
    with pytest.raises(tribofe.InputError, match="h_over_l="):
        tribofe.precursors.heights([])
    with pytest.raises(tribofe.InputError, match="max_events="):
        tribofe.precursors.dc([1e-7], tribofe.Scene(length=0.1), max_events=0)
    with pytest.raises(tribofe.InputError) as e:
        tribofe.precursors.dc([1e-7], r=1.5)
    assert str(e.value).startswith("invalid r=1.5:"), str(e.value)
    # The model's event count has the command's cap (--events at most 100 000).
    with pytest.raises(tribofe.InputError, match="events=: 100001: at most 100000"):
        tribofe.precursors.model(events=100_001)


def test_edges_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "edges"
    args = ["--length", "0.1", "--mu", "0.3,0.65", "--refine", "2,4", "--t-over-l", "0.02,0.01", "--open-refine", "4",
            "--h-over-l", "0.05,0.1"]
    r = run_cli(tribofe_bin, "edges", *args, "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.edges(tribofe.Scene(length=0.1), mu=[0.3, 0.65], refine=[2, 4], t_over_l=[0.02, 0.01],
                        open_refine=[4], h_over_l=[0.05, 0.1])
    assert isinstance(res, tribofe.EdgesResult)
    # Both tables are the command's CSVs (13 significant digits), counts int64.
    assert_table_is_the_csv("preslip", res.preslip, out / "preslip.csv", 13, res.units["preslip"])
    assert_table_is_the_csv("opening", res.opening, out / "opening.csv", 13, res.units["opening"])
    # The opening runs sit at g = 6 mu_d H/L, and their model F_1 is the paper's iteration at
    # (r, g) = (mu_d/mu_s, g).
    d = tribofe.defaults()["edges"]
    op = res.opening
    np.testing.assert_allclose(op["g"], 6 * d["mu_d"] * np.asarray(op["H_over_L"]), rtol=1e-12)
    for g, f1 in zip(op["g"], op["F1_model_over_mu_s_N"]):
        assert abs(f1 - tribofe.precursors.model(d["mu_d"] / d["mu_s"], g).F_1) < 1e-12
    with pytest.raises(tribofe.InputError, match="open_refine="):
        tribofe.edges(open_refine=[1])
    with pytest.raises(tribofe.InputError) as e:
        tribofe.edges(rule="damped")
    assert "rule=" in str(e.value) and '"paper", "overdamped"' in str(e.value), str(e.value)


def test_stability_equals_the_command(tribofe_bin, tmp_path):
    out = tmp_path / "stability"
    args = ["--study", "nu,thin,corners", "--corner-max", "8", "--n-ref", "4", "--length", "0.1"]
    r = run_cli(tribofe_bin, "stability", *args, "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.stability(tribofe.Scene(length=0.1), study=["nu", "thin", "corners"], corner_max=8, n_ref=4)
    assert isinstance(res, tribofe.StabilityResult) and list(res.tables) == ["nu", "thin", "corners"]
    # Every table is its CSV (7 significant digits), counts int64; the wall times only by name.
    for name, table in res.tables.items():
        assert_table_is_the_csv(name, table, out / f"{name}.csv", 7, res.units[name], measured=("time_s",))
    # The printed reading is summary.txt's, line for line but the thin study's (wall times).
    want = (out / "summary.txt").read_text().splitlines()
    got = res.summary.splitlines()
    differ = [a for a, b in zip(got, want) if a != b]
    assert len(got) == len(want) and len(differ) <= len(res.tables["thin"]["nx"]), differ
    # Theory: the thin layer's interior slope tends to the model's 12 (F/N)(H/L) at first
    # order in t/L: its error falls tenfold per decade of t/L (15 % for the printed ratio's
    # higher-order terms), and Williams' clamped-free corner exponent at nu = 0.4 is 0.6499.
    thin = res.tables["thin"]
    err = np.asarray(thin["slope_rel_err"])
    tl = np.asarray(thin["t_over_L"])
    fine = tl <= 1e-2
    ratios = err[fine][1:] / err[fine][:-1]
    np.testing.assert_allclose(ratios, tl[fine][1:] / tl[fine][:-1], rtol=0.15)
    assert abs(res.corners["lambda_williams"] - 0.6499) < 1e-3, res.corners
    assert res.corners["nu"] == 0.4
    # Options and scene keys that cannot act are refused naming the keyword.
    with pytest.raises(tribofe.InputError, match=r"n_ref=: cannot act"):
        tribofe.stability(study=["plate"], n_ref=4)
    with pytest.raises(tribofe.InputError, match=r"Scene\(h=\): cannot act"):
        tribofe.stability(tribofe.Scene(h=0.0005), study=["corners"])
    with pytest.raises(tribofe.InputError, match=r"study=: 'bogus' is not known"):
        tribofe.stability(study="bogus")


def test_interrupt_stops_stability_within_a_second(tmp_path):
    # The plate study solves about a hundred scenes of a few tenths of a second each and checks
    # the interrupt before and after every solve: SIGINT 2 s and 5 s into it ends it with
    # KeyboardInterrupt within a second, leaving no file.
    for after in (2.0, 5.0):
        assert_interrupt_stops(tmp_path, 'tribofe.stability(study=["plate"])', after)


def test_sweep_and_converge_tables(tribofe_bin, tmp_path):
    res = tribofe.sweep(thickness=[0.002, 0.004], height="0.02:0.08:3", progress=False)
    assert isinstance(res, tribofe.SweepResult)
    assert len(res.table["point"]) == len(res) == 2 * 3 * 3  # points x F/N
    # converge: convergence.csv's table from the library, every column, counts int64, equal
    # to the command's to its 7 printed digits (the times and peak heap are measured, so
    # they differ run to run: only their presence is compared).
    out = tmp_path / "cv"
    r = run_cli(tribofe_bin, "converge", "--n-thick", "1,2,4", "--thickness", "0.004", "--out", str(out))
    assert r.returncode == 0, r.stderr
    cv = tribofe.converge(tribofe.Scene(thickness=0.004), n_thick=[1, 2, 4], progress=False)
    assert isinstance(cv, tribofe.ConvergeResult) and "reference" in cv.summary
    assert cv.table.attrs["units"]["t_run_s"] == "s" and dict(cv.units)["dofs"] == "-"
    cli = read_csv(out / "convergence.csv")
    assert list(cv.table.keys()) == list(cli.keys())
    measured = {"t_pattern_s", "t_assembly_s", "t_symbolic_s", "t_numeric_s", "t_solve_s", "t_run_s", "peak_heap_mib"}
    for col, cells in cli.items():
        got = np.asarray(cv.table[col])
        if col in measured:
            assert got.dtype.kind == "f" and np.array_equal(np.isnan(got), [c == "" for c in cells]), col
        elif cells[0].lstrip("-").isdigit():
            assert got.dtype == np.int64, col
            np.testing.assert_array_equal(got, [int(c) for c in cells], err_msg=col)
        elif got.dtype.kind == "f":
            printed = np.array([float(f"{v:.6e}") if np.isfinite(v) else v for v in got])
            want = np.array([float(c) if c else np.nan for c in cells])
            np.testing.assert_allclose(printed, want, rtol=1e-12, equal_nan=True, err_msg=col)
        else:
            assert list(got) == cells, col
    assert int(np.sum(cv.table["is_reference"])) == 1


def test_sweep_columns_are_the_commands_table(tribofe_bin, tmp_path):
    # The arrays come from the library, not parsed back from text: the same columns, types
    # and values as the command's sweep.csv, to the digits the CSV prints (13 significant,
    # 7 for the edge widths: relative 5e-7), empty cells NaN. The wall-time column differs.
    kw = dict(thickness=[0.002, 0.004], length=0.05, converged=False)
    df = tribofe.sweep(**kw, progress=False).table
    cols = df if isinstance(df, dict) else {k: df[k].to_numpy() for k in df.columns}
    r = run_cli(tribofe_bin, "sweep", "--length", "0.05", "--thickness", "0.002,0.004",
                "--as-meshed", "--out", str(tmp_path / "sw"))
    assert r.returncode == 0, r.stderr
    with open(tmp_path / "sw" / "sweep.csv") as f:
        rows = list(csv.reader(f))
    assert list(cols) == rows[0]
    for j, name in enumerate(rows[0]):
        cells = [row[j] for row in rows[1:]]
        got = np.asarray(cols[name])
        assert len(got) == len(cells), name
        if name == "element":
            assert list(got) == cells
        elif name == "point_wall_s":
            assert np.all(got > 0)
        elif all(c.lstrip("-").isdigit() for c in cells):
            assert got.dtype.kind == "i", name
            assert list(got) == [int(c) for c in cells], name
        else:
            want = np.array([float(c) if c else np.nan for c in cells])
            assert got.dtype.kind == "f", name
            assert np.array_equal(np.isnan(got), np.isnan(want)), name
            ok = ~np.isnan(want)
            assert np.allclose(got[ok], want[ok], rtol=5e-7, atol=0), name


@pytest.mark.parametrize(
    "kwargs, flags",
    [
        ({"thickness": -1.0}, ["--thickness", "-1"]),
        ({"poisson": 0.5}, ["--poisson", "0.5"]),
        ({"element": "qua5"}, ["--element", "qua5"]),
    ],
)
def test_bad_input_raises_the_commands_message(tribofe_bin, tmp_path, kwargs, flags):
    r = run_cli(tribofe_bin, "check", *flags, "--out", str(tmp_path / "x"))
    assert r.returncode == 2
    with pytest.raises(tribofe.InputError) as e:
        tribofe.Scene(**kwargs)
    assert e.value.status == 2
    # The command's message, each flag named by its Python keyword (`--thickness` -> `thickness=`).
    keyworded = re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_") + "=", r.stderr.strip())
    # A parameter the command names bare (`invalid element:`) is the keyword too.
    keyworded = re.sub(r"^error: invalid ([a-z_]+):", r"error: invalid \1=:", keyworded)
    assert keyworded == f"error: {e.value}"


def test_errors_are_exceptions_not_crashes():
    with pytest.raises(tribofe.InputError, match="not a scene key"):
        tribofe.Scene(lenght=0.4)
    with pytest.raises(TypeError):
        tribofe.Scene(length="long")
    with pytest.raises(tribofe.InputError, match="law"):
        tribofe.slide(law="rubber", progress=False)
    with pytest.raises(tribofe.InputError):
        tribofe.precursors.model(1.5, 0.35)
    # A run that needs more events than its cap: the command's status 2, as an exception.
    with pytest.raises(tribofe.InputError, match="more than 3 events"):
        tribofe.slide(law="static-kinetic", cycles=1, max_events=3, progress=False)


def test_scene_toml_round_trip(tmp_path):
    s = tribofe.Scene(thickness=0.004, height=0.08)
    path = tmp_path / "scene.toml"
    path.write_text(s.to_toml())
    assert tribofe.Scene.from_toml(str(path)) == s
    assert s.replace(height=0.04) == tribofe.Scene(thickness=0.004)


def test_two_threads_equal_serial():
    scenes = [tribofe.Scene(thickness=0.002), tribofe.Scene(thickness=0.004, height=0.06)]
    serial = [tribofe.check(s).cases[2].p_over_pmean for s in scenes]
    results = [None, None]

    def work(i):
        results[i] = tribofe.check(scenes[i]).cases[2].p_over_pmean

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(serial, results):
        np.testing.assert_array_equal(a, b)


def test_interrupt_stops_a_long_run_within_a_second(tmp_path):
    # Slip weakening with D_c = 1 um on the paper's mesh runs for minutes (docs/friction.md),
    # much of it in relaxations between events that report no progress. SIGINT at 3 s and at
    # 9 s into the run must each end it with KeyboardInterrupt within a second, leaving no file.
    call = 'tribofe.slide(law="slip-weakening", r=0.9, g=0.35, dc=1e-6, cycles=1, progress=False)'
    for after in (3.0, 9.0):
        assert_interrupt_stops(tmp_path, call, after)


# The short slip-weakening scene of the Rust tests (L = 0.1 m, to X = 6e-6 m: 4 instabilities,
# a few seconds), its D_c and h left to the library as the command leaves them.
DYN_ARGS = ["--dynamics", "--law", "slip-weakening", "--length", "0.1", "--x-max", "6e-6"]


def test_dynamic_slide_equals_the_command_table_by_table(tribofe_bin, tmp_path):
    out = tmp_path / "dyn"
    r = run_cli(tribofe_bin, "slide", *DYN_ARGS, "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.dynamics.slide(tribofe.Scene(length=0.1), law="slip-weakening", x_max=6e-6)
    assert res.incomplete is None
    assert sum(1 for s in res.samples if s["instability"]) >= 1
    # Every table from the library's schema: every column of its CSV, integers as int64, the
    # numbers equal to the CSV's printed digits (10 significant, 13 in slide's own files).
    for name, table, digits in [("loading", res.loading, 13), ("events", res.events, 13),
                                ("advances", res.advances, 13), ("dyn_events", res.dyn_events, 10),
                                ("fronts_t", res.fronts, 10)]:
        key = "fronts" if name == "fronts_t" else name
        assert_table_is_the_csv(name, table, out / f"{name}.csv", digits, res.units[key])
        assert table.attrs["units"] == dict(res.units[key]), name
    assert_table_is_the_csv("summary", {k: np.array([v]) for k, v in res.summary.items()}, out / "summary.csv",
                            10, res.units["summary"])
    # dyn_events is the library's table, not its text: full precision and its units.
    x = np.asarray(res.dyn_events["X_m"])
    assert any(float(f"{v:.9e}") != v for v in x), "dyn_events looks parsed from 10-digit text"
    units = res.dyn_events.attrs["units"]
    assert list(units) == list(res.dyn_events.keys())
    assert units["X_m"] == "m" and units["duration_s"] == "s" and units["peak_slip_rate_m_per_s"] == "m/s"
    assert units["event"] == "-" and units["F_onset_over_mu_s_N"] == "1"
    # The library's choices, as the command made them: D_c for kappa = 0.509 and h = t/4.
    assert res.h_m == 5e-4
    assert abs(res.summary["kappa"] - 0.5093) < 5e-5
    assert any(n.startswith("dc= not given") for n in res.notes), res.notes
    # The samples: one row of slip rates per sample, one column per base node.
    s = res.samples[0]
    assert s["slip_rate_m_per_s"].shape == (len(s["slip_rate_t_s"]), len(res.x_over_L))
    np.testing.assert_array_equal(s["slip_rate_t_s"], s["t_s"][: len(s["slip_rate_t_s"])])


def test_dynamic_slide_passes_the_weakening_path():
    # The small scene (L = 0.1 m, h = 0.5 mm) to just past its first instability (4.8e-6 m).
    kw = dict(law="slip-weakening", h=5e-4, x_max=4.9e-6)
    stepped = tribofe.dynamics.slide(tribofe.Scene(length=0.1), weakening_steps=40, **kw)
    exact = tribofe.dynamics.slide(tribofe.Scene(length=0.1), exact_weakening=True, **kw)
    assert stepped.summary["weakening_steps"] == 40 and exact.summary["weakening_steps"] == 0
    # The exact onset's branch force is the command's fold, 0.77187062 mu_s N (printed to 8
    # digits: 1e-8); the stepped onset is off it by less than one step's strength change,
    # 1/N of mu_s N, either side (N = 20 lands below it, N = 80 and more above: stop 52's series).
    f_exact = float(exact.dyn_events["F_pre_over_mu_s_N"][0])
    assert abs(f_exact - 0.77187062) < 1e-8, f_exact
    f_stepped = float(stepped.dyn_events["F_onset_over_mu_s_N"][0])
    assert 0 < abs(f_exact - f_stepped) < 1 / 40, (f_exact, f_stepped)


def test_slide_refuses_rule_options_its_law_cannot_take():
    # As the command: the event rule and the paper rule's conventions belong to static-kinetic
    # (before stop 55 Python ran these silently with the rule ignored).
    for kw, named in [
        (dict(law="coulomb", rule="overdamped"), "rule="),
        (dict(law="slip-weakening", residual="pre-event"), "residual="),
        (dict(law="static-kinetic", rule="overdamped", backslip="forbidden"), "backslip="),
    ]:
        with pytest.raises(tribofe.InputError) as e:
            tribofe.slide(x_max=1e-7, **kw)
        assert named in str(e.value) and "static-kinetic" in str(e.value) and "--" not in str(e.value), kw


def test_dynamic_slide_is_silent_and_refuses_a_wrong_choice(capfd):
    res = tribofe.dynamics.slide(tribofe.Scene(length=0.1), law="coulomb", x_max=1e-6)
    assert res.law.startswith("coulomb")
    out, err = capfd.readouterr()
    assert out == "" and err == "", (out, err)
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.slide(tribofe.Scene(length=0.1), x_max=1e-6, cycle_end="cross")
    assert "cycle_end=" in str(e.value) and '"crossing"' in str(e.value) and '"whole-slip"' in str(e.value)
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.slide(tribofe.Scene(length=0.1), x_max=1e-6, heal="some")
    assert "heal=" in str(e.value)


# Each function with a command, the command's words and the flags the package names
# otherwise; every option both share is compared.
COMMANDS = {
    "solve": (["solve"], {}),
    "slide": (["slide"], {}),
    "dynamics.slide": (["slide"], {}),
    "sweep": (["sweep"], {}),
    "converge": (["converge"], {"case": "fn_ratio"}),
    "precursors.model": (["precursors", "model"], {}),
    "precursors.fe_fig4": (["precursors", "fe"], {}),
    "precursors.fe_fig5": (["precursors", "fe-map"], {}),
    "precursors.map": (["precursors", "map"], {}),
    "precursors.thin_layer": (["precursors", "thin-layer"], {}),
    "precursors.heights": (["precursors", "heights"], {}),
    "precursors.dc": (["precursors", "dc"], {}),
    "precursors.bonded": (["precursors", "bonded"], {}),
    "edges": (["edges"], {}),
    "stability": (["stability"], {}),
    "dynamics.rupture": (["rupture"], {}),
}
# Options the package deliberately defaults otherwise (none: every default is the library's).
DIFFERENT = set()


def help_defaults(text):
    """{flag: default} of every option whose help shows `[default: ...]`."""
    out = {}
    for block in re.split(r"\n(?=\s+(?:-\w, )?--)", text):
        m = re.match(r"\s+(?:-\w, )?--([a-z0-9-]+)", block)
        d = re.search(r"\[default: ([^\]]*)\]", block)
        if m and d:
            out[m.group(1)] = d.group(1)
    return out


def same(value, shown):
    if isinstance(value, (list, tuple)):
        return ",".join(str(v) for v in value) == shown
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value) == shown
    try:
        return float(shown) == float(value)
    except ValueError:
        return False


def test_defaults_equal_the_commands_help(tribofe_bin):
    import inspect

    lib = tribofe.defaults()
    compared = {}
    for name, (words, renamed) in COMMANDS.items():
        func = tribofe
        for part in name.split("."):
            func = getattr(func, part)
        params = inspect.signature(func).parameters
        shown = help_defaults(run_cli(tribofe_bin, *words, "--help").stdout)
        for flag, text in shown.items():
            key = renamed.get(flag, flag.replace("-", "_"))
            if key not in params or (name, key) in DIFFERENT:
                continue
            default = params[key].default
            if default is None:
                # None is the library's default: listed, or (a computed one) described in
                # words by the command too.
                if key in lib.get(name, {}):
                    default = lib[name][key]
                else:
                    assert " " in text, (name, key, text)
                    continue
            assert same(default, text), (name, key, default, text)
            compared.setdefault(name, set()).add(key)
    # The comparison reached the options it must (a help layout change would empty it).
    must = {
        "solve": {"lx", "ly", "nx", "ny", "element", "young", "poisson", "bottom", "right", "top", "left"},
        "slide": {"law", "rule", "residual", "backslip", "n_force", "max_events"},
        # law: `slide --dynamics` takes slide's --law default, and so does dynamics.slide.
        "dynamics.slide": {"law", "n_force", "max_events", "courant", "heal"},
        "sweep": {"rule", "cycles"},
        "converge": {"elements", "families", "fn_ratio"},
        "precursors.model": {"r", "g"},
        "precursors.fe_fig4": {"r", "g", "cycles"},
        "precursors.fe_fig5": {"resolution", "rules", "max_events"},
        "precursors.map": {"resolution"},
        "precursors.thin_layer": {"r", "g"},
        "precursors.heights": {"r", "g"},
        "precursors.dc": {"r", "g", "max_events"},
        "precursors.bonded": {"r", "g", "events"},
        "edges": {"mu", "refine", "mu_s", "mu_d", "rule", "t_over_l", "open_refine", "end_grading", "h_over_l"},
        "stability": {"corner_max", "n_ref"},
        "dynamics.rupture": {"s", "h", "dc", "t_end", "length", "height", "mu_s", "mu_d", "sigma0", "young",
                             "poisson", "density", "courant", "damping", "contact", "normal_lag",
                             "patch_taper", "max_steps"},
    }
    for name, keys in must.items():
        assert keys <= compared.get(name, set()), (name, keys - compared.get(name, set()))
    # No signature restates a number the library owns: the keywords listed are None.
    for name, keys in lib.items():
        func = tribofe
        for part in name.split("."):
            func = getattr(func, part)
        params = inspect.signature(func).parameters
        for key in keys:
            assert params[key].default is None, (name, key, params[key].default)


def test_slide_takes_every_choice_of_the_command(tribofe_bin, tmp_path):
    # The paper rule's conventions, the operator, the states kept and the cycle end, as the
    # command takes them: every column of loading.csv and events.csv equal.
    out = tmp_path / "slide"
    args = ["--law", "static-kinetic", "--rule", "paper", "--residual", "pre-event", "--backslip", "forbidden",
            "--cycles", "1", "--cycle-end", "crossing", "--operator", "banded", "--states", "none"]
    r = run_cli(tribofe_bin, "slide", *args, "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = tribofe.slide(law="static-kinetic", rule="paper", residual="pre-event", backslip="forbidden", cycles=1,
                        cycle_end="crossing", operator="banded", states="none")
    assert_table_is_the_csv("loading", res.loading, out / "loading.csv", 13, res.units["loading"])
    assert_table_is_the_csv("events", res.events, out / "events.csv", 13, res.units["events"])
    # states="none": the last state only.
    assert res.states["p_force_N_per_m"].shape[0] == 1
    # The conventions act: the default convention gives other events.
    default = tribofe.slide(law="static-kinetic", cycles=1, cycle_end="crossing")
    assert len(default.events) != len(res.events) or not np.allclose(
        np.asarray(default.events["F_over_mu_s_N"]), np.asarray(res.events["F_over_mu_s_N"]), rtol=1e-9)


@pytest.mark.parametrize(
    "kwargs, keyword, accepted",
    [
        ({"operator": "sparse"}, "operator=", ['"dense"', '"banded"']),
        ({"states": "some"}, "states=", ['"all"', '"none"']),
        ({"cycle_end": "cross"}, "cycle_end=", ['"whole-slip"', '"crossing"']),
        ({"law": "static-kinetic", "rule": "damped"}, "rule=", ['"paper"', '"overdamped"']),
        ({"law": "static-kinetic", "residual": "after"}, "residual=", ['"relaxed"', '"pre-event"']),
        ({"law": "static-kinetic", "backslip": "yes"}, "backslip=", ['"allowed"', '"forbidden"']),
    ],
)
def test_slide_refuses_a_wrong_choice_with_the_accepted_values(kwargs, keyword, accepted):
    with pytest.raises(tribofe.InputError) as e:
        tribofe.slide(cycles=1, **kwargs)
    msg = str(e.value)
    assert keyword in msg and all(a in msg for a in accepted), msg


def test_options_that_cannot_act_are_refused_by_keyword(tribofe_bin, tmp_path):
    small = tribofe.Scene(length=0.1)
    # weakening_steps has no meaning under a drive velocity (updated every explicit step).
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.slide(small, law="slip-weakening", drive_velocity=1e-5, x_max=1e-6, weakening_steps=40)
    assert "weakening_steps=" in str(e.value) and "drive_velocity=" in str(e.value), str(e.value)
    r = run_cli(tribofe_bin, "slide", "--dynamics", "--law", "slip-weakening", "--length", "0.1", "--drive-velocity",
                "1e-5", "--x-max", "1e-6", "--weakening-steps", "40", "--out", str(tmp_path / "x"))
    assert r.returncode == 2 and "--weakening-steps" in r.stderr, r.stderr
    # exact_weakening is the other path: refused beside a step count, and under a drive velocity.
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.slide(small, law="slip-weakening", x_max=1e-6, exact_weakening=True, weakening_steps=40)
    assert "exact_weakening=" in str(e.value) and "weakening_steps=" in str(e.value), str(e.value)
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.slide(small, law="slip-weakening", drive_velocity=1e-5, x_max=1e-6, exact_weakening=True)
    assert "exact_weakening=" in str(e.value) and "drive_velocity=" in str(e.value), str(e.value)
    # event_end: the held mode's events only; a wrong name lists the accepted ones.
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.slide(small, law="slip-weakening", drive_velocity=1e-5, x_max=1e-6, event_end="slip")
    assert "event_end=" in str(e.value) and "drive_velocity=" in str(e.value), str(e.value)
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.slide(small, law="slip-weakening", x_max=1e-6, event_end="rest")
    assert "event_end=" in str(e.value) and '"energy", "slip"' in str(e.value), str(e.value)
    # The sweep's frictional settings without its frictional run.
    for kw in ({"rule": "overdamped"}, {"cycles": 3}):
        with pytest.raises(tribofe.InputError) as e:
            tribofe.sweep(thickness=0.002, converged=False, **kw)
        key = next(iter(kw))
        assert f"{key}=" in str(e.value) and "friction=" in str(e.value), str(e.value)
        r = run_cli(tribofe_bin, "sweep", "--thickness", "0.002", f"--{key}", str(kw[key]), "--out", str(tmp_path / "y"))
        assert r.returncode == 2 and f"--{key}" in r.stderr, r.stderr
    # The paper model's parameters by keyword, not the scene file's `r = 1.5`.
    with pytest.raises(tribofe.InputError) as e:
        tribofe.precursors.model(r=1.5)
    assert str(e.value).startswith("invalid r=1.5:"), str(e.value)
    assert " = 1.5" not in str(e.value)


def test_dynamics_slide_takes_rate_and_state():
    # Rate strengthening at V = 2e-5 m/s on a block driven at its top: F/N settles at the
    # steady state mu_ss(V) = f0 + (a - b) ln(V / v0) (tests/it/rate_state.rs, the same run).
    res = tribofe.dynamics.slide(law="rate-state", a=0.01, b=0.005, l_rs=4e-7, f0=0.6,
                                 scene=tribofe.Scene(length=0.1, height=0.002, h=1e-3),
                                 drive_velocity=2e-5, x_max=4e-5)
    want = 0.6 + 0.005 * np.log(20.0)
    assert abs(float(np.asarray(res.loading["F_over_N"])[-1]) - want) < 1e-9
    # The held mode's quasi-static phase refuses it, naming the keyword that runs it.
    with pytest.raises(tribofe.InputError, match="drive_velocity="):
        tribofe.dynamics.slide(law="rate-state", a=0.01, b=0.005, l_rs=4e-7, f0=0.6)
    with pytest.raises(tribofe.InputError, match="l_rs="):
        tribofe.dynamics.slide(law="rate-state", a=0.01, b=0.005, f0=0.6, drive_velocity=2e-5, x_max=1e-5)
