"""Type stubs of the compiled extension (conversions of the tribofe Rust library)."""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

__version__: str

class Scene:
    """The paper's scene (L = 0.4 m, t = 2 mm, E = 2 kPa, nu = 0.4, H = 4 cm, rigid plate,
    1 mm QUA4 mesh) with any key overridden; SI units. Keys: length, thickness (m), young (Pa),
    poisson, height (m), fn_ratios (F/N list), plate ('rigid' | 'elastic'), plate_thickness (m),
    plate_young (Pa), plate_poisson, h (m), grading, h_max (m), n_thick, element, mesh (path of a
    Gmsh file), tol, max_dofs. Validated on construction (InputError, the command's message)."""

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
    def h(self) -> float: ...
    @property
    def element(self) -> str: ...

def check(scene: Optional[Scene] = None, fields: bool = False) -> Dict[str, Any]: ...
def slide(
    scene: Optional[Scene] = None,
    law: str = "coulomb",
    *,
    mu: Optional[float] = None,
    mu_s: Optional[float] = None,
    mu_d: Optional[float] = None,
    r: Optional[float] = None,
    g: Optional[float] = None,
    rule: str = "paper",
    dc: Optional[float] = None,
    n_force: float = 1.0,
    x_max: Optional[float] = None,
    cycles: int = 10,
    max_events: int = 50000,
    newton: bool = False,
    keep_states: bool = True,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
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
    rule: str = "paper",
    cycles: int = 1,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def converge(
    scene: Optional[Scene] = None,
    *,
    elements: List[str] = ...,
    families: List[str] = ...,
    n_thick: List[int] = ...,
    fn_ratio: float = 0.82,
    parallel: bool = True,
    target: Optional[float] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def precursors_model(r: float = 0.9, g: float = 0.35, events: Optional[int] = None) -> Dict[str, Any]: ...
def precursors_fe_fig4(
    scene: Optional[Scene] = None, r: float = 0.9, g: float = 0.35, cycles: int = 1,
    progress: Optional[Callable[[float], None]] = None,
) -> List[Dict[str, Any]]: ...
def precursors_fe_fig5(
    scene: Optional[Scene] = None, resolution: int = 20, rules: List[str] = ..., max_events: int = 2000,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def rupture(
    *,
    s_ratio: float = 2.0,
    h: float = 1e-3,
    dc: float = 7.7e-7,
    t_end: float = 0.1,
    length: float = 0.2,
    height: float = 0.1,
    mu_s: float = 0.648,
    mu_d: float = 0.583,
    sigma0: float = 2.5,
    young: float = 2000.0,
    poisson: float = 0.4,
    density: float = 1000.0,
    courant: float = 0.5,
    damping: float = 0.0,
    contact: str = "bilateral",
    normal_lag: float = 1e-3,
    patch_taper: float = 0.0,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
def dynamic_slide(
    scene: Optional[Scene] = None,
    law: str = "slip-weakening",
    *,
    mu: Optional[float] = None,
    mu_s: Optional[float] = None,
    mu_d: Optional[float] = None,
    r: Optional[float] = None,
    g: Optional[float] = None,
    dc: Optional[float] = None,
    h: Optional[float] = None,
    n_force: float = 1.0,
    x_max: Optional[float] = None,
    cycles: Optional[int] = None,
    cycle_end: Optional[str] = None,
    max_events: int = 50000,
    operator: Optional[str] = None,
    keep_states: bool = False,
    damping: Optional[float] = None,
    courant: Optional[float] = None,
    drive_velocity: Optional[float] = None,
    plate_mass: float = 0.0,
    plate_inertia: float = 0.0,
    heal: str = "all",
    weakening_steps: Optional[float] = None,
    progress: Optional[Callable[[float], None]] = None,
) -> Dict[str, Any]: ...
