"""The package as a scripting front end (issue 44): silent unless asked, the command's
defaults from the library, integer codes as integers, errors naming the keyword, Ctrl-C in
a dynamic slide, the rupture's step cap."""

import csv
import inspect
import re
import warnings

import numpy as np
import pytest

import tribofe
from conftest import assert_interrupt_stops, run_cli


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [r[k] for r in rows] for k in rows[0]}


def keyworded(stderr: str) -> str:
    """The command's message as the package words it: `--x-y` -> `x_y=`."""
    return re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_") + "=", stderr.strip())


# Every public call that can report progress, with cheap arguments (each well under a second
# or two on the paper's machine).
SMALL = tribofe.Scene(length=0.1)
QUIET_CALLS = {
    "slide": lambda: tribofe.slide(law="static-kinetic", cycles=1),
    "sweep": lambda: tribofe.sweep(thickness=[0.002, 0.004], length=0.05, converged=False),
    "converge": lambda: tribofe.converge(n_thick=[1, 2]),
    "precursors.fe_fig4": lambda: tribofe.precursors.fe_fig4(SMALL, cycles=1),
    "precursors.fe_fig5": lambda: tribofe.precursors.fe_fig5(resolution=2),
    "precursors.thin_layer": lambda: tribofe.precursors.thin_layer([0.02]),
    "precursors.heights": lambda: tribofe.precursors.heights([0.1], SMALL),
    "precursors.dc": lambda: tribofe.precursors.dc([1e-7], SMALL),
    "edges": lambda: tribofe.edges(SMALL, mu=[0.3], refine=[2], t_over_l=[0.02], open_refine=[2], h_over_l=[0.1]),
    "dynamics.slide": lambda: tribofe.dynamics.slide(SMALL, law="coulomb", x_max=1e-6),
    "dynamics.rupture": lambda: tribofe.dynamics.rupture(t_end=0.005),
    "stability": lambda: tribofe.stability(SMALL, study=["corners"], corner_max=4),
    "precursors.bonded": lambda: tribofe.precursors.bonded(SMALL, sweep=True),
}


def public(name):
    obj = tribofe
    for part in name.split("."):
        obj = getattr(obj, part)
    return obj


@pytest.mark.parametrize("name", sorted(QUIET_CALLS))
def test_default_calls_print_nothing(name, capfd):
    # progress defaults to False everywhere: no tqdm bar, no text, on either stream.
    assert inspect.signature(public(name)).parameters["progress"].default is False
    capfd.readouterr()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning would be printed too
        res = QUIET_CALLS[name]()
    assert res is not None
    out, err = capfd.readouterr()
    assert out == "" and err == "", (name, out[-500:], err[-500:])


def test_progress_when_asked(capfd):
    seen = []
    tribofe.sweep(thickness=[0.002, 0.004], length=0.05, converged=False, progress=seen.append)
    # The points run in parallel: their fractions may arrive out of order, all of them do.
    assert seen and max(seen) == pytest.approx(1.0) and min(seen) >= 0.0
    assert capfd.readouterr() == ("", "")


def test_state_code_is_integer(tribofe_bin, tmp_path):
    # states.csv writes each node's state as a word; the package's codes are integers
    # 0 stick, 1 slip, 2 open, node for node the same.
    out = tmp_path / "sl"
    assert run_cli(tribofe_bin, "slide", "--law", "static-kinetic", "--cycles", "1", "--out", str(out)).returncode == 0
    res = tribofe.slide(law="static-kinetic", cycles=1)
    code = res.states["state_code"]
    assert code.dtype == np.int64
    words = read_csv(out / "states.csv")["state"]
    want = np.array([{"stick": 0, "slip": 1, "open": 2}[w] for w in words]).reshape(code.shape)
    np.testing.assert_array_equal(code, want)
    assert {0, 1} <= set(np.unique(code))


def test_rupture_takes_the_commands_s(tribofe_bin, tmp_path):
    out = tmp_path / "r"
    assert run_cli(tribofe_bin, "rupture", "--s", "1.5", "--t-end", "0.02", "--out", str(out)).returncode == 0
    res = tribofe.dynamics.rupture(s=1.5, t_end=0.02)
    x, t = np.asarray(res.x_m), np.asarray(res.t_arrival_s)
    mask = (x >= -1e-12) & np.isfinite(t)
    assert mask.sum() > 10
    np.testing.assert_allclose(t[mask], [float(v) for v in read_csv(out / "arrival.csv")["t_arrival_s"]], rtol=1e-11)
    # A different S is a different run: the keyword reaches the library.
    other = tribofe.dynamics.rupture(t_end=0.02)
    assert not np.array_equal(np.asarray(other.t_arrival_s)[mask], t[mask])
    # The old name still works, warned, and equals s=.
    with pytest.warns(DeprecationWarning, match="s="):
        old = tribofe.dynamics.rupture(s_ratio=1.5, t_end=0.02)
    np.testing.assert_array_equal(np.asarray(old.t_arrival_s), np.asarray(res.t_arrival_s))
    with pytest.raises(tribofe.InputError, match="s_ratio="):
        tribofe.dynamics.rupture(s=1.5, s_ratio=1.5)


def test_rupture_max_steps_is_the_commands(tribofe_bin, tmp_path):
    # The default run's own step count fits; one step fewer is refused before any work with
    # the command's message, the flags named as keywords.
    n = tribofe.dynamics.rupture().steps
    assert n > 100
    assert tribofe.dynamics.rupture(max_steps=n).steps == n
    r = run_cli(tribofe_bin, "rupture", "--max-steps", str(n - 1), "--out", str(tmp_path / "x"))
    assert r.returncode == 2 and not (tmp_path / "x").exists()
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.rupture(max_steps=n - 1)
    assert keyworded(r.stderr) == f"error: {e.value}"
    assert "max_steps=" in str(e.value) and "t_end=" in str(e.value) and "--" not in str(e.value)


def test_rupture_takes_a_scene_file(tribofe_bin, tmp_path):
    # TPV205-2D at 200 m from Python equals the command's station file, and a keyword given
    # overrides the file's key and is named as a keyword when refused.
    import pathlib

    scene = pathlib.Path(__file__).resolve().parents[2] / "validation/dynamics/tpv205_2d/tpv205_2d.toml"
    out = tmp_path / "t"
    assert run_cli(tribofe_bin, "rupture", "--scene", str(scene), "--h", "200", "--out", str(out)).returncode == 0
    res = tribofe.dynamics.rupture(scene=scene, h=200)
    st = res.stations[4500.0]
    cli = read_csv(out / "station_x4500.csv")
    # The station's table is the library's, the one the file is printed from: its columns in
    # order, with units.
    assert list(st.keys()) == list(cli) and dict(res.station_units)["shear_stress_Pa"] == "Pa"
    for key in cli:
        np.testing.assert_allclose(st[key], [float(v) for v in cli[key]], rtol=1e-11, atol=1e-300)
    assert "station_x4500" in res.to_pandas()
    # The rupture time at 4.5 km (a node midway: the field's 1.5 s, PyLith's 1.500).
    x, t = np.asarray(res.x_m), np.asarray(res.rupture_time_s)
    assert abs(np.interp(4500.0, x, t) - 1.55) < 0.01
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.rupture(scene=scene, h=200, dc=0.12)
    assert "h=" in str(e.value) and "dc=" in str(e.value) and "--" not in str(e.value)
    # A key of the file named as such when the keyword is not given.
    small_dc = tmp_path / "small_dc.toml"
    small_dc.write_text(scene.read_text().replace("dc = 0.40 ", "dc = 0.12 "))
    with pytest.raises(tribofe.InputError) as e:
        tribofe.dynamics.rupture(scene=small_dc, h=200)
    assert "[law] dc" in str(e.value) and "h=" in str(e.value)


def test_fe_fig4_defaults_are_the_commands(tribofe_bin, tmp_path):
    # `tribofe precursors fe` with no flag and precursors.fe_fig4() with no keyword are the
    # same runs (2 cycles): every number of summary.csv, to its printed digits.
    out = tmp_path / "pfe"
    assert run_cli(tribofe_bin, "precursors", "fe", "--out", str(out)).returncode == 0
    cli = {row["source"]: row for row in csv.DictReader(open(out / "summary.csv"))}
    runs = tribofe.precursors.fe_fig4().runs
    for rule in ("paper", "overdamped"):
        c, want = runs[rule].comparison, cli[rule]
        assert c["n_fe"] == int(want["precursors"])
        assert c["n_fe_long"] == int(want["precursors_longer_5t"])
        assert c["n_fe_advancing"] == int(want["precursors_advancing_5t"])
        for key, col in (("F_1_fe", "F1_over_mu_s_N"), ("x_1_fe", "x1_over_L"), ("F_max_fe", "Fmax_over_mu_s_N")):
            assert abs(c[key] - float(want[col])) <= 1e-12 * abs(float(want[col])), (rule, key)
    # The case: the overdamped F_max of the command, 0.9430 (1 cycle gave 0.9214).
    assert abs(runs["overdamped"].comparison["F_max_fe"] - 0.9430) < 5e-5


# Each call refused with the keyword it was given; the message never names a flag.
BAD_CALLS = [
    ("slide n_force", lambda: tribofe.slide(n_force=-1.0), "n_force="),
    ("slide dc", lambda: tribofe.slide(law="slip-weakening", dc=1e-20), "dc="),
    ("slide x_max", lambda: tribofe.slide(x_max=1.0), "x_max="),
    ("slide max_events", lambda: tribofe.slide(max_events=0), "max_events="),
    ("dynamics.slide x_max", lambda: tribofe.dynamics.slide(SMALL, x_max=-1.0), "x_max="),
    ("dynamics.slide damping", lambda: tribofe.dynamics.slide(SMALL, x_max=1e-6, damping=1e200), "damping="),
    ("dynamics.rupture courant", lambda: tribofe.dynamics.rupture(courant=1e-5), "courant="),
    ("dynamics.rupture dc", lambda: tribofe.dynamics.rupture(dc=-1.0), "dc="),
    ("dynamics.rupture s", lambda: tribofe.dynamics.rupture(s=-1.0), "s="),
    ("precursors.fe_fig4 cycles", lambda: tribofe.precursors.fe_fig4(cycles=0), "cycles="),
    ("scene thickness", lambda: tribofe.Scene(thickness=-1.0), "thickness="),
    ("scene plate_young", lambda: tribofe.Scene(plate="elastic", plate_young=-1.0), "plate_young="),
]


@pytest.mark.parametrize("call, keyword", [(c, k) for _, c, k in BAD_CALLS], ids=[n for n, _, _ in BAD_CALLS])
def test_errors_name_the_keyword(call, keyword):
    with pytest.raises(tribofe.InputError) as e:
        call()
    msg = str(e.value)
    assert keyword in msg, msg
    assert not re.search(r"(?<![\w-])--[a-z]", msg), msg
    assert e.value.status == 2


@pytest.mark.parametrize(
    "call",
    [
        lambda: tribofe.slide(law="rub\x1b[31mber"),
        lambda: tribofe.Scene(element="qua\x074"),
        lambda: tribofe.dynamics.rupture(contact="\x1b]0;title\x07glue"),
        lambda: tribofe.dynamics.slide(SMALL, x_max=1e-6, cycle_end="cross\x1b[2J"),
    ],
    ids=["law", "element", "contact", "cycle_end"],
)
def test_errors_carry_no_control_bytes(call):
    with pytest.raises(tribofe.InputError) as e:
        call()
    msg = str(e.value)
    assert not any(ord(c) < 32 or ord(c) == 127 for c in msg), repr(msg)


def test_interrupt_stops_a_dynamic_slide_within_a_second(tmp_path):
    # The paper's dynamic first cycle runs for tens of seconds; SIGINT 3 s into it must end
    # it with KeyboardInterrupt within a second and leave no file.
    assert_interrupt_stops(tmp_path, "tribofe.dynamics.slide(law='slip-weakening')", 3.0)


# Every call's result class, with cheap arguments.
RESULTS = {
    "slide": (lambda: tribofe.slide(SMALL, law="static-kinetic", cycles=1), tribofe.SlideResult, {"loading", "events"}),
    "sweep": (QUIET_CALLS["sweep"], tribofe.SweepResult, None),
    "converge": (QUIET_CALLS["converge"], tribofe.ConvergeResult, None),
    "precursors.model": (lambda: tribofe.precursors.model(), tribofe.ModelResult, None),
    "precursors.fe_fig5": (QUIET_CALLS["precursors.fe_fig5"], tribofe.FeFig5Result, None),
    "precursors.map": (lambda: tribofe.precursors.map(resolution=4), tribofe.NMapResult, None),
    "precursors.thin_layer": (QUIET_CALLS["precursors.thin_layer"], tribofe.SeriesResult, None),
    "precursors.bonded": (lambda: tribofe.precursors.bonded(), tribofe.BondedResult, None),
    "solve": (lambda: tribofe.solve(nx=4, ny=2), tribofe.SolveResult, {"reactions"}),
    "edges": (QUIET_CALLS["edges"], tribofe.EdgesResult, {"preslip", "opening"}),
    "stability": (QUIET_CALLS["stability"], tribofe.StabilityResult, {"corners"}),
    "dynamics.slide": (QUIET_CALLS["dynamics.slide"], tribofe.DynamicSlideResult, {"loading", "events", "dyn_events", "fronts", "summary"}),
    "dynamics.rupture": (QUIET_CALLS["dynamics.rupture"], tribofe.RuptureResult, {"nodes", "summary", "energy"}),
}


@pytest.mark.parametrize("name", sorted(RESULTS))
def test_every_call_returns_its_result_class_with_to_pandas(name):
    import pandas as pd

    call, cls, frames = RESULTS[name]
    res = call()
    assert type(res) is cls
    got = res.to_pandas()
    if frames is None:
        assert isinstance(got, pd.DataFrame) and len(got) > 0
    else:
        assert set(got) == frames and all(isinstance(df, pd.DataFrame) for df in got.values())


def test_to_pandas_without_pandas_names_pandas(monkeypatch):
    import sys

    res = tribofe.precursors.model()
    monkeypatch.setitem(sys.modules, "pandas", None)  # `import pandas` now raises ImportError
    with pytest.raises(ImportError, match="pandas"):
        res.to_pandas()
    # Without pandas the call's tables are dicts of numpy arrays, counts int64.
    bare = tribofe.precursors.model()
    assert isinstance(bare.events, dict) and bare.events["event"].dtype == np.int64


def test_old_dict_access_still_works_warned():
    # Scripts written against the dicts, lists and tuples the calls returned keep running,
    # each old form warned with its new spelling.
    m = tribofe.precursors.model()
    with pytest.warns(DeprecationWarning, match=r"\.n\b"):
        assert m["n"] == m.n == 10
    with pytest.warns(DeprecationWarning):
        assert list(m["events"]["event"]) == list(m.events["event"])
    r = tribofe.dynamics.rupture(t_end=0.005)
    with pytest.warns(DeprecationWarning, match=r"\.x_m"):
        np.testing.assert_array_equal(r["x_m"], r.x_m)
    with pytest.warns(DeprecationWarning):
        assert r["energy"]["kinetic_j_per_m"] == r.energy["kinetic_j_per_m"]
    with pytest.raises(KeyError):
        r["no_such_key"]
    sw = QUIET_CALLS["sweep"]()
    with pytest.warns(DeprecationWarning, match=r"\.table\["):
        np.testing.assert_array_equal(sw["point"], sw.table["point"])
    with pytest.warns(DeprecationWarning, match=r"\.table\.groupby"):
        assert len(sw.groupby("point")) == 2  # the old DataFrame's methods
    cv = QUIET_CALLS["converge"]()
    with pytest.warns(DeprecationWarning, match=r"\.summary"):
        table, summary = cv
    assert summary == cv.summary and table is cv.table
    f5 = QUIET_CALLS["precursors.fe_fig5"]()
    with pytest.warns(DeprecationWarning):
        assert list(f5["paper_status"]) == list(f5.table["paper_status"])


def test_fe_fig4_old_list_access_still_works_warned():
    res = tribofe.precursors.fe_fig4(SMALL, cycles=1)
    with pytest.warns(DeprecationWarning) as seen:
        runs = {run["rule"]: run for run in res}
    assert any(".runs" in str(w.message) for w in seen) and any(".rule" in str(w.message) for w in seen)
    assert set(runs) == {"paper", "overdamped"} and len(res) == 2
    with pytest.warns(DeprecationWarning):
        first = res[0]
    assert first is res.runs["paper"]
    with pytest.warns(DeprecationWarning, match=r"\.comparison"):
        c = runs["paper"]["comparison"]
    assert c is res.runs["paper"].comparison


# Calls with many progress ticks (a slide reports every event; a rupture every few steps).
NOISY_CALLS = {
    "slide": lambda p: tribofe.slide(law="static-kinetic", r=0.9, g=0.35, cycles=1, progress=p),
    "sweep": lambda p: tribofe.sweep(thickness=[0.002, 0.003, 0.004], length=0.05, converged=False, progress=p),
    "dynamics.slide": lambda p: tribofe.dynamics.slide(SMALL, law="coulomb", x_max=1e-6, progress=p),
    "dynamics.rupture": lambda p: tribofe.dynamics.rupture(t_end=0.005, progress=p),
}


@pytest.mark.parametrize("name", sorted(NOISY_CALLS))
def test_progress_without_a_terminal_writes_a_few_lines(name, capfd):
    # progress=True with stderr redirected (not a terminal): a line per tenth done at most,
    # however many ticks the run reports; unset: nothing at all.
    ticks = []
    NOISY_CALLS[name](ticks.append)
    # A slide reports every event: more ticks than the lines allowed.
    assert len(ticks) > (15 if name == "slide" else 0), len(ticks)
    capfd.readouterr()
    NOISY_CALLS[name](True)
    out, err = capfd.readouterr()
    lines = err.replace("\r", "\n").splitlines()
    assert out == "" and 1 <= len(lines) <= 15, (name, len(lines), err[-300:])
    NOISY_CALLS[name](False)
    assert capfd.readouterr() == ("", "")


def test_progress_lines_are_bounded_however_many_ticks(capfd):
    # Ten thousand ticks without a terminal: one line per tenth, the first at 0 %.
    update, close = tribofe._progress(True, "run")
    for k in range(10001):
        update(k / 10000)
    close()
    out, err = capfd.readouterr()
    assert out == "" and err.splitlines() == [f"run: {10 * k} %" for k in range(11)]


def test_progress_on_a_terminal_draws_a_tqdm_bar(tmp_path):
    # Under a pseudo-terminal, progress=True is tqdm's bar (a percentage and "|" frame).
    pytest.importorskip("tqdm")
    import fcntl
    import os
    import pty
    import struct
    import subprocess
    import sys
    import termios

    code = "import tribofe; tribofe.slide(law='static-kinetic', r=0.9, g=0.35, cycles=1, progress=True)"
    master, slave = pty.openpty()
    # An 80-column terminal (a new pty has 0 columns, where tqdm draws nothing).
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.DEVNULL, stderr=slave, close_fds=True)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 4096)
        except OSError:
            break
        if not data:
            break
        chunks.append(data)
    assert proc.wait(timeout=120) == 0
    os.close(master)
    text = b"".join(chunks).decode(errors="replace")
    assert "%|" in text and "slide" in text, text[-300:]
