//! The `tribofe._tribofe` extension: conversions between Python and the tribofe library, and
//! nothing else. Every number comes from the Rust library; this layer turns its results into
//! numpy arrays and dicts, its errors into the exception classes of `tribofe.errors` (one per
//! exit status of the command), releases the GIL during the work and turns the interrupt key
//! into a cancellation of the run ([`tribofe::Cancel`]).

use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use tribofe::law::Rule;
use tribofe::scene::{MeshGeometry, Overrides, PlateModel, Scene as RsScene};
use tribofe::{Cancel, Error, Progress, Tick};

/// The library's names of parameters that differ from the Python keyword (the command's
/// flags are renamed by [`keywords`]).
const KEYWORDS: &[(&str, &str)] = &[
    ("N", "n_force"),
    ("x-max", "x_max"),
    ("mu-s", "mu_s"),
    ("mu-d", "mu_d"),
    ("mu-s/mu-d", "mu_s/mu_d"),
    ("--mu-s/--mu-d", "mu_s/mu_d"),
    ("--plate-modulus", "plate_young"),
    ("--plane-stress", "state"),
];

/// A refusal as a Python caller reads it: the parameter by its keyword (`dc=`, `n_force=`),
/// not by the command's flag (`--dc`) or the library's name (`N`). Every flag in the message
/// becomes its keyword (`--x-max` -> `x_max=`); the command's own advice that has no keyword
/// (`--states none`) reads the same way, as the nearest spelling.
fn keywords(e: Error) -> Error {
    let rename = |text: &str| {
        let mut out = String::with_capacity(text.len());
        let mut rest = text;
        while let Some(at) = rest.find("--") {
            out.push_str(&rest[..at]);
            let tail = &rest[at + 2..];
            let len = tail.find(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).unwrap_or(tail.len());
            let flag = &tail[..len];
            if flag.is_empty() || !flag.starts_with(|c: char| c.is_ascii_lowercase()) {
                out.push_str("--");
                rest = tail;
                continue;
            }
            let full = format!("--{flag}");
            let key = KEYWORDS
                .iter()
                .find(|(f, _)| *f == full)
                .map_or(flag.replace('-', "_"), |(_, k)| k.to_string());
            out.push_str(&key);
            out.push('=');
            rest = &tail[len..];
            // A choice's value after its flag (`--operator dense`) is the keyword's string.
            let word = rest
                .strip_prefix(' ')
                .map(|w| &w[..w.find(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).unwrap_or(w.len())]);
            if let Some(value) = word.filter(|w| !w.is_empty() && choice_names(&key).contains(w)) {
                out.push_str(&format!("{value:?}"));
                rest = &rest[1 + value.len()..];
            }
        }
        out.push_str(rest);
        out
    };
    match e {
        Error::Input { what, why } => {
            // A bare name (`dc`, `rule`) or the scene file's `r = 1.5` is the keyword `dc=`,
            // `r=1.5`.
            let ident = |w: &str| {
                w.starts_with(|c: char| c.is_ascii_lowercase())
                    && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            };
            let what = match KEYWORDS.iter().find(|(name, _)| *name == what) {
                Some((_, key)) => format!("{key}="),
                None if ident(&what) => format!("{what}="),
                None => match what.split_once(" = ") {
                    Some((name, value)) if ident(name) => format!("{name}={value}"),
                    _ => rename(&what),
                },
            };
            Error::Input { what, why: rename(&why) }
        }
        e => e,
    }
}

/// The accepted names of a choice keyword (none for another keyword).
fn choice_names(key: &str) -> Vec<&'static str> {
    fn names<T>(t: &[(&'static str, T)]) -> Vec<&'static str> {
        t.iter().map(|(n, _)| *n).collect()
    }
    match key {
        "operator" => names(OPERATORS),
        "states" => names(STATES),
        "cycle_end" => names(CYCLE_ENDS),
        "rule" => names(RULES),
        "residual" => names(RESIDUALS),
        "backslip" => names(BACKSLIPS),
        "heal" => names(HEALS),
        "rig" => names(RIGS),
        "top" => names(TOPS),
        _ => Vec::new(),
    }
}

/// The exception class of `tribofe.errors` for an error of the library.
fn to_py(e: Error) -> PyErr {
    use tribofe::error::exit;
    let e = keywords(e);
    let class = match e.exit_status() {
        exit::INPUT => "InputError",
        exit::NUMERICAL => "NumericalError",
        exit::INTERRUPTED => "Interrupted",
        _ => "OutputError",
    };
    let msg = e.to_string();
    Python::attach(|py| {
        let made = py
            .import("tribofe.errors")
            .and_then(|m| m.getattr(class))
            .and_then(|c| c.call1((msg.clone(), e.exit_status())));
        match made {
            Ok(obj) => PyErr::from_value(obj),
            Err(err) => err,
        }
    })
}

/// Runs `work` without the GIL, on a worker thread, while this (the interpreter's main) thread
/// waits and looks for a pending signal every [`SIGNAL_POLL`]: the interrupt key cancels the run
/// wherever it is (the run checks its token at every solve), whether or not it reports progress.
/// Every progress tick takes the GIL back briefly to give the Python callback the fraction.
/// Returns the result and the wall time of `work` itself (the Rust core), s.
fn run_detached<T: Send>(
    py: Python<'_>,
    progress: Option<Py<PyAny>>,
    work: impl FnOnce(&Cancel, Progress) -> tribofe::Result<T> + Send,
) -> PyResult<(T, f64)> {
    let cancel = Cancel::new();
    let pending: std::sync::Mutex<Option<PyErr>> = std::sync::Mutex::new(None);
    let fail = |err: PyErr| {
        pending.lock().unwrap_or_else(|e| e.into_inner()).get_or_insert(err);
        cancel.cancel();
    };
    let poll = |t: &Tick| {
        if let (Some(cb), Some(frac)) = (&progress, t.fraction) {
            Python::attach(|py| cb.call1(py, (frac,)).map(|_| ()).unwrap_or_else(&fail));
        }
    };
    let result = py.detach(|| {
        std::thread::scope(|s| {
            let (tx, rx) = std::sync::mpsc::channel();
            let (token, poll) = (&cancel, &poll);
            let worker = s.spawn(move || {
                let clock = std::time::Instant::now();
                let r = work(token, Progress::new(poll)).map(|r| (r, clock.elapsed().as_secs_f64()));
                let _ = tx.send(());
                r
            });
            // Signal handlers run on the main thread only: look here until the worker is done.
            while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) = rx.recv_timeout(SIGNAL_POLL) {
                Python::attach(|py| py.check_signals().unwrap_or_else(&fail));
            }
            worker.join()
        })
    });
    if let Some(err) = pending.lock().unwrap_or_else(|e| e.into_inner()).take() {
        return Err(err); // KeyboardInterrupt, or the progress callback's own exception
    }
    // A signal that arrived after the last look still ends the call here.
    py.check_signals()?;
    match result {
        Ok(r) => r.map_err(to_py),
        Err(_) => Err(pyo3::exceptions::PyRuntimeError::new_err(
            "tribofe: the run's worker thread panicked (a bug: please report it)",
        )),
    }
}

/// How often the waiting main thread looks for a signal (the interrupt key's latency).
const SIGNAL_POLL: std::time::Duration = std::time::Duration::from_millis(20);

/// A choice keyword parsed once into the library's value (`accepted`: each name with its
/// value); a wrong value is refused naming the keyword and listing the accepted names.
fn choice<T: Copy>(key: &str, v: Option<&str>, accepted: &[(&str, T)]) -> PyResult<Option<T>> {
    let Some(v) = v else { return Ok(None) };
    match accepted.iter().find(|(name, _)| *name == v) {
        Some(&(_, t)) => Ok(Some(t)),
        None => {
            let names: Vec<String> = accepted.iter().map(|(n, _)| format!("{n:?}")).collect();
            Err(to_py(Error::input(format!("{key}="), format!("{v:?}: give one of {}", names.join(", ")))))
        }
    }
}

/// The library's event operators by name (`--operator`).
const OPERATORS: &[(&str, tribofe::interface::events::Operator)] = &[
    ("dense", tribofe::interface::events::Operator::Dense),
    ("banded", tribofe::interface::events::Operator::Banded),
];
/// `[block] state`: the out-of-plane state (`--plane-stress`).
const PLANE_STATES: &[(&str, tribofe::scene::State)] = &[
    ("plane-strain", tribofe::scene::State::PlaneStrain),
    ("plane-stress", tribofe::scene::State::PlaneStress),
];
/// `rig=`: the loading rig (`[loading] rig`).
const RIGS: &[(&str, tribofe::scene::Rig)] =
    &[("top-plate", tribofe::scene::Rig::TopPlate), ("side-push", tribofe::scene::Rig::SidePush)];
/// `top=`: the side push's normal load on the top face (`[loading] top`).
const TOPS: &[(&str, tribofe::scene::Top)] = &[
    ("uniform-pressure", tribofe::scene::Top::UniformPressure),
    ("sliding-plate", tribofe::scene::Top::SlidingPlate),
];
/// `--states`: whether every event's state is kept.
const STATES: &[(&str, bool)] = &[("all", true), ("none", false)];
/// `--cycle-end`: whether a front crossing also ends a cycle.
const CYCLE_ENDS: &[(&str, bool)] = &[("whole-slip", false), ("crossing", true)];
/// The static-kinetic rules and the paper rule's conventions.
const RULES: &[(&str, Rule)] = &[("paper", Rule::Paper), ("overdamped", Rule::Overdamped)];
const RESIDUALS: &[(&str, tribofe::law::Residual)] =
    &[("relaxed", tribofe::law::Residual::Relaxed), ("pre-event", tribofe::law::Residual::PreEvent)];
const BACKSLIPS: &[(&str, bool)] = &[("allowed", true), ("forbidden", false)];
/// `--heal`: whether only the nodes that slipped heal.
const HEALS: &[(&str, bool)] = &[("all", false), ("slipped", true)];

/// The name of `value` among `accepted` (a default shown by [`defaults`]).
fn name_of<T: PartialEq>(accepted: &[(&'static str, T)], value: T) -> &'static str {
    accepted.iter().find(|(_, t)| *t == value).map_or("", |(n, _)| n)
}

fn f64_arg(v: &Bound<'_, PyAny>, key: &str) -> PyResult<f64> {
    v.extract::<f64>().map_err(|_| PyTypeError::new_err(format!("{key}: expected a number (SI units)")))
}

/// The paper's scene with overrides; every keyword is a scene key in SI units.
#[pyclass(module = "tribofe._tribofe", name = "Scene", frozen)]
struct Scene {
    inner: RsScene,
}

const SCENE_KEYS: &str = "length, thickness, young, poisson, height, fn_ratios, plate, plate_thickness, \
plate_young, plate_poisson, h, grading, h_max, n_thick, element, mesh, geometry, tol, max_dofs, state, width, \
rig, push_height, push_width, push_stiffness, top";

fn overrides(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Overrides> {
    let mut o = Overrides::default();
    let Some(kw) = kwargs else { return Ok(o) };
    for (k, v) in kw.iter() {
        let key: String = k.extract()?;
        let f = |v: &Bound<'_, PyAny>| f64_arg(v, &key).map(Some);
        match key.as_str() {
            "length" => o.length = f(&v)?,
            "thickness" => o.thickness = f(&v)?,
            "young" => o.young = f(&v)?,
            "poisson" => o.poisson = f(&v)?,
            "height" => o.height = f(&v)?,
            "plate_thickness" => o.plate_thickness = f(&v)?,
            "plate_young" => o.plate_young = f(&v)?,
            "plate_poisson" => o.plate_poisson = f(&v)?,
            "h" => o.h = f(&v)?,
            "grading" => o.grading = f(&v)?,
            "h_max" => o.h_max = f(&v)?,
            "tol" => o.tol = f(&v)?,
            "width" => o.width = f(&v)?,
            "push_height" => o.push_height = f(&v)?,
            "push_width" => o.push_width = f(&v)?,
            "push_stiffness" => o.push_stiffness = f(&v)?,
            "rig" => o.rig = choice("rig", Some(&v.extract::<String>()?), RIGS)?,
            "top" => o.top = choice("top", Some(&v.extract::<String>()?), TOPS)?,
            "state" => o.state = choice("state", Some(&v.extract::<String>()?), PLANE_STATES)?,
            "fn_ratios" => {
                o.fn_ratios = Some(
                    v.extract().map_err(|_| PyTypeError::new_err("fn_ratios: expected a list of numbers"))?,
                )
            }
            "n_thick" => {
                o.n_thick =
                    Some(v.extract().map_err(|_| PyTypeError::new_err("n_thick: expected a whole number"))?)
            }
            "max_dofs" => {
                o.max_dofs =
                    Some(v.extract().map_err(|_| PyTypeError::new_err("max_dofs: expected a whole number"))?)
            }
            "element" => o.element = Some(v.extract()?),
            "mesh" => o.mesh = Some(PathBuf::from(v.str()?.to_string())),
            "geometry" => {
                let s: String = v.extract()?;
                o.geometry = Some(match s.as_str() {
                    "block" => MeshGeometry::Block,
                    "file" => MeshGeometry::File,
                    _ => {
                        return Err(to_py(Error::input(
                            "geometry",
                            format!("'{}': use block or file", tribofe::error::quote(&s)),
                        )))
                    }
                })
            }
            "plate" => {
                let s: String = v.extract()?;
                o.plate = Some(match s.as_str() {
                    "rigid" => PlateModel::Rigid,
                    "elastic" => PlateModel::Elastic,
                    _ => {
                        return Err(to_py(Error::input(
                            "plate",
                            format!("'{}': use rigid or elastic", tribofe::error::quote(&s)),
                        )))
                    }
                })
            }
            other => {
                return Err(to_py(Error::input(
                    tribofe::error::quote(other),
                    format!("not a scene key; the keys are {SCENE_KEYS}"),
                )))
            }
        }
    }
    Ok(o)
}

#[pymethods]
impl Scene {
    #[new]
    #[pyo3(signature = (**kwargs))]
    fn new(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        let o = overrides(kwargs)?;
        Ok(Scene { inner: RsScene::default().apply(&o).map_err(to_py)? })
    }

    /// Reads a scene file (TOML; every key defaults to the paper's value).
    #[staticmethod]
    fn from_toml(path: PathBuf) -> PyResult<Scene> {
        Ok(Scene { inner: RsScene::from_file(&path).map_err(to_py)? })
    }

    /// The scene as TOML text (every key), a template to edit.
    fn to_toml(&self) -> PyResult<String> {
        self.inner.to_toml().map_err(to_py)
    }

    /// The same scene with some keys changed (validated like the constructor).
    #[pyo3(signature = (**kwargs))]
    fn replace(&self, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        let o = overrides(kwargs)?;
        Ok(Scene { inner: self.inner.apply(&o).map_err(to_py)? })
    }

    #[getter]
    fn length(&self) -> f64 {
        self.inner.block.length
    }
    #[getter]
    fn thickness(&self) -> f64 {
        self.inner.block.thickness
    }
    #[getter]
    fn young(&self) -> f64 {
        self.inner.block.young
    }
    #[getter]
    fn poisson(&self) -> f64 {
        self.inner.block.poisson
    }
    #[getter]
    fn height(&self) -> f64 {
        self.inner.loading.height
    }
    #[getter]
    fn fn_ratios(&self) -> Vec<f64> {
        self.inner.loading.fn_ratios.clone()
    }
    #[getter]
    fn state(&self) -> &'static str {
        self.inner.block.state.name()
    }
    #[getter]
    fn width(&self) -> Option<f64> {
        self.inner.block.width
    }
    #[getter]
    fn h(&self) -> f64 {
        self.inner.mesh.h
    }
    #[getter]
    fn element(&self) -> String {
        self.inner.mesh.element.clone()
    }

    /// Estimated number of unknowns of the scene's mesh.
    fn estimate_dofs(&self) -> PyResult<f64> {
        self.inner.estimate_dofs().map_err(to_py)
    }

    fn __repr__(&self) -> String {
        let s = &self.inner;
        let mesh = match &s.mesh.file {
            Some(f) => format!("mesh={:?}", f.display().to_string()),
            None => format!("h={} m, element={:?}", s.mesh.h, s.mesh.element),
        };
        format!(
            "Scene(L={} m, t={} m, E={} Pa, nu={}, H={} m, plate={:?}, F/N={:?}, {mesh})",
            s.block.length,
            s.block.thickness,
            s.block.young,
            s.block.poisson,
            s.loading.height,
            format!("{:?}", s.plate.model).to_lowercase(),
            s.loading.fn_ratios
        )
    }

    fn __eq__(&self, other: &Scene) -> bool {
        self.inner == other.inner
    }
}

fn arr<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

/// The paper's bonded check; returns a dict: `cases` (one dict per F/N with numpy profiles,
/// stresses in units of the mean pressure N/L) and `summary` (numbers of the run).
/// With `fields`, also the whole block: node coordinates (n x 2, m), and per case the
/// displacement (n x 2, m) and the nodal stresses (n x 4: sigma_xx, sigma_yy, sigma_xy,
/// sigma_zz, Pa; extrapolated from the integration points and averaged).
#[pyfunction]
#[pyo3(signature = (scene=None, fields=false))]
fn check<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    fields: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    let opts = tribofe::linalg::solve::SolverOptions::default();
    let ((res, sm), core_s) = run_detached(py, None, |cancel, _| {
        cancel.check()?;
        let r = tribofe::studies::check::run(&scene, &opts)?;
        r.0.self_check()?;
        Ok(r)
    })?;
    let out = PyDict::new(py);
    let cases = PyList::empty(py);
    for c in &res.cases {
        let d = PyDict::new(py);
        d.set_item("fn_ratio", c.fn_ratio)?;
        d.set_item("N_N_per_m", c.n)?;
        d.set_item("F_N_per_m", c.f)?;
        d.set_item("tilt_rad", c.tilt)?;
        d.set_item("x_over_L", arr(py, &c.x_over_l))?;
        d.set_item("p_over_pmean", arr(py, &c.p))?;
        d.set_item("tau_over_pmean", arr(py, &c.tau))?;
        d.set_item("p_model", arr(py, &c.p_model))?;
        d.set_item("tau_model", arr(py, &c.tau_model))?;
        d.set_item("p_extrap", arr(py, &c.p_extrap))?;
        d.set_item("tau_extrap", arr(py, &c.tau_extrap))?;
        d.set_item("p_corrected", arr(py, &c.p_corrected))?;
        let m = &c.metrics;
        let md = PyDict::new(py);
        md.set_item("slope_interior", m.slope_interior)?;
        md.set_item("slope_model", m.slope_model)?;
        md.set_item("slope_corrected", m.slope_corrected)?;
        md.set_item("interior_dev_p", m.interior_dev_p)?;
        md.set_item("interior_dev_tau", m.interior_dev_tau)?;
        md.set_item("tau_center", m.tau_center)?;
        md.set_item("edge_p_over_t", m.edge_p_t.to_vec())?;
        md.set_item("edge_tau_over_t", m.edge_tau_t.to_vec())?;
        md.set_item("balance_n", m.balance_n)?;
        md.set_item("balance_f", m.balance_f)?;
        md.set_item("balance_moment", m.balance_moment)?;
        d.set_item("metrics", md)?;
        cases.append(d)?;
    }
    out.set_item("cases", cases)?;
    out.set_item("n_nodes", res.n_nodes)?;
    out.set_item("n_elements", res.n_elements)?;
    out.set_item("balance_error", res.balance_error())?;
    out.set_item("core_s", core_s)?;
    if fields {
        let model = sm.model();
        let grid = |rows: Vec<Vec<f64>>| {
            PyArray2::from_vec2(py, &rows).map_err(|e| PyTypeError::new_err(e.to_string()))
        };
        let f = PyDict::new(py);
        f.set_item("nodes_m", grid(sm.mesh.nodes.iter().map(|p| p.to_vec()).collect())?)?;
        let (mut disp, mut stress) = (Vec::new(), Vec::new());
        for u in &res.displacements {
            // The block's node DOFs come first (a rigid plate's three unknowns follow).
            disp.push(grid(u[..2 * sm.mesh.nodes.len()].chunks(2).map(|c| c.to_vec()).collect())?);
            let s = tribofe::fem::recovery::nodal_stresses(&model, u);
            stress.push(grid(s.iter().map(|v| v.to_vec()).collect())?);
        }
        f.set_item("displacement_m", disp)?;
        f.set_item("stress_Pa", stress)?;
        out.set_item("fields", f)?;
    }
    Ok(out)
}

/// `tribofe solve`: the rectangle [0, lx] x [0, ly] (m) of nx x ny elements in plane strain
/// (young Pa, poisson), one condition per side (`bottom`, `right`, `top`, `left`: "free",
/// "clamped", "roller", "u=UX,UY" in m or "t=TX,TY" in Pa). Returns the reactions per side
/// and their sum (N per metre of width), the applied traction force, the unknowns, and the
/// fields: node coordinates (n x 2, m), displacement (n x 2, m), nodal stresses (n x 4:
/// sigma_xx, sigma_yy, sigma_xy, sigma_zz, Pa). None is the command's default.
#[pyfunction]
#[pyo3(signature = (*, lx=None, ly=None, nx=None, ny=None, element=None, young=None, poisson=None,
    bottom=None, right=None, top=None, left=None, max_dofs=None))]
#[allow(clippy::too_many_arguments)]
fn solve<'py>(
    py: Python<'py>,
    lx: Option<f64>,
    ly: Option<f64>,
    nx: Option<usize>,
    ny: Option<usize>,
    element: Option<&str>,
    young: Option<f64>,
    poisson: Option<f64>,
    bottom: Option<&str>,
    right: Option<&str>,
    top: Option<&str>,
    left: Option<&str>,
    max_dofs: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::scene::rectangle as rect;
    let d = rect::DEFAULT_SIDES;
    let p = rect::RectangleProblem::from_inputs(
        lx.unwrap_or(rect::DEFAULT_LX),
        ly.unwrap_or(rect::DEFAULT_LY),
        nx.unwrap_or(rect::DEFAULT_NX),
        ny.unwrap_or(rect::DEFAULT_NY),
        element.unwrap_or(rect::DEFAULT_ELEMENT),
        young.unwrap_or(rect::DEFAULT_YOUNG),
        poisson.unwrap_or(rect::DEFAULT_POISSON),
        [bottom.unwrap_or(d[0]), right.unwrap_or(d[1]), top.unwrap_or(d[2]), left.unwrap_or(d[3])],
    )
    .map_err(to_py)?;
    p.check_size(max_dofs).map_err(to_py)?;
    let (r, core_s) = run_detached(py, None, |cancel, _| {
        cancel.check()?;
        p.solve()
    })?;
    let model = tribofe::fem::assembly::Model {
        tech: p.element.tech,
        ..tribofe::fem::assembly::Model::new(&r.mesh, p.material)
    };
    let grid =
        |rows: Vec<Vec<f64>>| PyArray2::from_vec2(py, &rows).map_err(|e| PyTypeError::new_err(e.to_string()));
    let u = &r.solution.u[0];
    let n = r.mesh.nodes.len();
    let out = PyDict::new(py);
    let reactions = PyDict::new(py);
    for (name, f) in rect::SIDES.iter().zip(&r.side_reactions) {
        reactions.set_item(*name, (f[0], f[1]))?;
    }
    out.set_item("reactions_N_per_m", reactions)?;
    out.set_item("total_reaction_N_per_m", (r.total_reaction[0], r.total_reaction[1]))?;
    out.set_item("applied_N_per_m", (r.applied[0], r.applied[1]))?;
    out.set_item("unknowns", r.solution.stats.n_unknowns)?;
    out.set_item("nodes_m", grid(r.mesh.nodes.iter().map(|q| q.to_vec()).collect())?)?;
    out.set_item("displacement_m", grid(u[..2 * n].chunks(2).map(|c| c.to_vec()).collect())?)?;
    let stress = tribofe::fem::recovery::nodal_stresses(&model, u);
    out.set_item("stress_Pa", grid(stress.iter().map(|v| v.to_vec()).collect())?)?;
    out.set_item("core_s", core_s)?;
    Ok(out)
}

/// `tribofe edges`: the block's ends on the frictional interface, pre-slip under N alone
/// against refinement (coulomb `mu`, `refine` elements through t) and the trailing end's
/// opening under the drive against the first precursor (static-kinetic `mu_s`, `mu_d`,
/// `rule`, over `t_over_l` x `open_refine` x `h_over_l`), meshes graded from the ends by
/// `end_grading`: preslip.csv's and opening.csv's tables (the library's), with their units.
#[pyfunction]
#[pyo3(signature = (scene=None, *, mu=None, refine=None, mu_s=None, mu_d=None, rule=None, t_over_l=None,
    open_refine=None, end_grading=None, h_over_l=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn edges<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    mu: Option<Vec<f64>>,
    refine: Option<Vec<usize>>,
    mu_s: Option<f64>,
    mu_d: Option<f64>,
    rule: Option<&str>,
    t_over_l: Option<Vec<f64>>,
    open_refine: Option<Vec<usize>>,
    end_grading: Option<f64>,
    h_over_l: Option<Vec<f64>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::edges as ed;
    let base = ed::EdgesOptions::default();
    let o = ed::EdgesOptions {
        mu: mu.unwrap_or(base.mu),
        refine: refine.unwrap_or(base.refine),
        mu_s: mu_s.unwrap_or(base.mu_s),
        mu_d: mu_d.unwrap_or(base.mu_d),
        rule: choice("rule", rule, RULES)?.unwrap_or(base.rule),
        t_over_l: t_over_l.unwrap_or(base.t_over_l),
        open_refine: open_refine.unwrap_or(base.open_refine),
        h_over_l: h_over_l.unwrap_or(base.h_over_l),
        end_grading: end_grading.unwrap_or(base.end_grading),
    };
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    refuse_scene_keys(
        &scene,
        &["h", "grading", "h_max", "n_thick", "height", "fn_ratios", "tol", "geometry"],
        "edges builds its own meshes: refine= (pre-slip) and t_over_l= (h = t/2), the heights from h_over_l=",
    )?;
    o.check(&scene).map_err(to_py)?;
    let ((pre, open), _) = run_detached(py, progress, |cancel, poll| ed::run(&scene, &o, cancel, poll))?;
    let out = PyDict::new(py);
    out.set_item("preslip", table_with_units(py, &tribofe::report::edges::preslip_table(&pre))?)?;
    out.set_item("opening", table_with_units(py, &tribofe::report::edges::opening_table(&open))?)?;
    Ok(out)
}

/// The frictional interface under N then the drive X at height H, event by event (`tribofe
/// slide`: every option of it but the files'; a choice is parsed here into the library's
/// value, refused with the accepted names).
#[pyfunction]
#[pyo3(signature = (scene=None, law=None, *, mu=None, mu_s=None, mu_d=None, r=None, g=None,
    rule=None, residual=None, backslip=None, dc=None, n_force=None, x_max=None, cycles=None,
    cycle_end=None, max_events=None, newton=false, operator=None, states=None, keep_states=None,
    progress=None))]
#[allow(clippy::too_many_arguments)]
fn slide<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    law: Option<&str>,
    mu: Option<f64>,
    mu_s: Option<f64>,
    mu_d: Option<f64>,
    r: Option<f64>,
    g: Option<f64>,
    rule: Option<&str>,
    residual: Option<&str>,
    backslip: Option<&str>,
    dc: Option<f64>,
    n_force: Option<f64>,
    x_max: Option<f64>,
    cycles: Option<usize>,
    cycle_end: Option<&str>,
    max_events: Option<usize>,
    newton: bool,
    operator: Option<&str>,
    states: Option<&str>,
    keep_states: Option<bool>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::slide as sl;
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    let (n_force, cycles) = (n_force.unwrap_or(sl::DEFAULT_N_FORCE), cycles.unwrap_or(sl::DEFAULT_CYCLES));
    let max_events = max_events.unwrap_or(sl::DEFAULT_MAX_EVENTS);
    let rule = choice("rule", rule, RULES)?;
    let rule_given = rule.is_some();
    let rule = rule.unwrap_or(sl::DEFAULT_RULE.parse().map_err(to_py)?);
    let paper = tribofe::law::PaperOptions {
        residual: choice("residual", residual, RESIDUALS)?
            .unwrap_or(tribofe::law::PaperOptions::default().residual),
        backslip: choice("backslip", backslip, BACKSLIPS)?
            .unwrap_or(tribofe::law::PaperOptions::default().backslip),
    };
    let law_given = law.is_some();
    let choice_law = sl::LawChoice {
        law: law.unwrap_or(sl::DEFAULT_LAW).to_string(),
        mu,
        mu_s,
        mu_d,
        r,
        g,
        rule: name_of(RULES, rule).to_string(),
        dc,
        ..Default::default()
    }
    .with_scene(&scene.law, law_given, rule_given);
    choice_law.check_rule_options(rule_given, residual.is_some(), backslip.is_some()).map_err(to_py)?;
    let law = choice_law.law(&scene).and_then(|l| l.with_paper_options(paper)).map_err(to_py)?;
    if newton && !law.weakens() {
        return Err(to_py(Error::input("newton", "newton cannot act without law='slip-weakening'")));
    }
    let keep_states = match (choice("states", states, STATES)?, keep_states) {
        (Some(_), Some(_)) => {
            return Err(to_py(Error::input("keep_states", "the old spelling of states=: give states= alone")))
        }
        (Some(k), None) | (None, Some(k)) => k,
        (None, None) => true,
    };
    let base = sl::SlideOptions::default();
    let o = sl::SlideOptions {
        law,
        n_force,
        x_max,
        cycles,
        end_at_crossing: choice("cycle_end", cycle_end, CYCLE_ENDS)?.unwrap_or(base.end_at_crossing),
        max_events,
        newton,
        keep_states,
        // The command's rule: by the interface's size.
        operator: choice("operator", operator, OPERATORS)?
            .unwrap_or_else(|| tribofe::interface::events::Operator::for_scene(&scene)),
        ..Default::default()
    };
    sl::check_options(&scene, &o).map_err(to_py)?;
    let (res, core_s) = run_detached(py, progress, |cancel, poll| {
        let o = sl::SlideOptions { cancel: cancel.clone(), ..o };
        sl::run(&scene, &o, poll)
    })?;
    let out = slide_result(py, &res)?;
    out.set_item("core_s", core_s)?;
    Ok(out)
}

fn slide_result<'py>(
    py: Python<'py>,
    res: &tribofe::studies::slide::SlideResult,
) -> PyResult<Bound<'py, PyDict>> {
    let run = &res.run;
    let c = &res.condensed;
    // loading.csv's and events.csv's tables (report::table), every column, with their units.
    use tribofe::report::slide as rs;
    let (loading, events) = (rs::loading_table(res), rs::events_table(res));
    let out = PyDict::new(py);
    out.set_item("law", res.options.law.name())?;
    out.set_item("mu_s", res.options.law.mu_s())?;
    out.set_item("mu_d", res.options.law.mu_d())?;
    out.set_item("n_force_N_per_m", res.options.n_force)?;
    out.set_item("x_over_L", arr(py, &c.x.iter().map(|x| x / c.l).collect::<Vec<_>>()))?;
    out.set_item("width_m", arr(py, &c.w))?;
    out.set_item("loading", table(py, &loading)?)?;
    let units = PyDict::new(py);
    units.set_item("loading", table_units(&loading))?;
    units.set_item("events", table_units(&events))?;
    out.set_item("units", units)?;
    // The drive phase as the paper's fig. 4: (F^c, F) / (mu_s N), each instability a drop.
    let (fc, f): (Vec<f64>, Vec<f64>) = tribofe::report::slide::fe_curve(res).into_iter().unzip();
    out.set_item("curve_Fc_over_mu_s_N", arr(py, &fc))?;
    out.set_item("curve_F_over_mu_s_N", arr(py, &f))?;
    out.set_item("events", table(py, &events)?)?;
    out.set_item("sliding_events", run.sliding_events)?;
    out.set_item("max_violation", run.max_violation)?;
    out.set_item("condense_s", res.condense_s)?;
    out.set_item("events_s", res.events_s)?;
    // Interface states as (states x nodes) arrays from the library's struct-of-arrays
    // accessor: forces per node in N/m, slip and gap in m, state codes 0 stick, 1 slip, 2 open.
    use tribofe::studies::slide::StateField;
    let grid = |f: StateField| -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (v, shape) = res.field(f);
        numpy::PyArray1::from_vec(py, v).reshape(shape)
    };
    let states = PyDict::new(py);
    states.set_item("p_force_N_per_m", grid(StateField::NormalForce)?)?;
    states.set_item("t_force_N_per_m", grid(StateField::TangentialForce)?)?;
    states.set_item("slip_m", grid(StateField::Slip)?)?;
    states.set_item("gap_m", grid(StateField::Gap)?)?;
    states.set_item("contact_area_over_A0", grid(StateField::ContactAreaOverA0)?)?;
    // The codes are integers (0, 1, 2), as in states.csv.
    let (codes, shape) = res.field(StateField::Code);
    let codes: Vec<i64> = codes.iter().map(|&c| c as i64).collect();
    states.set_item("state_code", PyArray1::from_vec(py, codes).reshape(shape)?)?;
    out.set_item("states", states)?;
    Ok(out)
}

/// A library table as a dict of columns, in its order: int64 and float64 arrays (NaN where
/// the CSV cell is empty), lists of strings; a count that may be missing as [`maybe_ints`].
fn table<'py>(py: Python<'py>, t: &tribofe::report::table::Table) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::report::table::Values;
    let out = PyDict::new(py);
    for c in &t.columns {
        match &c.values {
            Values::Int(v) => out.set_item(&c.name, PyArray1::from_slice(py, v))?,
            Values::MaybeInt(v) => out.set_item(&c.name, maybe_ints(py, v))?,
            Values::Float(v) => out.set_item(&c.name, arr(py, v))?,
            Values::Text(v) => out.set_item(&c.name, v)?,
        }
    }
    Ok(out)
}

/// Counts that may be missing: int64 when every row has one, else float64 with NaN where
/// one is missing (pandas' convention for an integer column with gaps).
fn maybe_ints<'py>(py: Python<'py>, v: &[Option<i64>]) -> Bound<'py, PyAny> {
    match v.iter().copied().collect::<Option<Vec<i64>>>() {
        Some(v) => PyArray1::from_vec(py, v).into_any(),
        None => arr(py, &v.iter().map(|i| i.map_or(f64::NAN, |i| i as f64)).collect::<Vec<_>>()).into_any(),
    }
}

/// A library table as `{"table": columns, "units": [(column, unit)...]}`.
fn table_with_units<'py>(py: Python<'py>, t: &tribofe::report::table::Table) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("table", table(py, t)?)?;
    out.set_item("units", table_units(t))?;
    Ok(out)
}

/// A library table's units as (column, unit) pairs, in its order.
fn table_units(t: &tribofe::report::table::Table) -> Vec<(&str, &'static str)> {
    t.columns.iter().map(|c| (c.name.as_ref(), c.unit)).collect()
}

/// The paper's analytic event iteration for (r, g): n, F_1 and F_max, `events`, events.csv's
/// table (the library's: `tribofe::report::precursors::events_table`), with its units, and
/// the fig. 4 curve (loading.csv's columns).
#[pyfunction]
#[pyo3(signature = (r=None, g=None, events=None))]
fn precursors_model<'py>(
    py: Python<'py>,
    r: Option<f64>,
    g: Option<f64>,
    events: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::precursors as pm;
    use tribofe::report::precursors as rp;
    let (r, g) = (r.unwrap_or(pm::PAPER_R), g.unwrap_or(pm::PAPER_G));
    let p = pm::Params::new(r, g).map_err(to_py)?;
    let n = pm::n_precursors(&p).map_err(to_py)?;
    let count = events.unwrap_or(n + 1);
    // The command's cap on --events.
    pm::check_events(count).map_err(to_py)?;
    let ev = pm::simulate(&p, count);
    let out = PyDict::new(py);
    out.set_item("r", r)?;
    out.set_item("g", g)?;
    out.set_item("n", n)?;
    out.set_item("F_1", p.f1())?;
    out.set_item("F_max", pm::f_max(&p))?;
    let events = rp::events_table(&ev);
    out.set_item("events", table_with_units(py, &events)?)?;
    // The loading curve of the paper's fig. 4 (loading.csv): (F^c, F) / (mu_s N) with each
    // event's drop.
    out.set_item("curve", table(py, &rp::loading_table(&pm::loading_curve(&ev)))?)?;
    Ok(out)
}

/// One swept parameter: a list of numbers, or the command's text form (`a,b,c`, `a:b:n`,
/// `a:b:ng`).
fn axis_values(key: &str, v: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if let Ok(text) = v.extract::<String>() {
        return tribofe::studies::sweep::parse_values(&text).map_err(to_py);
    }
    if let Ok(x) = v.extract::<f64>() {
        return Ok(vec![x]);
    }
    v.extract::<Vec<f64>>()
        .map_err(|_| PyTypeError::new_err(format!("{key}: expected a number, a list of numbers or 'a:b:n'")))
}

/// The bonded check over the product of the given parameter values; returns `sweep.csv`'s
/// table, the library's ([`tribofe::report::sweep::table`]), with its units.
#[pyfunction]
#[pyo3(signature = (scene=None, *, length=None, thickness=None, height=None, young=None, poisson=None,
    converged=true, friction=None, rule=None, cycles=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn sweep<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    length: Option<Bound<'py, PyAny>>,
    thickness: Option<Bound<'py, PyAny>>,
    height: Option<Bound<'py, PyAny>>,
    young: Option<Bound<'py, PyAny>>,
    poisson: Option<Bound<'py, PyAny>>,
    converged: bool,
    friction: Option<(f64, f64)>,
    rule: Option<&str>,
    cycles: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::sweep::{self as sw, Axis, Param};
    sw::check_friction_settings(
        friction.is_some(),
        &[("rule=", rule.is_some()), ("cycles=", cycles.is_some())],
    )
    .map_err(to_py)?;
    let rule =
        choice("rule", rule, RULES)?.unwrap_or(tribofe::studies::slide::DEFAULT_RULE.parse().map_err(to_py)?);
    let cycles = cycles.unwrap_or(sw::DEFAULT_FRICTION_CYCLES);
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    let mut axes = Vec::new();
    for (param, v) in [
        (Param::Length, length),
        (Param::Thickness, thickness),
        (Param::Height, height),
        (Param::Young, young),
        (Param::Poisson, poisson),
    ] {
        if let Some(v) = v {
            axes.push(Axis { param, values: axis_values(param.flag(), &v)? });
        }
    }
    let friction = friction.map(|(mu_s, mu_d)| sw::FrictionSweep { mu_s, mu_d, rule, cycles });
    let (points, _) = run_detached(py, progress, |cancel, poll| {
        let o = sw::SweepOptions { converged, friction, cancel: cancel.clone(), ..Default::default() };
        let forward = poll.forward::<sw::Point>();
        sw::run(&scene, &axes, &o, Progress::new(&forward))
    })?;
    table_with_units(py, &tribofe::report::sweep::table(&points).map_err(to_py)?)
}

/// Mesh and element convergence of the check; returns `convergence.csv`'s table, the
/// library's ([`tribofe::report::convergence::table`]), with its units and the printed
/// summary under `"summary"`.
#[pyfunction]
#[pyo3(signature = (scene=None, *, elements=None, families=None, n_thick=None, fn_ratio=None, parallel=true,
    target=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn converge<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    elements: Option<Vec<String>>,
    families: Option<Vec<String>>,
    n_thick: Option<Vec<usize>>,
    fn_ratio: Option<f64>,
    parallel: bool,
    target: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::convergence as cv;
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    let base = cv::StudyOptions::default();
    let families = match families {
        Some(f) => {
            f.iter().map(|f| f.parse()).collect::<tribofe::Result<Vec<cv::Family>>>().map_err(to_py)?
        }
        None => base.families.clone(),
    };
    let elements = elements.unwrap_or_else(|| base.elements.clone());
    let n_thick = n_thick.unwrap_or_else(|| base.n_thick.clone());
    let fn_ratio = fn_ratio.unwrap_or(base.fn_ratio);
    let (study, _) = run_detached(py, progress, |cancel, poll| {
        let o = cv::StudyOptions {
            elements,
            families,
            n_thick,
            fn_ratio,
            parallel,
            cancel: cancel.clone(),
            ..Default::default()
        };
        let forward = poll.forward::<cv::Run>();
        cv::study(&scene, &o, Progress::new(&forward))
    })?;
    let out = table_with_units(py, &tribofe::report::convergence::table(&study))?;
    out.set_item("summary", tribofe::report::convergence::summary(&study, target))?;
    Ok(out)
}

fn comparison<'py>(
    py: Python<'py>,
    c: &tribofe::studies::slide::PaperComparison,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("r", c.r)?;
    d.set_item("g", c.g)?;
    d.set_item("n_model", c.n)?;
    d.set_item("F_1_model", c.f1)?;
    d.set_item("x_1_model", c.x1)?;
    d.set_item("F_max_model", c.f_max)?;
    d.set_item("n_fe", c.n_fe)?;
    d.set_item("n_fe_long", c.n_fe_long)?;
    d.set_item("n_fe_advancing", c.n_fe_advancing)?;
    d.set_item("F_1_fe", c.f1_fe)?;
    d.set_item("x_1_fe", c.x1_fe)?;
    d.set_item("F_max_fe", c.f_max_fe)?;
    d.set_item("definition", tribofe::precursors::definition::DEFINITION)?;
    d.set_item("n_front", c.n_front)?;
    d.set_item("F_1_front", c.f1_front)?;
    d.set_item("x_1_front", c.x1_front)?;
    d.set_item("front_definition", tribofe::precursors::definition::ADVANCES)?;
    Ok(d)
}

/// The paper's fig. 4 from the frictional FE: `runs`, one dict per static-kinetic rule (paper,
/// overdamped): the comparison with the model (forces in units of mu_s N, x in units of L),
/// the precursors' arrest positions, the peaks, and the whole run as `slide` returns it; and
/// `summary`, summary.csv's table (the library's, with its units).
#[pyfunction]
#[pyo3(signature = (scene=None, r=None, g=None, cycles=None, progress=None))]
fn precursors_fe_fig4<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    r: Option<f64>,
    g: Option<f64>,
    cycles: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    refuse_scene_keys(&scene, FE_UNUSED, FE_WHY)?;
    let (r, g) = (r.unwrap_or(tribofe::precursors::PAPER_R), g.unwrap_or(tribofe::precursors::PAPER_G));
    let cycles = cycles.unwrap_or(tribofe::studies::precursors_fe::DEFAULT_FIG4_CYCLES);
    let (runs, _) = run_detached(py, progress, |cancel, poll| {
        tribofe::studies::precursors_fe::fig4(&scene, r, g, cycles, cancel, poll)
    })?;
    let p = tribofe::precursors::Params::new(r, g).map_err(to_py)?;
    let summary = tribofe::report::precursors::fe_fig4_summary_table(&p, &runs).map_err(to_py)?;
    let list = PyList::empty(py);
    for run in runs {
        let f = run.map_err(to_py)?;
        let d = PyDict::new(py);
        d.set_item("rule", f.rule.name())?;
        d.set_item("comparison", comparison(py, &f.cmp)?)?;
        d.set_item("x_arrest_fe_over_L", arr(py, &f.x_fe))?;
        d.set_item("x_arrest_model_over_L", arr(py, &f.x_model))?;
        d.set_item("peaks_over_mu_s_N", arr(py, &f.peaks))?;
        d.set_item("worst_violation", f.worst_violation)?;
        d.set_item("run", slide_result(py, &f.run)?)?;
        list.append(d)?;
    }
    let out = PyDict::new(py);
    out.set_item("runs", list)?;
    out.set_item("summary", table_with_units(py, &summary)?)?;
    Ok(out)
}

/// The paper's fig. 5 from the frictional FE: fig5_fe.csv's table (the library's,
/// `tribofe::report::precursors::fe_fig5_table`), one row per (r, g) cell with the model's n
/// and F_max and per rule the FE run's status and counts, with its units.
#[pyfunction]
#[pyo3(signature = (scene=None, resolution=None, rules=None, max_events=None, progress=None))]
fn precursors_fe_fig5<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    resolution: Option<usize>,
    rules: Option<Vec<String>>,
    max_events: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::precursors_fe as pfe;
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    refuse_scene_keys(&scene, FE_UNUSED, FE_WHY)?;
    let resolution = resolution.unwrap_or(pfe::DEFAULT_FIG5_RESOLUTION);
    let max_events = max_events.unwrap_or(pfe::DEFAULT_FIG5_MAX_EVENTS);
    let rules = match rules {
        Some(v) => v.iter().map(|r| r.parse()).collect::<tribofe::Result<Vec<Rule>>>().map_err(to_py)?,
        None => pfe::DEFAULT_FIG5_RULES.to_vec(),
    };
    let (cells, _) = run_detached(py, progress, |cancel, poll| {
        pfe::fig5(&scene, resolution, &rules, max_events, cancel, poll)
    })?;
    table_with_units(py, &tribofe::report::precursors::fe_fig5_table(&cells))
}

/// The model's n(r, g) at the cell centres of a `resolution` x `resolution` grid over the
/// (r, g) square (`tribofe precursors map`): n_map.csv's table (the library's,
/// `tribofe::report::precursors::n_map_table`), with its units.
#[pyfunction]
#[pyo3(signature = (resolution=None))]
fn precursors_map(py: Python<'_>, resolution: Option<usize>) -> PyResult<Bound<'_, PyDict>> {
    let resolution = resolution.unwrap_or(tribofe::precursors::DEFAULT_MAP_RESOLUTION);
    let (map, _) = run_detached(py, None, |cancel, _| tribofe::precursors::n_map(resolution, cancel))?;
    table_with_units(py, &tribofe::report::precursors::n_map_table(&map))
}

/// A series' values (`t_over_l=`, `h_over_l=`, `dc=`): at least one, as the command's list.
fn series_values(key: &str, v: &[f64]) -> PyResult<()> {
    if v.is_empty() {
        return Err(to_py(Error::input(key, "an empty list: give at least one value")));
    }
    Ok(())
}

/// The paper's (r, g), validated (None: the paper's fig. 4 case).
fn rg(r: Option<f64>, g: Option<f64>) -> PyResult<tribofe::precursors::Params> {
    tribofe::precursors::Params::new(
        r.unwrap_or(tribofe::precursors::PAPER_R),
        g.unwrap_or(tribofe::precursors::PAPER_G),
    )
    .map_err(to_py)
}

/// The scene keys the FE precursor studies cannot use, and why (the command's rule).
const FE_UNUSED: &[&str] = &["fn_ratios", "tol"];
const FE_WHY: &str = "the FE precursor studies load N then X until the interface slides";

/// Refuses a scene whose `keys` (Python's `Scene` keywords) differ from the paper's scene:
/// the call sets them itself, so they could not act (`why` says how).
fn refuse_scene_keys(scene: &RsScene, keys: &[&str], why: &str) -> PyResult<()> {
    let d = RsScene::default();
    for &key in keys {
        let differs = match key {
            "thickness" => scene.block.thickness != d.block.thickness,
            "height" => scene.loading.height != d.loading.height,
            "fn_ratios" => scene.loading.fn_ratios != d.loading.fn_ratios,
            "h" => scene.mesh.h != d.mesh.h,
            "grading" => scene.mesh.grading != d.mesh.grading,
            "h_max" => scene.mesh.h_max != d.mesh.h_max,
            "n_thick" => scene.mesh.n_thick != d.mesh.n_thick,
            "element" => scene.mesh.element != d.mesh.element,
            "mesh" => scene.mesh.file != d.mesh.file,
            "geometry" => scene.mesh.geometry != d.mesh.geometry,
            "tol" => scene.report.tol != d.report.tol,
            _ => unreachable!("not a scene keyword: {key}"),
        };
        if differs {
            return Err(to_py(Error::input(
                format!("Scene({key}=)"),
                format!("cannot act here: {why} (leave it at the paper's value)"),
            )));
        }
    }
    Ok(())
}

/// `tribofe stability`: the numerical stability studies of the paper's check (`study`: any of
/// plate, nu, shape, thin, corners; None: all), `corner_max` the finest corner mesh and
/// `n_ref` the qua9 reference's elements through the thickness: each study's table (the
/// library's, `tribofe::report::stability::tables`, the ones its CSV files are printed from)
/// with its units, the printed summary, and the corner study's exponents.
#[pyfunction]
#[pyo3(signature = (scene=None, study=None, corner_max=None, n_ref=None, progress=None))]
fn stability<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    study: Option<Vec<String>>,
    corner_max: Option<usize>,
    n_ref: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::stability as st;
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    refuse_scene_keys(
        &scene,
        &["h", "n_thick", "fn_ratios", "mesh", "geometry"],
        "each stability study sets its own meshes (n_ref=, corner_max=) and load case",
    )?;
    if !scene.loading.rig.is_top_plate() {
        return Err(to_py(Error::input(
            "Scene(rig=)",
            "side-push: the stability studies run the paper's top-plate rig; the side push runs in check() and slide()",
        )));
    }
    let studies = study.unwrap_or_else(|| st::STUDIES.iter().map(|s| s.to_string()).collect());
    st::refuse_idle(&studies, n_ref.map(|_| "n_ref"), corner_max.map(|_| "corner_max")).map_err(to_py)?;
    let base = st::Options::default();
    let o = st::Options {
        n_ref: n_ref.unwrap_or(base.n_ref),
        corner_n_thick: st::corner_meshes(corner_max.unwrap_or(st::DEFAULT_CORNER_MAX)),
        ..base
    };
    let (res, core_s) = run_detached(py, progress, |cancel, poll| {
        let o = st::Options { cancel: cancel.clone(), ..o };
        st::run(&scene, &studies, &o, poll)
    })?;
    let out = PyDict::new(py);
    let tables = PyDict::new(py);
    for (name, t) in tribofe::report::stability::tables(&res).map_err(to_py)? {
        tables.set_item(name, table_with_units(py, &t)?)?;
    }
    out.set_item("tables", tables)?;
    out.set_item("summary", tribofe::report::stability::summary(&res))?;
    if let Some(c) = &res.corners {
        let d = PyDict::new(py);
        d.set_item("factor", c.factor)?;
        d.set_item("lambda_measured", c.lambda_measured)?;
        d.set_item("lambda_williams", c.lambda_williams)?;
        d.set_item("factor_williams", c.factor_williams)?;
        d.set_item("nu", c.nu)?;
        out.set_item("corners", d)?;
    }
    out.set_item("core_s", core_s)?;
    Ok(out)
}

/// The thin-layer limit (`tribofe precursors thin-layer`): the `paper` rule at (r, g) on
/// blocks of each t/L at the scene's L and H/L (h = t, 2 elements through t):
/// thin_layer.csv's table (the library's, `series_table`), with its units.
#[pyfunction]
#[pyo3(signature = (t_over_l, scene=None, r=None, g=None, progress=None))]
fn precursors_thin_layer<'py>(
    py: Python<'py>,
    t_over_l: Vec<f64>,
    scene: Option<PyRef<'_, Scene>>,
    r: Option<f64>,
    g: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    series_values("t_over_l", &t_over_l)?;
    let p = rg(r, g)?;
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    refuse_scene_keys(&scene, FE_UNUSED, FE_WHY)?;
    refuse_scene_keys(
        &scene,
        &["thickness", "h", "n_thick", "grading", "h_max"],
        "precursors.thin_layer sets t = (t/L) L, h = t and 2 elements through t per run (t_over_l=)",
    )?;
    let (rows, _) = run_detached(py, progress, |cancel, poll| {
        tribofe::studies::precursors_fe::thin_layer(&scene, p.r(), p.g(), &t_over_l, cancel, poll)
    })?;
    table_with_units(py, &tribofe::report::precursors::series_table("t_over_L", "1", &rows))
}

/// The height of the drive (`tribofe precursors heights`): the `paper` rule with the
/// coefficients of (r, g) at the scene's H kept fixed, over H/L: heights.csv's table (the
/// library's), with its units, and those coefficients (`mu_s`, `mu_d`).
#[pyfunction]
#[pyo3(signature = (h_over_l, scene=None, r=None, g=None, progress=None))]
fn precursors_heights<'py>(
    py: Python<'py>,
    h_over_l: Vec<f64>,
    scene: Option<PyRef<'_, Scene>>,
    r: Option<f64>,
    g: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    series_values("h_over_l", &h_over_l)?;
    let p = rg(r, g)?;
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    refuse_scene_keys(&scene, FE_UNUSED, FE_WHY)?;
    let mu = tribofe::studies::slide::coefficients_from_rg(&scene, p.r(), p.g()).map_err(to_py)?;
    let (rows, _) = run_detached(py, progress, |cancel, poll| {
        tribofe::studies::precursors_fe::heights(&scene, p.r(), p.g(), &h_over_l, cancel, poll)
    })?;
    let out = table_with_units(py, &tribofe::report::precursors::series_table("H_over_L", "1", &rows))?;
    out.set_item("mu_s", mu.0)?;
    out.set_item("mu_d", mu.1)?;
    Ok(out)
}

/// The event rule against D_c (`tribofe precursors dc`): the `paper` rule (the row D_c = 0)
/// and slip-weakening with each D_c (m) at (r, g), one cycle each: dc.csv's table (the
/// library's), with its units, and the coefficients (`mu_s`, `mu_d`).
#[pyfunction]
#[pyo3(signature = (dc, scene=None, r=None, g=None, max_events=None, progress=None))]
fn precursors_dc<'py>(
    py: Python<'py>,
    dc: Vec<f64>,
    scene: Option<PyRef<'_, Scene>>,
    r: Option<f64>,
    g: Option<f64>,
    max_events: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::precursors_fe as pfe;
    series_values("dc", &dc)?;
    let p = rg(r, g)?;
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    refuse_scene_keys(&scene, FE_UNUSED, FE_WHY)?;
    let max_events = max_events.unwrap_or(pfe::DEFAULT_DC_MAX_EVENTS);
    let mu = tribofe::studies::slide::coefficients_from_rg(&scene, p.r(), p.g()).map_err(to_py)?;
    let (rows, _) = run_detached(py, progress, |cancel, poll| {
        pfe::dc_series(&scene, p.r(), p.g(), &dc, max_events, cancel, poll)
    })?;
    let out = table_with_units(py, &tribofe::report::precursors::series_table("Dc_m", "m", &rows))?;
    out.set_item("mu_s", mu.0)?;
    out.set_item("mu_d", mu.1)?;
    Ok(out)
}

/// The earlier comparison (`tribofe precursors bonded`): the 1D model fed with the scene's
/// bonded interface fields next to the paper's linear fields on the same cells:
/// fe_events.csv's table (the library's, `comparison_table`), with its units, and the
/// comparison's numbers (forces in units of mu_s N); with `sweep`, also fe_sweep.csv's table
/// (`sweep_table`: the comparison over H/L and t/L around the scene's) as `sweep`.
#[pyfunction]
#[pyo3(signature = (scene=None, r=None, g=None, events=None, sweep=false, progress=None))]
fn precursors_bonded<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    r: Option<f64>,
    g: Option<f64>,
    events: Option<usize>,
    sweep: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::precursors_fe as pfe;
    let (r, g) = (r.unwrap_or(tribofe::precursors::PAPER_R), g.unwrap_or(tribofe::precursors::PAPER_G));
    let events = events.unwrap_or(tribofe::precursors::DEFAULT_EVENTS);
    let scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    let ((c, rows), _) = run_detached(py, progress, |cancel, poll| {
        let c = pfe::bonded(&scene, r, g, events, cancel)?;
        let rows = if sweep { Some(pfe::bonded_sweep(&scene, r, g, events, cancel, poll)?) } else { None };
        Ok((c, rows))
    })?;
    let out = table_with_units(py, &tribofe::report::precursors::comparison_table(&c))?;
    if let Some(rows) = &rows {
        let t = tribofe::report::precursors::sweep_table(rows).map_err(to_py)?;
        out.set_item("sweep", table_with_units(py, &t)?)?;
    }
    let first = |run: &tribofe::precursors::discrete::Run| run.events.first().map(|e| e.f);
    out.set_item("r", c.params.r())?;
    out.set_item("g", c.params.g())?;
    out.set_item("mu_s", c.mu_s)?;
    out.set_item("mu_d", c.mu_d)?;
    out.set_item("H_over_L", c.h_over_l)?;
    out.set_item("t_over_L", c.t_over_l)?;
    out.set_item("n_fe", c.fe.n_precursors())?;
    out.set_item("n_linear", c.linear.n_precursors())?;
    out.set_item("F_1_fe", first(&c.fe))?;
    out.set_item("F_1_linear", first(&c.linear))?;
    out.set_item("F_max_fe", c.fe.f_limit())?;
    out.set_item("F_max_linear", c.linear.f_limit())?;
    Ok(out)
}

/// The spec `tribofe rupture` runs when no flag is given: the cross-check spec with the
/// default normal-stress lag. Every keyword left at None keeps its value here.
fn rupture_defaults() -> tribofe::dynamics::rupture::RuptureSpec {
    use tribofe::dynamics::rupture as rp;
    rp::RuptureSpec { normal: tribofe::law::Normal::Time { t: rp::DEFAULT_NORMAL_LAG }, ..Default::default() }
}

/// The dynamic-rupture scene on a rigid flat (`tribofe rupture`, docs/dynamics.md): explicit
/// elastodynamics with slip-weakening friction on the base. Arrays per base node (x >= any),
/// NaN where the front never arrived; scalars in SI units. `s` is the command's `--s`.
#[pyfunction]
#[pyo3(signature = (*, scene=None, s=None, h=None, dc=None, t_end=None, length=None, height=None, mu_s=None,
    mu_d=None, sigma0=None, young=None, poisson=None, density=None, courant=None, damping=None,
    contact=None, normal_lag=None, normal_lag_length=None, normal_lag_v_star=None, patch_taper=None,
    max_steps=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn rupture<'py>(
    py: Python<'py>,
    scene: Option<std::path::PathBuf>,
    s: Option<f64>,
    h: Option<f64>,
    dc: Option<f64>,
    t_end: Option<f64>,
    length: Option<f64>,
    height: Option<f64>,
    mu_s: Option<f64>,
    mu_d: Option<f64>,
    sigma0: Option<f64>,
    young: Option<f64>,
    poisson: Option<f64>,
    density: Option<f64>,
    courant: Option<f64>,
    damping: Option<f64>,
    contact: Option<&str>,
    normal_lag: Option<f64>,
    normal_lag_length: Option<f64>,
    normal_lag_v_star: Option<f64>,
    patch_taper: Option<f64>,
    max_steps: Option<u64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::dynamics::rupture as rp;
    let warn = |text: &str, class: &Bound<'py, pyo3::types::PyType>| {
        PyErr::warn(py, class, &std::ffi::CString::new(text).unwrap_or_default(), 1)
    };
    let inputs = rp::SceneInputs {
        s,
        h,
        dc,
        t_end,
        length,
        height,
        mu_s,
        mu_d,
        sigma0,
        young,
        poisson,
        density,
        courant,
        damping,
        contact: contact.map(str::to_string),
        normal_lag,
        normal_lag_length,
        normal_lag_v_star,
        patch_taper,
        max_steps,
    };
    // A rupture scene file with the keywords on top, or the flag-driven scene (as the
    // command's `--scene` and flags).
    let spec = match &scene {
        Some(path) => inputs.spec(path).map(|(spec, _)| spec),
        None => inputs.flag_spec(),
    }
    .map_err(to_py)?;
    if let Some(w) = spec.instantaneous_normal_warning() {
        warn(&w.replace("--normal-lag", "normal_lag="), &py.get_type::<pyo3::exceptions::PyUserWarning>())?;
    }
    let (r, core_s) = run_detached(py, progress, |cancel, poll| rp::run(&spec, cancel, poll))?;
    rupture_dict(py, &r, core_s)
}

/// A rupture run as the dict `rupture` returns.
fn rupture_dict<'py>(
    py: Python<'py>,
    r: &tribofe::dynamics::rupture::RuptureResult,
    core_s: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let opt = |v: &[Option<f64>]| v.iter().map(|t| t.unwrap_or(f64::NAN)).collect::<Vec<_>>();
    let out = PyDict::new(py);
    out.set_item("x_m", arr(py, &r.x))?;
    out.set_item("width_m", arr(py, &r.width))?;
    out.set_item("tau0_Pa", arr(py, &r.tau0))?;
    out.set_item("t_arrival_s", arr(py, &opt(&r.t_arrival)))?;
    out.set_item("t_weakened_s", arr(py, &opt(&r.t_weakened)))?;
    out.set_item("slip_m", arr(py, &r.slip))?;
    out.set_item("peak_slip_rate_m_per_s", arr(py, &r.peak_slip_rate))?;
    out.set_item("force_drop_N_per_m", r.force_drop)?;
    out.set_item("min_sigma_Pa", r.min_sigma)?;
    out.set_item("steps", r.steps)?;
    out.set_item("dt_s", r.dt)?;
    out.set_item("dt_stable_s", r.dt_stable)?;
    out.set_item("front_speed_m_per_s", r.front_speed)?;
    out.set_item("c_p_m_per_s", r.speeds.c_p)?;
    out.set_item("c_s_m_per_s", r.speeds.c_s)?;
    out.set_item("c_R_m_per_s", r.speeds.c_r)?;
    out.set_item("lambda0_m", r.lambda0)?;
    // energy.csv's one row, under its column names (the library's table).
    let energy = PyDict::new(py);
    for c in &tribofe::report::rupture::energy_table(r).columns {
        if let tribofe::report::table::Values::Float(v) = &c.values {
            energy.set_item(&c.name, v[0])?;
        }
    }
    out.set_item("energy", energy)?;
    out.set_item("rupture_time_s", arr(py, &opt(&r.rupture_time)))?;
    out.set_item("rate_threshold_m_per_s", r.rate_threshold)?;
    // Each station's table (station_x<x>.csv's, the library's), keyed by its x (m).
    let stations = PyDict::new(py);
    for st in &r.stations {
        stations.set_item(st.x, table_with_units(py, &tribofe::report::rupture::station_table(st))?)?;
    }
    out.set_item("stations", stations)?;
    out.set_item("core_s", core_s)?;
    Ok(out)
}

/// `tribofe slide --dynamics` (docs/dynamics.md): the quasi-static loading with each
/// instability run in elastodynamics (or the whole drive at `drive_velocity`). Every default
/// is the library's (the command's): None means "the library's default".
#[pyfunction]
#[pyo3(signature = (scene=None, law=None, *, mu=None, mu_s=None, mu_d=None, r=None, g=None,
    dc=None, h=None, n_force=None, x_max=None, cycles=None, cycle_end=None, max_events=None,
    operator=None, states=None, keep_states=None, damping=None, courant=None, drive_velocity=None,
    plate_mass=None, plate_inertia=None, heal=None, weakening_steps=None, exact_weakening=None, event_end=None, density=None, a=None, b=None,
    l_rs=None, f0=None, v0=None, state_law=None, theta0=None, normal_lag=None, normal_lag_length=None,
    normal_lag_v_star=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn dynamic_slide<'py>(
    py: Python<'py>,
    scene: Option<PyRef<'_, Scene>>,
    law: Option<&str>,
    mu: Option<f64>,
    mu_s: Option<f64>,
    mu_d: Option<f64>,
    r: Option<f64>,
    g: Option<f64>,
    dc: Option<f64>,
    h: Option<f64>,
    n_force: Option<f64>,
    x_max: Option<f64>,
    cycles: Option<usize>,
    cycle_end: Option<&str>,
    max_events: Option<usize>,
    operator: Option<&str>,
    states: Option<&str>,
    keep_states: Option<bool>,
    damping: Option<f64>,
    courant: Option<f64>,
    drive_velocity: Option<f64>,
    plate_mass: Option<f64>,
    plate_inertia: Option<f64>,
    heal: Option<&str>,
    weakening_steps: Option<f64>,
    exact_weakening: Option<bool>,
    event_end: Option<&str>,
    density: Option<f64>,
    a: Option<f64>,
    b: Option<f64>,
    l_rs: Option<f64>,
    f0: Option<f64>,
    v0: Option<f64>,
    state_law: Option<&str>,
    theta0: Option<f64>,
    normal_lag: Option<f64>,
    normal_lag_length: Option<f64>,
    normal_lag_v_star: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    use tribofe::studies::dynamic_slide as ds;
    let base = ds::DynamicOptions::default();
    let n_force = n_force.unwrap_or(tribofe::studies::slide::DEFAULT_N_FORCE);
    let max_events = max_events.unwrap_or(tribofe::studies::slide::DEFAULT_MAX_EVENTS);
    let mut scene = scene.map(|s| s.inner.clone()).unwrap_or_default();
    if let Some(h) = h {
        scene.mesh.h = h;
        scene.validate().map_err(to_py)?;
    }
    // The command's default law (`slide --dynamics` takes slide's `--law`), unless the scene's
    // [law] names one.
    let law_given = law.is_some();
    let law = law.or(scene.law.kind.as_deref()).unwrap_or(tribofe::studies::slide::DEFAULT_LAW).to_string();
    let law = law.as_str();
    let mut law_choice = tribofe::studies::slide::LawChoice {
        law: law.to_string(),
        mu,
        mu_s,
        mu_d,
        r,
        g,
        rule: tribofe::studies::slide::DEFAULT_RULE.to_string(),
        dc,
        rate_state: tribofe::studies::slide::RateStateChoice {
            a,
            b,
            l_rs,
            v0,
            f0,
            state_law: state_law.map(str::to_string),
            theta0,
        },
        ..Default::default()
    }
    .with_scene(&scene.law, law_given, false);
    let mut notes = Vec::new();
    if law == "slip-weakening" {
        let res = ds::physics::resolve(&mut scene, &law_choice, n_force, h.is_some(), ["dc=", "h="])
            .map_err(to_py)?;
        law_choice.dc = res.law.dc();
        notes = res.notes;
    }
    // The block's density, as the command's --density (after D_c and h, which do not use it).
    if let Some(rho) = density {
        scene.block.density = rho;
        scene.validate().map_err(to_py)?;
    }
    // Every choice parsed here, once, before any work (refused with the accepted names).
    let end_at_crossing = choice("cycle_end", cycle_end, CYCLE_ENDS)?;
    let operator = choice("operator", operator, OPERATORS)?;
    let heal_slipped_only = choice("heal", heal, HEALS)?.unwrap_or(base.heal_slipped_only);
    let event_end = choice("event_end", event_end, &tribofe::dynamics::driven::EventEnd::NAMES)?;
    let keep_states = match (choice("states", states, STATES)?, keep_states) {
        (Some(_), Some(_)) => {
            return Err(to_py(Error::input("keep_states", "the old spelling of states=: give states= alone")))
        }
        (Some(k), None) | (None, Some(k)) => k,
        // `--states none` with --dynamics.
        (None, None) => false,
    };
    let o = tribofe::studies::slide::SlideOptions {
        law: law_choice.law(&scene).map_err(to_py)?,
        n_force,
        x_max,
        cycles: cycles.unwrap_or(ds::DEFAULT_CYCLES),
        end_at_crossing: end_at_crossing.unwrap_or(ds::DEFAULT_END_AT_CROSSING),
        max_events,
        keep_states,
        operator: operator.unwrap_or_else(|| ds::default_operator(&scene)),
        ..Default::default()
    };
    // The stepped path (weakening_steps= or the default) unless exact_weakening=True.
    let exact = exact_weakening.unwrap_or(false);
    let o = tribofe::studies::slide::SlideOptions {
        weakening: ds::weakening(exact, weakening_steps.is_some(), &o, drive_velocity).map_err(to_py)?,
        ..o
    };
    let d = ds::DynamicOptions {
        damping,
        courant: courant.unwrap_or(ds::DEFAULT_COURANT),
        drive_velocity,
        plate_mass: plate_mass.unwrap_or(base.plate_mass),
        plate_inertia: plate_inertia.unwrap_or(base.plate_inertia),
        heal_slipped_only,
        weakening_steps: ds::weakening_steps(weakening_steps, &o, drive_velocity).map_err(to_py)?,
        event_end: ds::event_end(event_end, drive_velocity).map_err(to_py)?,
        normal: scene.law.normal([normal_lag, normal_lag_length, normal_lag_v_star]).map_err(to_py)?,
        ..Default::default()
    };
    // ds::run makes every check before any work (the quasi-static ones on a rate-free law).
    let (res, core_s) = run_detached(py, progress, |cancel, poll| {
        let o = tribofe::studies::slide::SlideOptions { cancel: cancel.clone(), ..o };
        ds::run(&scene, &o, &d, poll)
    })?;
    // Every table from the library's schema (report::table), the one the CSV is printed from:
    // every column of each file at full precision, with its type and unit.
    use tribofe::report::{dynamic_slide as rd, slide as rs};
    let out = PyDict::new(py);
    let units = PyDict::new(py);
    let mut tables = vec![
        ("loading", rs::loading_table(&res.slide)),
        ("events", rs::events_table(&res.slide)),
        ("dyn_events", rd::events_table(&res)),
        ("fronts", rd::fronts_table(&res)),
        ("summary", rd::summary_table(&res)),
    ];
    if res.slide.options.law.weakens() {
        tables.push(("advances", rs::advances_table(&res.slide)));
    }
    for (name, t) in &tables {
        out.set_item(*name, table(py, t)?)?;
        units.set_item(*name, table_units(t))?;
    }
    out.set_item("units", units)?;
    // Each dynamic event's samples: time since onset (s), drive force (N/m), tip x (m, NaN
    // before nucleation), and |v_x| of every base node (samples x nodes, m/s) at slip_rate_t_s.
    let samples = PyList::empty(py);
    for e in &res.events {
        let rec = &e.record;
        let d = PyDict::new(py);
        d.set_item("event", e.event)?;
        d.set_item("instability", rec.weakened)?;
        d.set_item("t_s", arr(py, &rec.t))?;
        d.set_item("F_N_per_m", arr(py, &rec.force))?;
        d.set_item("tip_m", arr(py, &rec.tip))?;
        let n = res.slide.condensed.n;
        let flat: Vec<f64> = rec.rates.iter().flat_map(|row| row.iter().map(|&v| v as f64)).collect();
        d.set_item("slip_rate_m_per_s", PyArray1::from_vec(py, flat).reshape([rec.rates.len(), n])?)?;
        // The rates' rows are the samples before the event's end (its last sample has none).
        d.set_item("slip_rate_t_s", arr(py, &rec.t[..rec.rates.len().min(rec.t.len())]))?;
        samples.append(d)?;
    }
    out.set_item("samples", samples)?;
    let c = &res.slide.condensed;
    out.set_item("law", res.slide.options.law.name())?;
    out.set_item("mu_s", res.slide.options.law.mu_s())?;
    out.set_item("mu_d", res.slide.options.law.mu_d())?;
    out.set_item("x_over_L", arr(py, &c.x.iter().map(|x| x / c.l).collect::<Vec<_>>()))?;
    out.set_item("h_m", scene.mesh.h)?;
    out.set_item("dt_s", res.dt)?;
    out.set_item("dt_stable_s", res.dt_stable)?;
    out.set_item("damping_eta_s", res.eta)?;
    out.set_item("c_s_m_per_s", res.speeds.c_s)?;
    out.set_item("c_p_m_per_s", res.speeds.c_p)?;
    out.set_item("c_R_m_per_s", res.speeds.c_r)?;
    out.set_item("dofs", res.dofs)?;
    out.set_item("steps", res.steps)?;
    out.set_item("incomplete", res.incomplete.clone())?;
    out.set_item("notes", notes)?;
    out.set_item("core_s", core_s)?;
    Ok(out)
}

/// The library's default of every keyword whose Python default is None and that has one fixed
/// value, per function (`"slide"`, `"dynamics.rupture"`...): what None means, read from the
/// same constants the calls use and the command's `--help` shows.
#[pyfunction]
fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    use tribofe::studies::{
        convergence as cv, dynamic_slide as ds, precursors_fe as pfe, slide as sl, sweep as sw,
    };
    let (pr, pg) = (tribofe::precursors::PAPER_R, tribofe::precursors::PAPER_G);
    let conv = cv::StudyOptions::default();
    let dyn_o = ds::DynamicOptions::default();
    let rp = rupture_defaults();
    let out = PyDict::new(py);
    // One dict of keyword -> default per function.
    macro_rules! put {
        ($name:expr, [$(($k:expr, $v:expr)),* $(,)?] $(,)?) => {{
            let d = PyDict::new(py);
            $(d.set_item($k, $v)?;)*
            out.set_item($name, d)?;
        }};
    }
    put!(
        "slide",
        [
            ("law", sl::DEFAULT_LAW),
            ("rule", sl::DEFAULT_RULE),
            ("residual", name_of(RESIDUALS, tribofe::law::PaperOptions::default().residual)),
            ("backslip", name_of(BACKSLIPS, tribofe::law::PaperOptions::default().backslip)),
            ("n_force", sl::DEFAULT_N_FORCE),
            ("cycles", sl::DEFAULT_CYCLES),
            ("max_events", sl::DEFAULT_MAX_EVENTS),
        ],
    );
    put!(
        "dynamics.slide",
        [
            ("law", sl::DEFAULT_LAW),
            ("n_force", sl::DEFAULT_N_FORCE),
            ("max_events", sl::DEFAULT_MAX_EVENTS),
            ("cycles", ds::DEFAULT_CYCLES),
            ("cycle_end", name_of(CYCLE_ENDS, ds::DEFAULT_END_AT_CROSSING)),
            ("operator", ds::DEFAULT_OPERATOR.name()),
            ("courant", ds::DEFAULT_COURANT),
            ("weakening_steps", ds::DEFAULT_WEAKENING_STEPS),
            ("plate_mass", dyn_o.plate_mass),
            ("plate_inertia", dyn_o.plate_inertia),
            ("heal", name_of(HEALS, dyn_o.heal_slipped_only)),
            ("event_end", dyn_o.event_end.name()),
        ],
    );
    put!("sweep", [("rule", sl::DEFAULT_RULE), ("cycles", sw::DEFAULT_FRICTION_CYCLES)]);
    let families: Vec<String> = conv.families.iter().map(|f| f.name().to_string()).collect();
    put!(
        "converge",
        [
            ("elements", conv.elements),
            ("families", families),
            ("n_thick", conv.n_thick),
            ("fn_ratio", conv.fn_ratio),
        ],
    );
    put!("precursors.model", [("r", pr), ("g", pg)]);
    put!("precursors.fe_fig4", [("r", pr), ("g", pg), ("cycles", pfe::DEFAULT_FIG4_CYCLES)]);
    let rules: Vec<&str> = pfe::DEFAULT_FIG5_RULES.iter().map(|r| r.name()).collect();
    put!(
        "precursors.fe_fig5",
        [
            ("resolution", pfe::DEFAULT_FIG5_RESOLUTION),
            ("rules", rules),
            ("max_events", pfe::DEFAULT_FIG5_MAX_EVENTS),
        ],
    );
    {
        use tribofe::scene::rectangle as rect;
        let d = rect::DEFAULT_SIDES;
        put!(
            "solve",
            [
                ("lx", rect::DEFAULT_LX),
                ("ly", rect::DEFAULT_LY),
                ("nx", rect::DEFAULT_NX),
                ("ny", rect::DEFAULT_NY),
                ("element", rect::DEFAULT_ELEMENT),
                ("young", rect::DEFAULT_YOUNG),
                ("poisson", rect::DEFAULT_POISSON),
                ("bottom", d[0]),
                ("right", d[1]),
                ("top", d[2]),
                ("left", d[3]),
            ],
        );
    }
    {
        use tribofe::studies::edges as ed;
        put!(
            "edges",
            [
                ("mu", ed::DEFAULT_MU.to_vec()),
                ("refine", ed::DEFAULT_REFINE.to_vec()),
                ("mu_s", ed::DEFAULT_MU_S),
                ("mu_d", ed::DEFAULT_MU_D),
                ("rule", ed::DEFAULT_RULE.name()),
                ("t_over_l", ed::DEFAULT_T_OVER_L.to_vec()),
                ("open_refine", ed::DEFAULT_OPEN_REFINE.to_vec()),
                ("end_grading", ed::DEFAULT_END_GRADING),
                ("h_over_l", ed::DEFAULT_H_OVER_L.to_vec()),
            ],
        );
    }
    {
        use tribofe::studies::stability as st;
        put!("stability", [("corner_max", st::DEFAULT_CORNER_MAX), ("n_ref", st::DEFAULT_N_REF)]);
    }
    put!("precursors.map", [("resolution", tribofe::precursors::DEFAULT_MAP_RESOLUTION)]);
    put!("precursors.thin_layer", [("r", pr), ("g", pg)]);
    put!("precursors.heights", [("r", pr), ("g", pg)]);
    put!("precursors.dc", [("r", pr), ("g", pg), ("max_events", pfe::DEFAULT_DC_MAX_EVENTS)]);
    put!("precursors.bonded", [("r", pr), ("g", pg), ("events", tribofe::precursors::DEFAULT_EVENTS)]);
    put!(
        "dynamics.rupture",
        [
            ("s", rp.s_ratio),
            ("h", rp.h),
            ("dc", rp.dc()),
            ("t_end", rp.t_end),
            ("length", rp.length),
            ("height", rp.height),
            ("mu_s", rp.friction.mu_s()),
            ("mu_d", rp.friction.mu_d()),
            ("sigma0", rp.sigma0),
            ("young", rp.young),
            ("poisson", rp.poisson),
            ("density", rp.density),
            ("courant", rp.courant),
            ("damping", rp.damping),
            ("contact", rp.contact.name()),
            ("normal_lag", if let tribofe::law::Normal::Time { t } = rp.normal { t } else { 0.0 }),
            ("patch_taper", rp.patch_taper),
            ("max_steps", rp.max_steps),
        ],
    );
    Ok(out)
}

#[pymodule]
fn _tribofe(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Malloc arenas that fit RLIMIT_AS (threads of other modules may already run: best effort).
    tribofe::scene::limits::fit_malloc_arenas();
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(slide, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(edges, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_model, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(converge, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_fe_fig4, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_fe_fig5, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_map, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_thin_layer, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_heights, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_dc, m)?)?;
    m.add_function(wrap_pyfunction!(precursors_bonded, m)?)?;
    m.add_function(wrap_pyfunction!(rupture, m)?)?;
    m.add_function(wrap_pyfunction!(dynamic_slide, m)?)?;
    m.add_function(wrap_pyfunction!(stability, m)?)?;
    m.add_function(wrap_pyfunction!(defaults, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
