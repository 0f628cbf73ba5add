"""tribofe from Python: the Rust library's studies with numpy arrays in and out.

Units are SI throughout (m, Pa, N per metre of width); dimensionless quantities say so in
their names (``x_over_L``, ``p_over_pmean``, ``F_over_mu_s_N``).

>>> import tribofe
>>> r = tribofe.check()                     # the paper's scene
>>> case = r.cases[2]                       # F/N = 0.82
>>> case.x_over_L, case.p_over_pmean        # numpy arrays
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Union

import numpy as np

from . import errors
from ._tribofe import Scene, __version__
from ._tribofe import check as _check
from ._tribofe import converge as _converge
from ._tribofe import defaults as _defaults
from ._tribofe import dynamic_slide as _dynamic_slide
from ._tribofe import edges as _edges
from ._tribofe import precursors_fe_fig4 as _fe_fig4
from ._tribofe import precursors_fe_fig5 as _fe_fig5
from ._tribofe import precursors_bonded as _bonded
from ._tribofe import precursors_dc as _dc
from ._tribofe import precursors_heights as _heights
from ._tribofe import precursors_map as _n_map
from ._tribofe import precursors_model as _precursors_model
from ._tribofe import precursors_thin_layer as _thin_layer
from ._tribofe import rupture as _rupture
from ._tribofe import slide as _slide
from ._tribofe import solve as _solve
from ._tribofe import stability as _stability
from ._tribofe import sweep as _sweep
from ._results import (
    BondedResult,
    ConvergeResult,
    EdgesResult,
    FeFig4Result,
    FeFig4Run,
    FeFig5Result,
    ModelResult,
    NMapResult,
    RuptureResult,
    SeriesResult,
    SolveResult,
    StabilityResult,
    SweepResult,
    _df,
    _row,
    _table,
    rupture_result,
)
from .errors import InputError, Interrupted, NumericalError, OutputError, TribofeError

__all__ = [
    "Scene",
    "check",
    "solve",
    "slide",
    "precursors",
    "dynamics",
    "sweep",
    "converge",
    "edges",
    "stability",
    "defaults",
    "CheckResult",
    "CheckCase",
    "SolveResult",
    "SlideResult",
    "DynamicSlideResult",
    "SweepResult",
    "ConvergeResult",
    "ModelResult",
    "FeFig4Result",
    "FeFig4Run",
    "FeFig5Result",
    "NMapResult",
    "SeriesResult",
    "BondedResult",
    "EdgesResult",
    "StabilityResult",
    "RuptureResult",
    "TribofeError",
    "InputError",
    "NumericalError",
    "OutputError",
    "Interrupted",
    "errors",
    "__version__",
]


def defaults() -> Dict[str, Dict[str, Any]]:
    """What a keyword left at None means: the library's default per function and keyword
    (``defaults()["slide"]["cycles"]``), the same constants the calls use and
    ``tribofe <command> --help`` shows. Keywords whose default depends on the scene (``dc``,
    ``h``, ``damping`` of :func:`dynamics.slide`, ``x_max``, the coefficients) are not listed:
    their docstrings say how the library chooses them."""
    return _defaults()


def _progress(progress, desc: str):
    """The progress callback: a callable gets the done fraction in [0, 1]; ``None``/``False``
    stays silent; ``True`` draws a tqdm bar on a terminal (or in a notebook) and, elsewhere (a
    log file, a pipe) or without tqdm, writes a plain line at each tenth done, so a redirected
    stream gets at most 11 lines however many ticks the run reports. Returns (callback, close)."""
    if callable(progress):
        return progress, lambda: None
    if not progress:
        return None, lambda: None
    stream = sys.stderr
    terminal = getattr(stream, "isatty", lambda: False)() or "ipykernel" in sys.modules
    tqdm = None
    if terminal:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            pass
    if tqdm is not None:
        bar = tqdm(total=1000, desc=desc, unit="‰", leave=False)

        def update(frac: float) -> None:
            # tqdm's own rate limit (mininterval) decides when to redraw; parallel points may
            # report out of order, the bar only advances.
            n = int(1000 * min(max(frac, 0.0), 1.0))
            if n > bar.n:
                bar.update(n - bar.n)

        return update, bar.close
    shown = [-1]

    def line(frac: float) -> None:
        tenth = int(10 * min(max(frac, 0.0), 1.0))
        if tenth > shown[0]:
            shown[0] = tenth
            print(f"{desc}: {10 * tenth} %", file=stream, flush=True)

    return line, lambda: None


@dataclass(frozen=True)
class CheckCase:
    """One load case of the bonded check; stresses in units of the mean pressure N/L."""

    fn_ratio: float
    N_N_per_m: float
    F_N_per_m: float
    tilt_rad: float
    x_over_L: np.ndarray
    p_over_pmean: np.ndarray
    tau_over_pmean: np.ndarray
    p_model: np.ndarray
    tau_model: np.ndarray
    p_extrap: np.ndarray
    tau_extrap: np.ndarray
    p_corrected: np.ndarray
    metrics: Dict[str, Any]

    def profile(self):
        """The interface profile as a table (DataFrame with pandas), the columns of
        ``profile_FN<ratio>.csv``."""
        return _table(
            {
                k: getattr(self, k)
                for k in (
                    "x_over_L",
                    "p_over_pmean",
                    "tau_over_pmean",
                    "p_model",
                    "tau_model",
                    "p_extrap",
                    "tau_extrap",
                    "p_corrected",
                )
            }
        )

    def __repr__(self) -> str:
        m = self.metrics
        return (
            f"CheckCase(F/N={self.fn_ratio}, {len(self.x_over_L)} interface nodes, interior slope "
            f"{m['slope_interior']:.5f} (model {m['slope_model']:.5f}, corrected {m['slope_corrected']:.5f}), "
            f"tau(0)={m['tau_center']:.5f} N/L)"
        )


@dataclass(frozen=True)
class CheckResult:
    """The paper's bonded check: one :class:`CheckCase` per F/N."""

    scene: Scene
    cases: List[CheckCase]
    n_nodes: int
    n_elements: int
    balance_error: float
    core_s: float = field(default=0.0, compare=False)
    fields: Optional[Dict[str, Any]] = field(default=None, compare=False, repr=False)

    def summary(self):
        """One row per F/N with the interior slopes, tau(0) and edge-zone widths (in units of t)."""
        rows: Dict[str, list] = {}
        for c in self.cases:
            row = {"fn_ratio": c.fn_ratio, "N_N_per_m": c.N_N_per_m, "F_N_per_m": c.F_N_per_m}
            for k, v in c.metrics.items():
                if isinstance(v, list):
                    for side, x in zip(("left", "right"), v):
                        row[f"{k}_{side}"] = np.nan if x is None else x
                else:
                    row[k] = v
            for k, v in row.items():
                rows.setdefault(k, []).append(v)
        return _table({k: np.asarray(v) for k, v in rows.items()})

    def to_pandas(self):
        """``{"summary": df, "profile_FN<ratio>": df...}``: the summary and each case's profile
        (the files' names of ``tribofe check``)."""
        out = {"summary": _df(self.summary())}
        for c in self.cases:
            out[f"profile_FN{0 if c.fn_ratio == 0 else f'{c.fn_ratio:g}'}"] = _df(c.profile())
        return out

    def __repr__(self) -> str:
        lines = [f"CheckResult({self.scene!r}, {self.n_nodes} nodes, {self.n_elements} elements, balance {self.balance_error:.1e})"]
        lines += [f"  {c!r}" for c in self.cases]
        return "\n".join(lines)


def check(scene: Optional[Scene] = None, fields: bool = False) -> CheckResult:
    """The paper's bonded check (fig. 2) on ``scene`` (default: the paper's).

    With ``fields=True``, ``result.fields`` holds the whole block: ``nodes_m`` (n x 2) and per
    F/N ``displacement_m`` (n x 2, m) and ``stress_Pa`` (n x 4: sigma_xx, sigma_yy, sigma_xy,
    sigma_zz, nodal values extrapolated from the integration points and averaged).

    Raises :class:`InputError` for a bad scene, :class:`NumericalError` for a refused solve.
    """
    scene = scene if scene is not None else Scene()
    raw = _check(scene, fields)
    cases = [CheckCase(**c) for c in raw["cases"]]
    return CheckResult(
        scene, cases, raw["n_nodes"], raw["n_elements"], raw["balance_error"], raw["core_s"], raw.get("fields")
    )


def solve(
    *,
    lx: Optional[float] = None,
    ly: Optional[float] = None,
    nx: Optional[int] = None,
    ny: Optional[int] = None,
    element: Optional[str] = None,
    young: Optional[float] = None,
    poisson: Optional[float] = None,
    bottom: Optional[str] = None,
    right: Optional[str] = None,
    top: Optional[str] = None,
    left: Optional[str] = None,
    max_dofs: Optional[int] = None,
) -> SolveResult:
    """A rectangle [0, lx] x [0, ly] (m) of ``nx`` x ``ny`` elements (``element``: qua4,
    qua4-sri, qua4-im, qua8, qua9, tri3, tri6) in plane strain (``young`` Pa, ``poisson``),
    one condition per side: ``bottom``, ``right``, ``top``, ``left`` each ``"free"``,
    ``"clamped"``, ``"roller"``, ``"u=UX,UY"`` (m) or ``"t=TX,TY"`` (Pa), as ``tribofe solve``
    (None is its default, ``defaults()["solve"]``: 1 m x 0.1 m, 40 x 4 QUA4, E = 2 kPa,
    nu = 0.4, bottom clamped, top displaced 1 mm along x). ``max_dofs``: refuse meshes above
    this many unknowns (None: what fits in memory). Returns a :class:`SolveResult`: the
    reactions per side, their balance and the fields. A bad input raises
    :class:`InputError` naming its keyword."""
    raw = _solve(
        lx=lx,
        ly=ly,
        nx=nx,
        ny=ny,
        element=element,
        young=young,
        poisson=poisson,
        bottom=bottom,
        right=right,
        top=top,
        left=left,
        max_dofs=max_dofs,
    )
    return SolveResult(**raw)


@dataclass(frozen=True)
class SlideResult:
    """A frictional run: the loading curve and events as tables, the interface states as
    (states x nodes) arrays (``states['p_force_N_per_m']`` etc.; ``state_code`` 0 stick,
    1 slip, 2 open)."""

    law: str
    mu_s: float
    mu_d: float
    n_force_N_per_m: float
    x_over_L: np.ndarray
    width_m: np.ndarray
    loading: Any
    curve_Fc_over_mu_s_N: np.ndarray
    curve_F_over_mu_s_N: np.ndarray
    events: Any
    states: Dict[str, np.ndarray]
    units: Dict[str, List[tuple]]
    sliding_events: int
    max_violation: float
    condense_s: float
    events_s: float
    core_s: float = field(default=0.0, compare=False)

    def to_pandas(self):
        """``{"loading": df, "events": df}``, each with its units in ``attrs["units"]``."""
        return {k: _df(getattr(self, k), self.units[k]) for k in ("loading", "events")}

    def __repr__(self) -> str:
        n_ev = len(self.events["event"]) if "event" in self.events else 0
        return (
            f"SlideResult({self.law}, {len(self.x_over_L)} interface nodes, {n_ev} events, "
            f"{self.sliding_events} whole slips, largest violation {self.max_violation:.1e} of N/n, "
            f"{self.condense_s + self.events_s:.3f} s)"
        )


def slide(
    scene: Optional[Scene] = None,
    law: Optional[str] = None,
    *,
    mu: Optional[float] = None,
    mu_s: Optional[float] = None,
    mu_d: Optional[float] = None,
    r: Optional[float] = None,
    g: Optional[float] = None,
    rule: Optional[str] = None,
    residual: Optional[str] = None,
    backslip: Optional[str] = None,
    dc: Optional[float] = None,
    n_force: Optional[float] = None,
    x_max: Optional[float] = None,
    cycles: Optional[int] = None,
    cycle_end: Optional[str] = None,
    max_events: Optional[int] = None,
    newton: bool = False,
    operator: Optional[str] = None,
    states: Optional[str] = None,
    keep_states: Optional[bool] = None,
    progress: Any = False,
) -> SlideResult:
    """The frictional interface under the normal force ``n_force`` (N/m), then the plate's
    drive X (m) at height H, solved event by event (as ``tribofe slide``).

    ``law``: ``"coulomb"`` (``mu``), ``"static-kinetic"`` (``mu_s``, ``mu_d`` or the paper's
    ``r``, ``g``; ``rule`` ``"paper"`` or ``"overdamped"``) or ``"slip-weakening"`` (plus
    ``dc``, m). The paper rule's conventions: ``residual`` (``"relaxed"`` or ``"pre-event"``)
    and ``backslip`` (``"allowed"`` or ``"forbidden"``). ``cycle_end``: ``"whole-slip"`` or
    ``"crossing"``; ``operator``: ``"dense"`` or ``"banded"``; ``states``: ``"all"`` (every
    event's interface state kept) or ``"none"`` (the last one only; ``keep_states`` is its old
    boolean spelling). A choice outside its list raises :class:`InputError` naming the keyword
    and the accepted values. A keyword left at None takes the command's default
    (``defaults()["slide"]``: law coulomb, rule paper, N = 1 N/m, 10 cycles, 50 000 events,
    whole-slip, dense, all states). The interrupt key stops
    the run within a second (:class:`KeyboardInterrupt`). ``progress``: True for a tqdm bar
    (on a terminal, with tqdm; a line per tenth done elsewhere), a callable for the fraction
    done, False (the default) for silence.
    """
    cb, close = _progress(progress, f"slide {law or _defaults()['slide']['law']}")
    try:
        raw = _slide(
            scene if scene is not None else Scene(),
            law,
            mu=mu,
            mu_s=mu_s,
            mu_d=mu_d,
            r=r,
            g=g,
            rule=rule,
            residual=residual,
            backslip=backslip,
            dc=dc,
            n_force=n_force,
            x_max=x_max,
            cycles=cycles,
            cycle_end=cycle_end,
            max_events=max_events,
            newton=newton,
            operator=operator,
            states=states,
            keep_states=keep_states,
            progress=cb,
        )
    finally:
        close()
    return _slide_result(raw)


def _slide_result(raw: Dict[str, Any]) -> SlideResult:
    """The extension's dict as a :class:`SlideResult`, each table with its units."""
    for k in ("loading", "events"):
        raw[k] = _table(raw[k], raw["units"][k])
    return SlideResult(**raw)


def sweep(
    scene: Optional[Scene] = None,
    *,
    length: Any = None,
    thickness: Any = None,
    height: Any = None,
    young: Any = None,
    poisson: Any = None,
    converged: bool = True,
    friction: Optional[tuple] = None,
    rule: Optional[str] = None,
    cycles: Optional[int] = None,
    progress: Any = False,
) -> SweepResult:
    """The bonded check over the product of the given values (each a number, a list, or the
    command's text ``"a:b:n"`` / ``"a:b:ng"`` for n linear / geometric points), as
    ``tribofe sweep``: one row per point and F/N with the columns of ``sweep.csv``
    (a pandas DataFrame when pandas is installed, else a dict of arrays).
    ``friction=(mu_s, mu_d)`` also runs the frictional interface at each point (``rule``,
    ``cycles``: None is the command's default, ``defaults()["sweep"]``). Silent unless
    ``progress`` is True (a tqdm bar, a few lines without a terminal) or a callable.
    Returns a :class:`SweepResult`: ``table`` (sweep.csv's rows, the library's table),
    ``units``."""
    cb, close = _progress(progress, "sweep")
    try:
        raw = _sweep(
            scene if scene is not None else Scene(),
            length=length,
            thickness=thickness,
            height=height,
            young=young,
            poisson=poisson,
            converged=converged,
            friction=friction,
            rule=rule,
            cycles=cycles,
            progress=cb,
        )
    finally:
        close()
    return SweepResult(_table(raw["table"], raw["units"]), raw["units"])


def converge(
    scene: Optional[Scene] = None,
    *,
    elements: Any = None,
    families: Any = None,
    n_thick: Any = None,
    fn_ratio: Optional[float] = None,
    parallel: bool = True,
    target: Optional[float] = None,
    progress: Any = False,
) -> ConvergeResult:
    """Mesh and element convergence of the check (``tribofe converge``): returns a
    :class:`ConvergeResult`, ``table`` the rows of ``convergence.csv`` (the library's table at
    full precision, ``units``) and ``summary`` the printed reading (orders, edge widths, the
    cheapest run reaching ``target``, an edge-zone error in units of N/L).
    None is the command's default (``defaults()["converge"]``: QUA4, uniform and graded,
    t/1 to t/64, F/N = 0.82, the command's ``--case``). Silent unless ``progress`` is asked."""
    cb, close = _progress(progress, "converge")
    try:
        raw = _converge(
            scene if scene is not None else Scene(),
            elements=None if elements is None else list(elements),
            families=None if families is None else list(families),
            n_thick=None if n_thick is None else list(n_thick),
            fn_ratio=fn_ratio,
            parallel=parallel,
            target=target,
            progress=cb,
        )
    finally:
        close()
    return ConvergeResult(_table(raw["table"], raw["units"]), raw["units"], raw["summary"])


def edges(
    scene: Optional[Scene] = None,
    *,
    mu: Any = None,
    refine: Any = None,
    mu_s: Optional[float] = None,
    mu_d: Optional[float] = None,
    rule: Optional[str] = None,
    t_over_l: Any = None,
    open_refine: Any = None,
    end_grading: Optional[float] = None,
    h_over_l: Any = None,
    progress: Any = False,
) -> EdgesResult:
    """The block's ends on the frictional interface, as ``tribofe edges``: pre-slip under N
    alone for each coulomb ``mu`` and refinement ``refine`` (elements through t), and the
    trailing end's opening under the drive (static-kinetic ``mu_s``, ``mu_d``, ``rule``
    ``"paper"`` or ``"overdamped"``) for each ``t_over_l`` x ``open_refine`` x ``h_over_l``;
    ``end_grading`` grows the elements from the ends (1: uniform). Each study meshes its own
    blocks from the scene's length and materials (its thickness, height and mesh keys do not
    act; a mesh file is refused). None is the command's default (``defaults()["edges"]``).
    Returns an :class:`EdgesResult`: ``preslip`` and ``opening``, the tables of preslip.csv
    and opening.csv. Silent unless ``progress`` is asked; the interrupt key stops it."""
    cb, close = _progress(progress, "edges")
    try:
        raw = _edges(
            scene if scene is not None else Scene(),
            mu=None if mu is None else [float(v) for v in mu],
            refine=None if refine is None else [int(v) for v in refine],
            mu_s=mu_s,
            mu_d=mu_d,
            rule=rule,
            t_over_l=None if t_over_l is None else [float(v) for v in t_over_l],
            open_refine=None if open_refine is None else [int(v) for v in open_refine],
            end_grading=end_grading,
            h_over_l=None if h_over_l is None else [float(v) for v in h_over_l],
            progress=cb,
        )
    finally:
        close()
    units = {k: raw[k]["units"] for k in ("preslip", "opening")}
    return EdgesResult(
        _table(raw["preslip"]["table"], units["preslip"]), _table(raw["opening"]["table"], units["opening"]), units
    )


def stability(
    scene: Optional[Scene] = None,
    *,
    study: Any = None,
    corner_max: Optional[int] = None,
    n_ref: Optional[int] = None,
    progress: Any = False,
) -> StabilityResult:
    """The numerical stability studies of the paper's check, as ``tribofe stability``:
    ``study`` any of ``"plate"`` (a stiff elastic plate against the exact rigid one:
    modelling error against round-off), ``"nu"`` (near-incompressibility: locking per
    element), ``"shape"`` (elongated and distorted elements), ``"thin"`` (t/L -> 0) and
    ``"corners"`` (the singular end nodes against converging integrated quantities); None
    runs all five. ``corner_max``: the finest corner mesh, elements through the thickness (1,
    2, 4, .. up to it); ``n_ref``: the qua9 reference mesh of the nu and shape studies,
    elements through the thickness; each refused when its study does not run. None is the
    command's default (``defaults()["stability"]``). The scene gives the block, plate and
    materials (lengths m, moduli Pa); every study sets its own meshes and load case, so a
    scene with other ``h``, ``n_thick``, ``fn_ratios``, ``mesh`` or ``geometry`` than the
    paper's is refused. Returns a :class:`StabilityResult`: ``tables[study]``, the study's
    CSV's table (errors in units of N/L, widths in units of t, times in s). Silent unless
    ``progress`` is asked; the interrupt key stops it between two solves."""
    cb, close = _progress(progress, "stability")
    try:
        raw = _stability(
            scene if scene is not None else Scene(),
            study=None if study is None else ([study] if isinstance(study, str) else [str(s) for s in study]),
            corner_max=corner_max,
            n_ref=n_ref,
            progress=cb,
        )
    finally:
        close()
    tables = {k: _table(v["table"], v["units"]) for k, v in raw["tables"].items()}
    units = {k: v["units"] for k, v in raw["tables"].items()}
    return StabilityResult(tables, units, raw["summary"], raw.get("corners"))


class precursors:  # noqa: N801 - a namespace, as tribofe::precursors
    """The paper's 1D precursor model."""

    @staticmethod
    def model(r: Optional[float] = None, g: Optional[float] = None, events: Optional[int] = None) -> ModelResult:
        """The paper's analytic event iteration for r = mu_d/mu_s and g = 6 mu_d H/L (None:
        the paper's fig. 4 case, 0.9 and 0.35, as ``tribofe precursors model``): a
        :class:`ModelResult`, ``events`` (forces in units of mu_s N, arrest x in units of L)
        as a table, ``n`` (precursors), ``F_1``, ``F_max`` and the fig. 4 curve. ``events``
        defaults to n + 1 (the precursors and the first whole slip)."""
        raw = _precursors_model(r, g, events)
        events = raw.pop("events")
        curve = raw.pop("curve")
        return ModelResult(
            events=_table(events["table"], events["units"]),
            units=events["units"],
            curve_Fc_over_mu_s_N=np.asarray(curve["Fc_over_mu_s_N"]),
            curve_F_over_mu_s_N=np.asarray(curve["F_over_mu_s_N"]),
            **raw,
        )

    @staticmethod
    def fe_fig4(
        scene: Optional[Scene] = None,
        r: Optional[float] = None,
        g: Optional[float] = None,
        cycles: Optional[int] = None,
        progress: Any = False,
    ) -> FeFig4Result:
        """The paper's fig. 4 from the frictional FE on ``scene``, as ``tribofe precursors fe``
        (the same runs and defaults: None is the paper's (r, g) = (0.9, 0.35) and the
        command's 2 cycles, ``defaults()["precursors.fe_fig4"]``): a :class:`FeFig4Result`,
        ``runs[rule]`` per static-kinetic rule (``"paper"``, ``"overdamped"``) with the
        comparison against the model (n, F_1, x_1, F_max; forces in units of mu_s N, x in
        units of L), the precursors' arrest positions and the whole run as a
        :class:`SlideResult`; ``summary`` the command's summary.csv (a row for the model, then
        one per rule)."""
        cb, close = _progress(progress, "fig. 4 (FE)")
        try:
            raw = _fe_fig4(scene if scene is not None else Scene(), r, g, cycles, progress=cb)
        finally:
            close()
        runs, summary = raw["runs"], raw["summary"]
        out = {}
        for run in runs:
            run["run"] = _slide_result(run["run"])
            out[run["rule"]] = FeFig4Run(**run)
        first = runs[0]["comparison"] if runs else {}
        return FeFig4Result(
            out,
            first.get("definition", ""),
            first.get("front_definition", ""),
            _table(summary["table"], summary["units"]),
            summary["units"],
        )

    @staticmethod
    def fe_fig5(
        scene: Optional[Scene] = None,
        resolution: Optional[int] = None,
        rules: Any = None,
        max_events: Optional[int] = None,
        progress: Any = False,
    ) -> FeFig5Result:
        """The paper's fig. 5 from the frictional FE: a :class:`FeFig5Result` whose ``table``
        has one row per (r, g) cell centre of a ``resolution`` x ``resolution`` grid and rule,
        with the model's n and F_max and the FE run's status (done, capped, refused) and
        counts. None is the command's default (``tribofe precursors fe-map``: 20, the paper
        rule, 2000 events)."""
        cb, close = _progress(progress, "fig. 5 (FE)")
        try:
            cols = _fe_fig5(
                scene if scene is not None else Scene(),
                resolution,
                None if rules is None else list(rules),
                max_events,
                progress=cb,
            )
        finally:
            close()
        return FeFig5Result(_table(cols["table"], cols["units"]), cols["units"])

    @staticmethod
    def map(resolution: Optional[int] = None) -> NMapResult:
        """The model's n(r, g) at the cell centres of a ``resolution`` x ``resolution`` grid
        over the (r, g) square (the paper's fig. 5), as ``tribofe precursors map`` (None: its
        40, ``defaults()["precursors.map"]``; 2 to 400): a :class:`NMapResult` whose ``table``
        is n_map.csv's (``r``, ``g``, ``n``)."""
        raw = _n_map(resolution)
        return NMapResult(_table(raw["table"], raw["units"]), raw["units"])

    @staticmethod
    def thin_layer(
        t_over_l: Any,
        scene: Optional[Scene] = None,
        r: Optional[float] = None,
        g: Optional[float] = None,
        progress: Any = False,
    ) -> SeriesResult:
        """The thin-layer limit, as ``tribofe precursors thin-layer``: the ``paper`` rule at
        (r, g) (None: 0.9, 0.35) on blocks of each ``t_over_l`` (t/L, a list; 0 < t/L <= 0.1)
        at the scene's L and H/L; each block is meshed here with h = t and 2 elements through
        t, so the scene's thickness and mesh keys do not act. A :class:`SeriesResult` whose
        ``table`` is thin_layer.csv's. Silent unless ``progress`` is asked; the interrupt key
        stops it."""
        cb, close = _progress(progress, "thin layer")
        try:
            raw = _thin_layer([float(v) for v in t_over_l], scene if scene is not None else Scene(), r, g, progress=cb)
        finally:
            close()
        return SeriesResult(_table(raw["table"], raw["units"]), raw["units"], "t_over_L")

    @staticmethod
    def heights(
        h_over_l: Any,
        scene: Optional[Scene] = None,
        r: Optional[float] = None,
        g: Optional[float] = None,
        progress: Any = False,
    ) -> SeriesResult:
        """The height of the drive, as ``tribofe precursors heights``: the ``paper`` rule with
        the coefficients of (r, g) (None: 0.9, 0.35) at the scene's H kept fixed, over each
        ``h_over_l`` (H/L, a list; g = 6 mu_d H/L must stay below 1). A :class:`SeriesResult`
        whose ``table`` is heights.csv's, with ``mu_s``, ``mu_d``. Silent unless ``progress``
        is asked; the interrupt key stops it."""
        cb, close = _progress(progress, "heights")
        try:
            raw = _heights([float(v) for v in h_over_l], scene if scene is not None else Scene(), r, g, progress=cb)
        finally:
            close()
        return SeriesResult(_table(raw["table"], raw["units"]), raw["units"], "H_over_L", raw["mu_s"], raw["mu_d"])

    @staticmethod
    def dc(
        dc: Any,
        scene: Optional[Scene] = None,
        r: Optional[float] = None,
        g: Optional[float] = None,
        max_events: Optional[int] = None,
        progress: Any = False,
    ) -> SeriesResult:
        """The event rule against D_c, as ``tribofe precursors dc``: at (r, g) (None: 0.9,
        0.35) the ``paper`` rule (its row has ``Dc_m`` = 0) and slip-weakening with each
        ``dc`` (m, a list), one cycle each, a run over ``max_events`` (None: 2000,
        ``defaults()["precursors.dc"]``) refused on its own row. A :class:`SeriesResult` whose
        ``table`` is dc.csv's, with ``mu_s``, ``mu_d``. Silent unless ``progress`` is asked;
        the interrupt key stops it."""
        cb, close = _progress(progress, "D_c")
        try:
            raw = _dc([float(v) for v in dc], scene if scene is not None else Scene(), r, g, max_events, progress=cb)
        finally:
            close()
        return SeriesResult(_table(raw["table"], raw["units"]), raw["units"], "Dc_m", raw["mu_s"], raw["mu_d"])

    @staticmethod
    def bonded(
        scene: Optional[Scene] = None,
        r: Optional[float] = None,
        g: Optional[float] = None,
        events: Optional[int] = None,
        sweep: bool = False,
        progress: Any = False,
    ) -> BondedResult:
        """The earlier comparison, as ``tribofe precursors bonded``: the 1D model fed with the
        scene's bonded interface fields next to the paper's linear fields on the same cells,
        at (r, g) (None: 0.9, 0.35), ``events`` events each (None: 200; at most 100 000). A
        :class:`BondedResult` whose ``table`` is fe_events.csv's. With ``sweep=True`` (the
        command's ``--sweep``), also ``sweep``, fe_sweep.csv's table: the comparison over
        H/L = (1/4, 1/2, 1, 2) x the scene's and t/L = (1/2, 1, 2, 4) x the scene's, one
        bonded check each (h no coarser than t/2). Silent unless ``progress`` is asked; the
        interrupt key stops the sweep between two geometries."""
        cb, close = _progress(progress, "bonded sweep")
        try:
            raw = _bonded(scene if scene is not None else Scene(), r, g, events, sweep=bool(sweep), progress=cb)
        finally:
            close()
        table = _table(raw.pop("table"), raw["units"])
        sw = raw.pop("sweep", None)
        if sw is not None:
            raw["sweep"] = _table(sw["table"], sw["units"])
            raw["sweep_units"] = sw["units"]
        return BondedResult(table=table, **raw)


@dataclass(frozen=True)
class DynamicSlideResult:
    """A dynamic slide (``tribofe slide --dynamics``): the command's tables, each with every
    column of its CSV (``loading``, ``events``, ``dyn_events``, ``fronts``, ``summary``, and
    ``advances`` for a weakening law; DataFrames when pandas is installed, else dicts of
    arrays; integer columns as integers, an empty cell as NaN; ``dyn_events`` is the library's
    table at full precision, its units in ``attrs["units"]``), each dynamic event's samples
    (``samples[k]``: ``t_s``, ``F_N_per_m``, ``tip_m``, and ``slip_rate_m_per_s``, samples x
    base nodes at the times ``slip_rate_t_s``), the run's scales, and the notes on what the library chose (D_c, h, kappa).
    ``incomplete`` names the cap a run met (None when it reached its end)."""

    law: str
    mu_s: float
    mu_d: float
    x_over_L: np.ndarray
    h_m: float
    dt_s: float
    dt_stable_s: float
    damping_eta_s: float
    c_s_m_per_s: float
    c_p_m_per_s: float
    c_R_m_per_s: float
    dofs: int
    steps: int
    loading: Any
    events: Any
    dyn_events: Any
    fronts: Any
    summary: Dict[str, Any]
    samples: List[Dict[str, Any]]
    notes: List[str]
    incomplete: Optional[str] = None
    advances: Any = None
    units: Dict[str, List[tuple]] = field(default_factory=dict)
    core_s: float = field(default=0.0, compare=False)

    def to_pandas(self):
        """``{"loading", "events", "dyn_events", "fronts", ["advances",] "summary"}`` as
        DataFrames (``summary`` one row), each with its units in ``attrs["units"]``."""
        out = {}
        for k in ("loading", "events", "dyn_events", "fronts", "advances"):
            t = getattr(self, k)
            if t is not None:
                out[k] = _df(t, self.units.get(k))
        out["summary"] = _row(self.summary)
        out["summary"].attrs["units"] = dict(self.units.get("summary", []))
        return out

    def __repr__(self) -> str:
        f1 = self.summary.get("first_advance_F_over_mu_s_N", float("nan"))
        return (
            f"DynamicSlideResult({self.law}, {len(self.x_over_L)} interface nodes, h = {self.h_m:.4g} m, "
            f"{len(self.samples)} dynamic events, F_1 = {f1:.4f} mu_s N"
            f"{', incomplete: ' + self.incomplete if self.incomplete else ''}, {self.core_s:.2f} s)"
        )


class dynamics:  # noqa: N801 - a namespace, as tribofe::dynamics
    """Explicit elastodynamics with a frictional base (docs/dynamics.md)."""

    @staticmethod
    def slide(
        scene: Optional[Scene] = None,
        law: Optional[str] = None,
        *,
        mu: Optional[float] = None,
        mu_s: Optional[float] = None,
        mu_d: Optional[float] = None,
        r: Optional[float] = None,
        g: Optional[float] = None,
        dc: Optional[float] = None,
        h: Optional[float] = None,
        n_force: Optional[float] = None,
        x_max: Optional[float] = None,
        cycles: Optional[int] = None,
        cycle_end: Optional[str] = None,
        max_events: Optional[int] = None,
        operator: Optional[str] = None,
        states: Optional[str] = None,
        keep_states: Optional[bool] = None,
        damping: Optional[float] = None,
        courant: Optional[float] = None,
        drive_velocity: Optional[float] = None,
        plate_mass: Optional[float] = None,
        plate_inertia: Optional[float] = None,
        heal: Optional[str] = None,
        weakening_steps: Optional[float] = None,
        exact_weakening: Optional[bool] = None,
        event_end: Optional[str] = None,
        density: Optional[float] = None,
        a: Optional[float] = None,
        b: Optional[float] = None,
        l_rs: Optional[float] = None,
        f0: Optional[float] = None,
        v0: Optional[float] = None,
        state_law: Optional[str] = None,
        theta0: Optional[float] = None,
        normal_lag: Optional[float] = None,
        normal_lag_length: Optional[float] = None,
        normal_lag_v_star: Optional[float] = None,
        progress: Any = False,
    ) -> DynamicSlideResult:
        """``tribofe slide --dynamics``: the paper's plate-driven block, loaded quasi-statically,
        each instability run in elastodynamics with the drive held (or the whole drive at
        ``drive_velocity``, m/s, with ``x_max`` required). Every ``None`` is the command's
        default, read from the library: ``dc`` (m) the D_c giving the paper scene's kappa =
        0.509 (2.3107e-7 m there), ``h`` (m) the scene's element size refined until the
        cohesive zone spans 3 elements (a given ``h`` that does not is refused), ``cycles`` 1
        ended at the first front crossing (``cycle_end``: ``"crossing"`` or ``"whole-slip"``),
        ``operator`` ``"banded"`` (``"dense"`` with the side push, which banded cannot
        border), ``damping`` (Kelvin-Voigt eta, s) 10 % of critical at the thickness mode,
        ``courant`` 0.9 of the stable step, ``weakening_steps`` 20 (held drive under slip
        weakening only: refused with ``drive_velocity``, which updates the coefficient every
        explicit step), ``exact_weakening`` False (True: the static
        loading follows slip weakening exactly, each onset at its fold, ``--exact-weakening``;
        ~10x slower on the paper's scene, docs/speed.md; refused beside ``weakening_steps``), ``event_end`` ``"energy"`` (a held-mode event
        ends at rest; ``"slip"``: once the state handed back is frozen, ``--event-end slip``,
        docs/speed.md "Event end"; refused with ``drive_velocity``), ``n_force`` 1 N/m, ``max_events`` 50 000,
        ``plate_mass`` and ``plate_inertia`` 0, ``heal`` ``"all"``, ``states`` ``"none"`` (only
        the last interface state kept; ``"all"``: every event's), ``density`` (kg/m^3) the
        scene's, ``law`` the command's ``"coulomb"`` (``defaults()["dynamics.slide"]``; the
        paper's dynamic run is ``law="slip-weakening"``, with ``mu_s``, ``mu_d`` or the paper's
        ``r``, ``g``; ``"coulomb"`` takes ``mu``). ``plate_mass`` (kg/m), ``plate_inertia``
        (kg m^2/m), ``heal`` (``"all"`` or ``"slipped"``). A choice outside its list raises
        :class:`InputError` naming the keyword and the accepted values. ``law="rate-state"``
        (rate-and-state, with ``drive_velocity`` only: the held mode's static phase is
        rate-independent) takes ``a``, ``b``, ``l_rs`` (m) and ``f0``, and optionally ``v0``
        (m/s, default 1e-6), ``state_law`` (``"aging"`` or ``"slip"``) and ``theta0`` (s,
        default ``l_rs / v0``). The base's normal response: ``normal_lag`` (s, Prakash-Clifton
        with a time scale) or ``normal_lag_length`` (m, with a slip length; ``normal_lag_v_star``
        m/s); default instantaneous. Silent unless ``progress`` is True (a tqdm bar; a few
        lines without a terminal) or a callable; the interrupt key stops the run (:class:`KeyboardInterrupt`). A run that
        meets a cap returns what it computed with ``incomplete`` naming the cap, and warns."""
        cb, close = _progress(progress, "slide --dynamics")
        try:
            raw = _dynamic_slide(
                scene if scene is not None else Scene(),
                law,
                mu=mu,
                mu_s=mu_s,
                mu_d=mu_d,
                r=r,
                g=g,
                dc=dc,
                h=h,
                n_force=n_force,
                x_max=x_max,
                cycles=cycles,
                cycle_end=cycle_end,
                max_events=max_events,
                operator=operator,
                states=states,
                keep_states=keep_states,
                damping=damping,
                courant=courant,
                drive_velocity=drive_velocity,
                plate_mass=plate_mass,
                plate_inertia=plate_inertia,
                heal=heal,
                weakening_steps=weakening_steps,
                exact_weakening=exact_weakening,
                event_end=event_end,
                density=density,
                a=a,
                b=b,
                l_rs=l_rs,
                f0=f0,
                v0=v0,
                state_law=state_law,
                theta0=theta0,
                normal_lag=normal_lag,
                normal_lag_length=normal_lag_length,
                normal_lag_v_star=normal_lag_v_star,
                progress=cb,
            )
        finally:
            close()
        if raw["incomplete"]:
            import warnings

            warnings.warn(f"tribofe: the run is incomplete: {raw['incomplete']}", stacklevel=2)
        summary = {k: (v[0] if len(v) else float("nan")) for k, v in raw.pop("summary").items()}
        units = raw["units"]
        for k in ("loading", "events", "dyn_events", "fronts", "advances"):
            if k in raw:
                raw[k] = _table(raw[k], units.get(k))
        return DynamicSlideResult(summary=summary, **raw)

    @staticmethod
    def rupture(
        *,
        scene: Optional[Union[str, "os.PathLike[str]"]] = None,
        s: Optional[float] = None,
        h: Optional[float] = None,
        dc: Optional[float] = None,
        t_end: Optional[float] = None,
        length: Optional[float] = None,
        height: Optional[float] = None,
        mu_s: Optional[float] = None,
        mu_d: Optional[float] = None,
        sigma0: Optional[float] = None,
        young: Optional[float] = None,
        poisson: Optional[float] = None,
        density: Optional[float] = None,
        courant: Optional[float] = None,
        damping: Optional[float] = None,
        contact: Optional[str] = None,
        normal_lag: Optional[float] = None,
        normal_lag_length: Optional[float] = None,
        normal_lag_v_star: Optional[float] = None,
        patch_taper: Optional[float] = None,
        max_steps: Optional[int] = None,
        s_ratio: Optional[float] = None,
        progress: Any = False,
    ) -> RuptureResult:
        """The dynamic-rupture scene on a rigid flat, as ``tribofe rupture``: each keyword is
        the command's flag (``s`` is ``--s``) and None its default (``defaults()["dynamics.rupture"]``:
        the cross-check spec's scene with the normal-stress lag ``normal_lag`` = 1e-3 s;
        ``normal_lag=0`` is the spec's instantaneous normal stress, warned on a rigid flat).
        ``s``: strength ratio S = (mu_s sigma0 - tau0) / (tau0 - mu_d sigma0) (``s_ratio`` is
        its deprecated old name), ``h`` (m), ``dc`` (m), ``t_end`` (s), ``length``, ``height``
        (m), ``mu_s``, ``mu_d``, ``sigma0`` (Pa), ``young`` (Pa), ``poisson``, ``density``
        (kg/m^3), ``courant``, ``damping`` (s), ``contact`` (``"bilateral"``,
        ``"unilateral"``, ``"symmetric"``), ``normal_lag`` (s), ``normal_lag_length`` (m: the
        Prakash-Clifton length form in place of the time form) with ``normal_lag_v_star``
        (m/s, default 0), ``patch_taper`` (m: a cosine
        ramp of the initial shear across the patch edge), ``max_steps`` (most explicit steps;
        a run above it is refused before any work, naming the largest ``t_end`` that fits).
        Silent unless ``progress`` is True (a tqdm bar; a few lines without a terminal) or a
        callable. ``scene``: a rupture scene file (``tribofe rupture --scene``: the block, ``[law]``, ``[interface]`` with
        values piecewise in x and a nucleation patch, ``[rupture]`` with stations), the
        keywords given on top of its keys.

        Returns a :class:`RuptureResult`: per base node ``x_m``, ``t_arrival_s`` (NaN where
        the front never arrived), ``slip_m``, ``peak_slip_rate_m_per_s``, ``rupture_time_s``
        (the first slip rate above ``rate_threshold_m_per_s``; NaN where never)... (``nodes``
        as a table), the force drop, front speed, wave speeds, cohesive-zone size
        ``lambda0_m``, the energy ledger, and ``stations``: per station x (m) the table of
        ``station_x<x>.csv`` (``t_s``, ``slip_m``, ``slip_rate_m_per_s``,
        ``shear_stress_Pa``, ``normal_stress_Pa``)."""
        if s_ratio is not None:
            # The old keyword, kept working: the command names it --s.
            if s is not None:
                raise InputError("s_ratio=: the old name of s=: give s= alone", 2)
            import warnings

            warnings.warn("tribofe.dynamics.rupture: s_ratio= is deprecated, use s= (the command's --s)", DeprecationWarning, stacklevel=2)
            s = s_ratio
        cb, close = _progress(progress, "rupture")
        try:
            raw = _rupture(
                scene=None if scene is None else os.fspath(scene),
                s=s,
                h=h,
                dc=dc,
                t_end=t_end,
                length=length,
                height=height,
                mu_s=mu_s,
                mu_d=mu_d,
                sigma0=sigma0,
                young=young,
                poisson=poisson,
                density=density,
                courant=courant,
                damping=damping,
                contact=contact,
                normal_lag=normal_lag,
                normal_lag_length=normal_lag_length,
                normal_lag_v_star=normal_lag_v_star,
                patch_taper=patch_taper,
                max_steps=max_steps,
                progress=cb,
            )
        finally:
            close()
        return rupture_result(raw)
