//! `tribofe rupture`: the shared cross-check scene (a block on a rigid flat with slip-weakening
//! friction, run explicitly; docs/dynamics.md), writing arrival.csv and summary.csv.

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use tribofe::dynamics::rupture::{Contact, RuptureSpec, SceneInputs};
use tribofe::law::Law;
use tribofe::scene::Scene;

// Every default is the library's RuptureSpec::default() (the cross-check spec), bar the
// normal lag; the Python package reads the same.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Strength ratio S = (mu_s sigma0 - tau0) / (tau0 - mu_d sigma0) outside the nucleation patch.
    #[arg(long, default_value_t = RuptureSpec::default().s_ratio)]
    pub s: f64,
    /// Element size, m (square QUA4; length and height must be whole multiples).
    #[arg(long, default_value_t = RuptureSpec::default().h)]
    pub h: f64,
    /// Slip-weakening distance D_c, m.
    #[arg(long, default_value_t = RuptureSpec::default().dc())]
    pub dc: f64,
    /// Run to this time, s (steps = round(t_end / dt)).
    #[arg(long, default_value_t = RuptureSpec::default().t_end)]
    pub t_end: f64,
    /// Block length (x in [-L/2, L/2]) and height, m.
    #[arg(long, default_value_t = RuptureSpec::default().length)]
    pub length: f64,
    #[arg(long, default_value_t = RuptureSpec::default().height)]
    pub height: f64,
    /// Static and dynamic friction coefficients.
    #[arg(long, default_value_t = RuptureSpec::default().friction.mu_s())]
    pub mu_s: f64,
    #[arg(long, default_value_t = RuptureSpec::default().friction.mu_d())]
    pub mu_d: f64,
    /// Background normal stress on the base (compressive positive), Pa.
    #[arg(long, default_value_t = RuptureSpec::default().sigma0)]
    pub sigma0: f64,
    /// Young's modulus (Pa), Poisson's ratio and density (kg/m^3) of the block.
    #[arg(long, default_value_t = RuptureSpec::default().young)]
    pub young: f64,
    #[arg(long, default_value_t = RuptureSpec::default().poisson)]
    pub poisson: f64,
    #[arg(long, default_value_t = RuptureSpec::default().density)]
    pub density: f64,
    /// Time step dt = courant h / c_p (refused above the mesh's stable step).
    #[arg(long, default_value_t = RuptureSpec::default().courant)]
    pub courant: f64,
    /// Kelvin-Voigt (stiffness-proportional) damping coefficient eta, s.
    #[arg(long, default_value_t = RuptureSpec::default().damping)]
    pub damping: f64,
    /// Base condition: bilateral (the spec: u_y = 0 on the rigid flat), unilateral (the flat
    /// cannot pull: nodes may open), symmetric (not a flat: the plane of a symmetric fault
    /// between two identical blocks, slip 2 u_x, the Andrews control case).
    #[arg(long, default_value = RuptureSpec::default().contact.name())]
    pub contact: String,
    /// Normal-stress regularisation time T, s: the strength follows the normal stress with
    /// d sigma*/dt = -(sigma* - sigma) / T (Prakash-Clifton). Default 1e-3 s, the time scale
    /// the rigid-flat rupture converges with (docs/dynamics-findings.md); 0: the instantaneous normal
    /// stress of the cross-check spec (warned on a rigid flat: ill-posed above a threshold).
    #[arg(long, default_value_t = tribofe::dynamics::rupture::DEFAULT_NORMAL_LAG)]
    pub normal_lag: f64,
    /// Prakash-Clifton with a slip length instead of a time: d sigma*/dt = -(sigma* - sigma)
    /// (|V| + V*) / L, L in m (in place of --normal-lag; docs/dynamics-findings.md compares
    /// the two forms' convergence).
    #[arg(long, conflicts_with = "normal_lag")]
    pub normal_lag_length: Option<f64>,
    /// The length form's reference slip rate V*, m/s (default 0: sigma* moves only with slip).
    #[arg(long)]
    pub normal_lag_v_star: Option<f64>,
    /// Width of a cosine ramp of the initial shear centred on the nucleation patch's edge
    /// (|x| = 0.01 m), m (default 0, as the spec: a jump).
    #[arg(long, default_value_t = RuptureSpec::default().patch_taper)]
    pub patch_taper: f64,
    /// Most explicit steps the run may take (t_end / dt, dt = courant h / c_p); a run above it
    /// is refused before any work. The default, 1e6 steps, is about 15 minutes on the default
    /// mesh (one step of 200 x 100 elements about 1 ms); the default run is 414 steps.
    #[arg(long, default_value_t = tribofe::dynamics::rupture::DEFAULT_MAX_STEPS)]
    pub max_steps: u64,
    /// A rupture scene file (TOML; docs/dynamics.md, "Rupture scenes"): the block, the
    /// material (young, poisson or c_p, c_s, with density), [law], [interface] (kind, sigma0,
    /// tau0, a nucleation patch, values piecewise in x) and [rupture] (t_end, stations,
    /// dt_out, ...). A flag given overrides the file's key; a key the file does not give takes
    /// the scene's default (the block's and mesh's) or this command's.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Output directory.
    #[arg(long, default_value = "out/rupture")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
}

/// The flags given, on top of a `--scene` file.
fn scene_inputs(a: &Args) -> SceneInputs {
    use super::given;
    let f = |id: &str, v: f64| given(id).then_some(v);
    SceneInputs {
        s: f("s", a.s),
        h: f("h", a.h),
        dc: f("dc", a.dc),
        t_end: f("t_end", a.t_end),
        length: f("length", a.length),
        height: f("height", a.height),
        mu_s: f("mu_s", a.mu_s),
        mu_d: f("mu_d", a.mu_d),
        sigma0: f("sigma0", a.sigma0),
        young: f("young", a.young),
        poisson: f("poisson", a.poisson),
        density: f("density", a.density),
        courant: f("courant", a.courant),
        damping: f("damping", a.damping),
        contact: given("contact").then(|| a.contact.clone()),
        normal_lag: f("normal_lag", a.normal_lag),
        normal_lag_length: a.normal_lag_length,
        normal_lag_v_star: a.normal_lag_v_star,
        patch_taper: f("patch_taper", a.patch_taper),
        max_steps: given("max_steps").then_some(a.max_steps),
    }
}

pub fn run(a: Args) -> tribofe::Result<()> {
    if let Some(path) = &a.scene {
        let (spec, scene) = scene_inputs(&a).spec(path)?;
        return run_spec(&a, &spec, Some(&scene));
    }
    let spec = RuptureSpec {
        length: a.length,
        height: a.height,
        h: a.h,
        young: a.young,
        poisson: a.poisson,
        density: a.density,
        sigma0: a.sigma0,
        s_ratio: a.s,
        friction: Law::SlipWeakening { mu_s: a.mu_s, mu_d: a.mu_d, dc: a.dc },
        courant: a.courant,
        t_end: a.t_end,
        damping: a.damping,
        contact: a.contact.parse::<Contact>()?,
        // --normal-lag has a default (clap refuses it given with --normal-lag-length).
        normal: tribofe::law::Normal::from_inputs(
            a.normal_lag_length.is_none().then_some(a.normal_lag),
            a.normal_lag_length,
            a.normal_lag_v_star,
            tribofe::law::Normal::Instantaneous,
            ["--normal-lag", "--normal-lag-length", "--normal-lag-v-star"],
        )?,
        patch_taper: a.patch_taper,
        max_steps: a.max_steps,
        ..Default::default()
    };
    spec.validate()?;
    run_spec(&a, &spec, None)
}

fn run_spec(a: &Args, spec: &RuptureSpec, scene: Option<&Scene>) -> tribofe::Result<()> {
    tribofe::io::outdir::check(&a.out, a.force)?;
    if let Some(w) = spec.instantaneous_normal_warning() {
        errln!("warning: {w}");
    }
    let lambda0 = spec.lambda0()?;
    let (dt, steps) = spec.steps()?;
    if let Some(path) = &a.scene {
        let p = spec.patch();
        let (t_back, from) = spec.clean_time()?;
        outln!(
            "rupture scene {}: {} x {} m block, h = {} m ({} x {} elements), {} interface; tau0 = {:.6e} Pa, sigma0 = {:.6e} Pa in the background, {} interval(s); nucleation {} <= x <= {} m at {:.6e} Pa; Lambda_0 >= {:.4e} m = {:.2} elements; {steps:.0} steps of dt = {dt:.4e} s; {} station(s); the first reflection ({from}) returns at {t_back:.4} s{}",
            tribofe::error::quote(&path.display().to_string()),
            spec.length,
            spec.height,
            spec.h,
            (spec.length / spec.h).round(),
            (spec.height / spec.h).round(),
            spec.contact.name(),
            spec.tau0(),
            spec.sigma0,
            spec.pieces.len(),
            p.x_min,
            p.x_max,
            p.tau0,
            lambda0,
            lambda0 / spec.h,
            spec.stations.len(),
            if t_back < spec.t_end { " (before t_end: allowed by the scene)" } else { "" }
        );
    } else {
        outln!(
            "rupture: S = {}, tau0 = {:.6} Pa outside |x| <= {} m ({}), h = {} m, D_c = {:e} m; Lambda_0 = {:.4e} m = {:.2} elements; {steps:.0} steps of dt = {dt:.4e} s (--max-steps {})",
            spec.s_ratio,
            spec.tau0(),
            spec.patch_half_width,
            if spec.patch_taper > 0.0 { format!("edge ramp {} m", spec.patch_taper) } else { "edge: a jump".to_string() },
            spec.h,
            spec.dc(),
            lambda0,
            lambda0 / spec.h,
            spec.max_steps
        );
    }
    let bar = ProgressBar::new(1000).with_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {percent}% {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message("rupture");
    let t0 = std::time::Instant::now();
    let tick = |t: &tribofe::Tick| bar.set_position((t.fraction.unwrap_or(0.0) * 1000.0) as u64);
    let r = tribofe::dynamics::rupture::run(spec, &tribofe::Cancel::new(), tribofe::Progress::new(&tick))?;
    let secs = t0.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let dir = super::begin_out(&a.out, a.force)?;
    tribofe::report::rupture::write(&r, dir.path())?;
    let results: toml::Table = [
        ("dt_s", toml::Value::from(r.dt)),
        ("steps", toml::Value::from(r.steps as i64)),
        ("lambda0_m", toml::Value::from(lambda0)),
        ("force_drop_N_per_m", toml::Value::from(r.force_drop)),
        ("min_sigma_Pa", toml::Value::from(r.min_sigma)),
        ("normal_response", toml::Value::from(spec.normal.name())),
        ("rate_threshold_m_per_s", toml::Value::from(r.rate_threshold)),
        ("wall_seconds", toml::Value::from(secs)),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .chain(r.front_speed.map(|v| ("front_speed_m_per_s".to_string(), toml::Value::from(v))))
    .collect();
    super::write_run_file(dir.path(), scene, &results)?;
    dir.commit()?;
    let w = &r.speeds;
    outln!(
        "c_p = {:.5} m/s, c_s = {:.5} m/s, c_R = {:.5} m/s; dt = {:.5e} s ({} steps; stable step {:.5e} s by the element bound)",
        w.c_p,
        w.c_s,
        w.c_r,
        r.dt,
        r.steps,
        r.dt_stable
    );
    match r.front_speed {
        Some(v) => outln!(
            "front speed (+x) over {} <= x <= {} m: {:.5} m/s = {:.4} c_s = {:.4} c_R{}",
            spec.speed_window.0,
            spec.speed_window.1,
            v,
            v / w.c_s,
            v / w.c_r,
            r.front_speed_left(spec.speed_window.0, spec.speed_window.1)
                .map_or(String::new(), |l| format!("; (-x) {:.5} m/s = {:.4} c_s", l, l / w.c_s))
        ),
        None => outln!(
            "front speed (+x): the front did not cross {} <= x <= {} m by t_end (fewer than 3 arrivals there)",
            spec.speed_window.0,
            spec.speed_window.1
        ),
    }
    let e = &r.energy;
    outln!(
        "force drop {:.6e} N/m; min normal stress {:.6} Pa; energy: kinetic {:.4e} + strain {:.4e} + friction {:.4e} = background work {:.4e} (+ contact {:.1e}), residual {:.1e} J/m",
        r.force_drop,
        r.min_sigma,
        e.kinetic,
        e.strain,
        e.friction,
        e.background_work,
        e.contact,
        e.residual
    );
    let zone = r.cohesive_zone();
    if let Some(&(x, z)) = zone.last() {
        outln!(
            "cohesive zone at x = {x:.4} m: {z:.4e} m = {:.3} Lambda_0 = {:.2} elements",
            z / lambda0,
            z / spec.h
        );
    }
    if !r.barrier_slipped.is_empty() {
        errln!(
            "warning: {} barrier node(s) (static strength over {} times the largest initial shear) slipped past D_c / 100, from x = {} to {} m: the barrier did not hold",
            r.barrier_slipped.len(),
            tribofe::dynamics::rupture::BARRIER_FACTOR,
            r.barrier_slipped[0],
            r.barrier_slipped[r.barrier_slipped.len() - 1]
        );
    }
    outln!(
        "{:.2} s ({:.3e} DOF-updates/s); wrote {}/{{{}}}",
        secs,
        (r.steps as f64)
            * 2.0
            * ((spec.length / spec.h).round() + 1.0)
            * ((spec.height / spec.h).round() + 1.0)
            / secs,
        a.out.display(),
        tribofe::report::rupture::files(&r).join(", ")
    );
    Ok(())
}
