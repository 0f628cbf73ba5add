"""Type stubs of the compiled extension (conversions of the tribofe Rust library)."""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

__version__: str

class Scene:
    """The paper's scene (L = 0.4 m, t = 2 mm, E = 2 kPa, nu = 0.4, H = 4 cm, rigid plate,
    1 mm QUA4 mesh) with any key overridden; SI units. Keys: length, thickness (m), young (Pa),
    poisson, height (m), fn_ratios (F/N list), plate ('rigid' | 'elastic'), plate_thickness (m),
    plate_young (Pa), plate_poisson, h (m), grading, h_max (m), n_thick, element, mesh (path of a
    Gmsh file), tol, max_dofs, state ('plane-strain' | 'plane-stress'), width (m, the plate's
    out-of-plane width; plane stress requires it). Validated on construction (InputError, the command's message)."""

    def __init__(
        self,
        *,
        length: float = ...,
        thickness: float = ...,
        young: float = ...,
        poisson: float = ...,
        height: float = ...,
        fn_ratios: Sequence[float] = ...,
        plate: str = ...,
        plate_thickness: float = ...,
        plate_young: float = ...,
        plate_poisson: float = ...,
        h: float = ...,
        grading: float = ...,
        h_max: float = ...,
        n_thick: int = ...,
        element: str = ...,
        mesh: str = ...,
        tol: float = ...,
        max_dofs: int = ...,
        state: str = ...,
        width: float = ...,
    ) -> None: ...
    @staticmethod
    def from_toml(path: str) -> Scene: ...
    def to_toml(self) -> str: ...
    def replace(self, **kwargs: Any) -> Scene: ...
    def estimate_dofs(self) -> float: ...
    @property
    def length(self) -> float: ...
    @property
    def thickness(self) -> float: ...
    @property
    def young(self) -> float: ...
    @property
    def poisson(self) -> float: ...
    @property
    def height(self) -> float: ...
    @property
    def fn_ratios(self) -> List[float]: ...
    @property
    def state(self) -> str: ...
    @property
    def width(self) -> Optional[float]: ...
    @property
    def h(self) -> float: ...
    @property
    def element(self) -> str: ...

def check(scene: Optional[Scene] = None, fields: bool = False) -> Dict[str, Any]: ...
# The reactions per side, their sum, the applied force, the unknowns and the fields; wrapped
# by tribofe.solve as SolveResult.
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
) -> Dict[str, Any]: ...
# A keyword at None takes the library's default (the command's), listed by defaults().
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
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
# sweep, converge: {"table": the library's table as {column: int64 / float64 array or list of
# str}, "units": [(column, unit)...]} (converge also "summary": str); tribofe.sweep and
# tribofe.converge wrap them as SweepResult and ConvergeResult.
def sweep(
    scene: Optional[Scene] = None,
    *,
    length: Union[None, float, Sequence[float], str] = None,
    thickness: Union[None, float, Sequence[float], str] = None,
    height: Union[None, float, Sequence[float], str] = None,
    young: Union[None, float, Sequence[float], str] = None,
    poisson: Union[None, float, Sequence[float], str] = None,
    converged: bool = True,
    friction: Optional[Tuple[float, float]] = None,
    rule: Optional[str] = None,
    cycles: Optional[int] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def converge(
    scene: Optional[Scene] = None,
    *,
    elements: Optional[List[str]] = None,
    families: Optional[List[str]] = None,
    n_thick: Optional[List[int]] = None,
    fn_ratio: Optional[float] = None,
    parallel: bool = True,
    target: Optional[float] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
# {"preslip": {"table", "units"}, "opening": {"table", "units"}}; tribofe.edges wraps it as
# EdgesResult.
def edges(
    scene: Optional[Scene] = None,
    *,
    mu: Optional[List[float]] = None,
    refine: Optional[List[int]] = None,
    mu_s: Optional[float] = None,
    mu_d: Optional[float] = None,
    rule: Optional[str] = None,
    t_over_l: Optional[List[float]] = None,
    open_refine: Optional[List[int]] = None,
    end_grading: Optional[float] = None,
    h_over_l: Optional[List[float]] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
# {"tables": {study: {"table", "units"}}, "summary", ["corners"], "core_s"}; tribofe.stability
# wraps it as StabilityResult.
def stability(
    scene: Optional[Scene] = None,
    study: Optional[List[str]] = None,
    corner_max: Optional[int] = None,
    n_ref: Optional[int] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
# precursors_model, precursors_fe_fig4, precursors_fe_fig5: wrapped by tribofe.precursors as
# ModelResult, FeFig4Result (one FeFig4Run per rule, and summary.csv's table) and
# FeFig5Result.
def precursors_model(r: Optional[float] = None, g: Optional[float] = None, events: Optional[int] = None) -> Dict[str, Any]: ...
def precursors_fe_fig4(
    scene: Optional[Scene] = None, r: Optional[float] = None, g: Optional[float] = None, cycles: Optional[int] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def precursors_fe_fig5(
    scene: Optional[Scene] = None, resolution: Optional[int] = None, rules: Optional[List[str]] = None,
    max_events: Optional[int] = None, progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
# precursors_map, _thin_layer, _heights, _dc, _bonded: {"table": the library's table, "units":
# [(column, unit)...]} (heights and dc also "mu_s", "mu_d"; bonded the comparison's numbers);
# wrapped by tribofe.precursors as NMapResult, SeriesResult and BondedResult.
def precursors_map(resolution: Optional[int] = None) -> Dict[str, Any]: ...
def precursors_thin_layer(
    t_over_l: Sequence[float], scene: Optional[Scene] = None, r: Optional[float] = None, g: Optional[float] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def precursors_heights(
    h_over_l: Sequence[float], scene: Optional[Scene] = None, r: Optional[float] = None, g: Optional[float] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def precursors_dc(
    dc: Sequence[float], scene: Optional[Scene] = None, r: Optional[float] = None, g: Optional[float] = None,
    max_events: Optional[int] = None, progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def precursors_bonded(
    scene: Optional[Scene] = None, r: Optional[float] = None, g: Optional[float] = None, events: Optional[int] = None,
    sweep: bool = False, progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
# The per-node arrays and scalars of a rupture, "energy" a dict, "stations" {x: {"table": ...,
# "units": ...}}; tribofe.dynamics.rupture wraps it as RuptureResult.
def rupture(
    *,
    scene: Optional[str] = None,
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
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def dynamic_slide(
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
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def defaults() -> Dict[str, Dict[str, Any]]: ...
