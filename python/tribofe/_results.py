"""The result classes: one per call, each with ``.to_pandas()``; tables follow the package's
one rule (the library's tables, DataFrames when pandas is installed, dicts of numpy arrays
otherwise, counts and codes int64, units in ``units`` and ``df.attrs["units"]``)."""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np


def _table(columns: Dict[str, Any], units: Optional[List[tuple]] = None):
    """A pandas DataFrame when pandas is installed, else the dict of arrays itself. A table
    the library defines with its units carries them as ``df.attrs["units"]`` (column -> unit:
    SI, ``1`` dimensionless, ``-`` a count, code or label)."""
    try:
        import pandas as pd
    except ImportError:
        return columns
    df = pd.DataFrame(columns)
    if units is not None:
        df.attrs["units"] = dict(units)
    return df


def _pandas():
    try:
        import pandas as pd
    except ImportError as e:
        raise ImportError("tribofe: .to_pandas() needs pandas (pip install pandas)") from e
    return pd


def _df(table, units: Optional[List[tuple]] = None):
    """A table as a DataFrame (it already is one when pandas was there at the call)."""
    pd = _pandas()
    if isinstance(table, pd.DataFrame):
        return table
    df = pd.DataFrame(table)
    if units is not None:
        df.attrs["units"] = dict(units)
    return df


def _row(values: Dict[str, Any]):
    """A one-row DataFrame of scalars."""
    return _pandas().DataFrame({k: [v] for k, v in values.items()})


def _deprecated(what: str, instead: str) -> None:
    # stacklevel 3: the user's line, above __getitem__ and this helper.
    warnings.warn(f"tribofe: {what} is deprecated, use {instead}", DeprecationWarning, stacklevel=3)


class _Result:
    """What every result shares: ``to_pandas()``, and the old dict-style access
    (``result["key"]`` is ``result.key``) kept working with a DeprecationWarning."""

    def __getitem__(self, key):
        if isinstance(key, str) and not key.startswith("_") and hasattr(self, key):
            _deprecated(f'{type(self).__name__}["{key}"]', f".{key}")
            return getattr(self, key)
        raise KeyError(key)

    def to_pandas(self):  # pragma: no cover - every class overrides it
        raise NotImplementedError


class _OneTable(_Result):
    """A result whose rows are one table (``table``). Before, the call returned the table
    itself: its column access (``result["col"]``), ``len`` and DataFrame methods still work
    on the result, with a DeprecationWarning."""

    table: Any
    units: Optional[List[Tuple[str, str]]]

    def __getitem__(self, key):
        if isinstance(key, str) and key in self.table:
            _deprecated(f'{type(self).__name__}["{key}"]', f'.table["{key}"]')
            return self.table[key]
        return super().__getitem__(key)

    def __getattr__(self, name):
        # Only reached for names the result lacks: the old DataFrame's methods (df.query...).
        if name.startswith("_") or name in ("table", "units"):
            raise AttributeError(name)
        table = self.__dict__.get("table")
        if table is not None and not isinstance(table, dict) and hasattr(table, name):
            _deprecated(f"{type(self).__name__}.{name}", f".table.{name}")
            return getattr(table, name)
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def __len__(self) -> int:
        first = next(iter(self.table), None)
        return 0 if first is None else len(self.table[first])

    def to_pandas(self):
        """The table as a DataFrame (its units in ``attrs["units"]``)."""
        return _df(self.table, self.units)


@dataclass(frozen=True, eq=False)
class SweepResult(_OneTable):
    """``tribofe sweep``: ``table``, the rows of sweep.csv (one per point and load case), the
    library's table with every column, ``units`` (column, unit) pairs."""

    table: Any
    units: List[Tuple[str, str]]

    def __repr__(self) -> str:
        return f"SweepResult({len(self)} rows x {len(self.units)} columns)"


@dataclass(frozen=True, eq=False)
class ConvergeResult(_OneTable):
    """``tribofe converge``: ``table``, the rows of convergence.csv (the library's table at
    full precision), ``units``, and ``summary``, the printed reading (orders, edge widths, the
    cheapest run reaching ``target``). ``table, summary = result`` still works (deprecated)."""

    table: Any
    units: List[Tuple[str, str]]
    summary: str

    def __iter__(self):
        _deprecated("unpacking converge()'s (table, summary)", ".table and .summary")
        return iter((self.table, self.summary))

    def __getitem__(self, key):
        if isinstance(key, int):
            _deprecated(f"converge()[{key}]", ".table and .summary")
            return (self.table, self.summary)[key]
        return super().__getitem__(key)

    def __repr__(self) -> str:
        return f"ConvergeResult({len(self)} runs)"


@dataclass(frozen=True, eq=False)
class FeFig5Result(_OneTable):
    """``tribofe precursors fe-map``: ``table``, fig5_fe.csv's rows and columns (the library's
    table): one row per (r, g) cell with the model's n and F_max, then per rule
    (``paper_...``, ``overdamped_...``) the FE run's status (done, capped, refused, empty when
    not run), counts (int64 when every row has one, else float64 with NaN where a run has
    none), peak, violation and seconds; ``units`` (column, unit). Until stop 57 the table had
    a row per cell and rule under other names."""

    table: Any
    units: Optional[List[Tuple[str, str]]] = None

    def __repr__(self) -> str:
        return f"FeFig5Result({len(self)} cells)"


@dataclass(frozen=True, eq=False)
class SolveResult(_Result):
    """``tribofe solve``: ``reactions_N_per_m`` per side (``"bottom"``, ``"right"``,
    ``"top"``, ``"left"``: (Fx, Fy), N per metre of width; a corner node counts for both its
    sides), ``total_reaction_N_per_m`` (each constrained DOF once) and ``applied_N_per_m``
    (the traction force; the two balance), ``unknowns``, and the fields: ``nodes_m`` (n x 2),
    ``displacement_m`` (n x 2, m), ``stress_Pa`` (n x 4: sigma_xx, sigma_yy, sigma_xy,
    sigma_zz; nodal values extrapolated from the integration points and averaged)."""

    reactions_N_per_m: Dict[str, Tuple[float, float]]
    total_reaction_N_per_m: Tuple[float, float]
    applied_N_per_m: Tuple[float, float]
    unknowns: int
    nodes_m: np.ndarray = field(repr=False)
    displacement_m: np.ndarray = field(repr=False)
    stress_Pa: np.ndarray = field(repr=False)
    core_s: float = field(default=0.0, compare=False)

    @property
    def reactions(self):
        """The reactions as a table: ``side``, ``Fx_N_per_m``, ``Fy_N_per_m``."""
        sides = list(self.reactions_N_per_m)
        f = np.asarray([self.reactions_N_per_m[k] for k in sides], dtype=float).reshape(-1, 2)
        return _table({"side": sides, "Fx_N_per_m": f[:, 0], "Fy_N_per_m": f[:, 1]})

    def to_pandas(self):
        """``{"reactions": df}``."""
        return {"reactions": _df(self.reactions)}

    def __repr__(self) -> str:
        return f"SolveResult({self.unknowns} unknowns, {len(self.nodes_m)} nodes, reactions {self.reactions_N_per_m})"


@dataclass(frozen=True, eq=False)
class EdgesResult(_Result):
    """``tribofe edges``: ``preslip``, preslip.csv's table (per coulomb mu and t/h the
    interface nodes and the pre-slip extents from each end, units of t), and ``opening``,
    opening.csv's (per t/L, t/h, H/L: g, F_1 of the model and the FE, the force and open
    length when the trailing end first opens, whether it opens before the first precursor,
    the open nodes; forces in units of mu_s N, lengths in units of t; an empty cell NaN);
    the library's tables, ``units[name]`` their (column, unit) pairs."""

    preslip: Any
    opening: Any
    units: Dict[str, List[Tuple[str, str]]]

    def to_pandas(self):
        """``{"preslip": df, "opening": df}``, each with its units in ``attrs["units"]``."""
        return {k: _df(getattr(self, k), self.units[k]) for k in ("preslip", "opening")}

    def __repr__(self) -> str:
        return f"EdgesResult({len(self.preslip['mu'])} pre-slip rows, {len(self.opening['g'])} opening runs)"


@dataclass(frozen=True, eq=False)
class StabilityResult(_Result):
    """``tribofe stability``: ``tables[study]``, each study's table as its CSV (``plate``,
    ``nu``, ``shape``, ``thin``, ``corners``: the library's tables, errors and stresses in
    units of N/L, widths in units of t, times in s; an empty cell NaN), ``units[study]`` their
    (column, unit) pairs, ``summary`` the printed reading (summary.txt), and ``corners`` (when
    that study ran): the end-value increments' ``factor`` per halving, the exponent
    ``lambda_measured`` = 1 - log2(factor), Williams' clamped-free corner exponent
    ``lambda_williams`` and its ``factor_williams`` at Poisson's ratio ``nu``."""

    tables: Dict[str, Any]
    units: Dict[str, List[Tuple[str, str]]]
    summary: str
    corners: Optional[Dict[str, float]] = None

    def to_pandas(self):
        """``{study: df}``, each with its units in ``attrs["units"]``."""
        return {k: _df(t, self.units[k]) for k, t in self.tables.items()}

    def __repr__(self) -> str:
        return f"StabilityResult({', '.join(self.tables)})"


@dataclass(frozen=True, eq=False)
class NMapResult(_OneTable):
    """``tribofe precursors map``: ``table``, n_map.csv's rows (the library's table): per cell
    centre ``r``, ``g`` (dimensionless) and the model's number of precursors ``n`` (int64);
    ``units`` (column, unit)."""

    table: Any
    units: List[Tuple[str, str]]

    def __repr__(self) -> str:
        n = np.asarray(self.table["n"])
        return f"NMapResult({len(self)} cells, n from {n.min() if len(n) else 0} to {n.max() if len(n) else 0})"


@dataclass(frozen=True, eq=False)
class SeriesResult(_OneTable):
    """``tribofe precursors thin-layer``, ``heights`` and ``dc``: ``table``, the rows of
    thin_layer.csv, heights.csv or dc.csv (the library's one series table): per value of
    ``parameter`` (``t_over_L``, ``H_over_L`` or ``Dc_m``, its first column) the model's n,
    F_1, x_1 and F_max, the FE run's counts (int64 when every run finished, else float64 with
    NaN on a refused run's row), F_1, x_1, peak and their deviations, the field checks, the
    worst violation and the wall time ``seconds`` (forces in units of mu_s N, x in units of
    L); ``units`` (column, unit); ``mu_s``, ``mu_d`` the coefficients of (r, g) at the scene's
    H (``heights`` and ``dc``)."""

    table: Any
    units: List[Tuple[str, str]]
    parameter: str
    mu_s: Optional[float] = None
    mu_d: Optional[float] = None

    def __repr__(self) -> str:
        return f"SeriesResult({len(self)} runs over {self.parameter})"


@dataclass(frozen=True, eq=False)
class BondedResult(_OneTable):
    """``tribofe precursors bonded``: ``table``, fe_events.csv's rows (the library's table):
    both discrete runs, ``model`` ``"fe"`` (the scene's bonded fields) then ``"linear"`` (the
    paper's fields on the same cells), per event ``i``, ``F``, ``Fc``, ``x_nucleation``,
    ``x``, ``Fstar`` and ``stick_slip`` (1 for the whole slip, 0 for a precursor); forces in
    units of mu_s N, x in units of L; ``units``; and the comparison's numbers: ``r``, ``g``,
    ``mu_s``, ``mu_d``, ``H_over_L``, ``t_over_L``, precursors ``n_fe`` and ``n_linear``,
    ``F_1_*`` and ``F_max_*`` (None where a run did not reach stick-slip); with
    ``sweep=True``, ``sweep``: fe_sweep.csv's table (the library's: per H/L and t/L around the
    scene's, the FE-fed and linear runs' ``n``, ``F1``, ``Fmax`` (units of mu_s N; NaN where a
    run did not reach stick-slip), ``max_abs_d_length`` (units of L) and ``outside_model``, why
    a geometry could not be run, its figures then NaN), its units in ``sweep_units``."""

    table: Any
    units: List[Tuple[str, str]]
    r: float
    g: float
    mu_s: float
    mu_d: float
    H_over_L: float
    t_over_L: float
    n_fe: Optional[int]
    n_linear: Optional[int]
    F_1_fe: Optional[float]
    F_1_linear: Optional[float]
    F_max_fe: Optional[float]
    F_max_linear: Optional[float]
    sweep: Any = None
    sweep_units: Optional[List[Tuple[str, str]]] = None

    def __repr__(self) -> str:
        return f"BondedResult(r={self.r}, g={self.g}: n FE-fed {self.n_fe}, linear {self.n_linear})"


@dataclass(frozen=True, eq=False)
class ModelResult(_Result):
    """The paper's analytic iteration for (r, g): ``n`` precursors, ``F_1`` and ``F_max``
    (units of mu_s N), ``events`` (events.csv's table, the library's: forces in units of
    mu_s N, arrest x in units of L; ``units`` its (column, unit) pairs) and the fig. 4 curve
    (loading.csv's columns ``curve_Fc_over_mu_s_N``, ``curve_F_over_mu_s_N``)."""

    r: float
    g: float
    n: int
    F_1: float
    F_max: float
    events: Any
    curve_Fc_over_mu_s_N: np.ndarray
    curve_F_over_mu_s_N: np.ndarray
    units: Optional[List[Tuple[str, str]]] = None

    def to_pandas(self):
        """The events table as a DataFrame."""
        return _df(self.events)

    def __repr__(self) -> str:
        return f"ModelResult(r={self.r}, g={self.g}: n = {self.n}, F_1 = {self.F_1:.4f}, F_max = {self.F_max:.4f})"


@dataclass(frozen=True, eq=False)
class FeFig4Run(_Result):
    """One static-kinetic rule's FE run of fig. 4: ``comparison`` with the model (dict: n,
    F_1, x_1, F_max of model and FE, the one definition's counts, the front advances),
    the precursors' arrest positions (FE and model, units of L), the stick-slip peaks (units
    of mu_s N), the worst violation and the whole ``run`` (a SlideResult)."""

    rule: str
    comparison: Dict[str, Any]
    x_arrest_fe_over_L: np.ndarray
    x_arrest_model_over_L: np.ndarray
    peaks_over_mu_s_N: np.ndarray
    worst_violation: float
    run: Any

    def to_pandas(self):
        """The run's tables: ``{"loading": df, "events": df}``."""
        return self.run.to_pandas()

    def __repr__(self) -> str:
        c = self.comparison
        return f"FeFig4Run({self.rule}: n advancing {c['n_fe_advancing']} (model {c['n_model']}), F_max {c['F_max_fe']:.4f})"


# The comparison's columns that are counts (int64 in the table).
_COUNTS = ("n_model", "n_fe", "n_fe_long", "n_fe_advancing", "n_front")


@dataclass(frozen=True, eq=False)
class FeFig4Result(_Result):
    """``tribofe precursors fe``: ``runs``, one :class:`FeFig4Run` per static-kinetic rule
    (``runs["paper"]``, ``runs["overdamped"]``), and ``summary``, the command's summary.csv
    (the library's table: the model's row, then a row per rule; ``units`` its (column, unit)
    pairs). Before, the call returned a list of dicts: ``result[0]``, iteration and ``len``
    still work (deprecated), and ``comparison`` (a table made here, under other names) is
    deprecated for ``summary``."""

    runs: Dict[str, FeFig4Run]
    definition: str
    front_definition: str
    summary: Any = None
    units: Optional[List[Tuple[str, str]]] = None

    @property
    def comparison(self):
        _deprecated("precursors.fe_fig4().comparison", ".summary")
        skip = ("definition", "front_definition")
        rows = [r.comparison for r in self.runs.values()]
        cols: Dict[str, Any] = {"rule": list(self.runs)}
        for k in (rows[0] if rows else {}):
            if k in skip:
                continue
            vals = [np.nan if row[k] is None else row[k] for row in rows]
            cols[k] = np.asarray(vals, dtype=np.int64 if k in _COUNTS else float)
        cols["worst_violation"] = np.asarray([r.worst_violation for r in self.runs.values()])
        return _table(cols)

    def __getitem__(self, key):
        if isinstance(key, int):
            _deprecated(f"precursors.fe_fig4()[{key}]", ".runs[rule]")
            return list(self.runs.values())[key]
        return super().__getitem__(key)

    def __iter__(self):
        _deprecated("iterating precursors.fe_fig4()", ".runs.values()")
        return iter(list(self.runs.values()))

    def __len__(self) -> int:
        return len(self.runs)

    def to_pandas(self):
        """``{"summary": df, "<rule>_loading": df, "<rule>_events": df, ...}``."""
        out = {"summary": _df(self.summary)}
        for rule, run in self.runs.items():
            for name, df in run.to_pandas().items():
                out[f"{rule}_{name}"] = df
        return out

    def __repr__(self) -> str:
        return "FeFig4Result(" + "; ".join(repr(r) for r in self.runs.values()) + ")"


# The per-node arrays of a rupture (one value per base node, x >= any).
_NODES = (
    "x_m",
    "width_m",
    "tau0_Pa",
    "t_arrival_s",
    "t_weakened_s",
    "slip_m",
    "peak_slip_rate_m_per_s",
    "rupture_time_s",
)
_SCALARS = (
    "force_drop_N_per_m",
    "min_sigma_Pa",
    "steps",
    "dt_s",
    "dt_stable_s",
    "front_speed_m_per_s",
    "c_p_m_per_s",
    "c_s_m_per_s",
    "c_R_m_per_s",
    "lambda0_m",
    "rate_threshold_m_per_s",
)


@dataclass(frozen=True, eq=False)
class RuptureResult(_Result):
    """``tribofe rupture``: per base node ``x_m``, ``width_m``, ``tau0_Pa``,
    ``t_arrival_s`` and ``t_weakened_s`` (NaN where never), ``slip_m``,
    ``peak_slip_rate_m_per_s``, ``rupture_time_s`` (the first slip rate above
    ``rate_threshold_m_per_s``; NaN where never) as arrays (``nodes``: them as a table); the
    force drop, front speed (None when no front), wave speeds, steps, cohesive-zone size
    ``lambda0_m``; ``energy`` the ledger at t_end (J/m), energy.csv's row under its column names; ``stations``: per station x (m) the table of
    ``station_x<x>.csv`` (the library's, its units in ``station_units``)."""

    x_m: np.ndarray
    width_m: np.ndarray
    tau0_Pa: np.ndarray
    t_arrival_s: np.ndarray
    t_weakened_s: np.ndarray
    slip_m: np.ndarray
    peak_slip_rate_m_per_s: np.ndarray
    rupture_time_s: np.ndarray
    force_drop_N_per_m: float
    min_sigma_Pa: float
    steps: int
    dt_s: float
    dt_stable_s: float
    front_speed_m_per_s: Optional[float]
    c_p_m_per_s: float
    c_s_m_per_s: float
    c_R_m_per_s: float
    lambda0_m: float
    rate_threshold_m_per_s: float
    energy: Dict[str, float]
    stations: Dict[float, Any]
    station_units: List[Tuple[str, str]] = field(default_factory=list)
    core_s: float = 0.0

    @property
    def nodes(self):
        """The per-node arrays as one table."""
        return _table({k: getattr(self, k) for k in _NODES})

    def to_pandas(self):
        """``{"nodes": df, "summary": one row, "energy": one row, "station_x<x>": df...}``."""
        out = {
            "nodes": _df(self.nodes),
            "summary": _row({k: getattr(self, k) for k in _SCALARS}),
            "energy": _row(self.energy),
        }
        for x, t in self.stations.items():
            out[f"station_x{x:g}"] = _df(t, self.station_units)
        return out

    def __repr__(self) -> str:
        arrived = int(np.isfinite(self.t_arrival_s).sum())
        speed = "none" if self.front_speed_m_per_s is None else f"{self.front_speed_m_per_s:.4g} m/s"
        return (
            f"RuptureResult({len(self.x_m)} base nodes, {arrived} reached, front {speed}, "
            f"force drop {self.force_drop_N_per_m:.4g} N/m, {self.steps} steps)"
        )


def rupture_result(raw: Dict[str, Any]) -> RuptureResult:
    """The extension's dict as a :class:`RuptureResult`, each station a table with units."""
    units: List[Tuple[str, str]] = []
    stations = {}
    for x, st in raw.pop("stations").items():
        units = st["units"]
        stations[x] = _table(st["table"], units)
    return RuptureResult(stations=stations, station_units=units, **raw)
