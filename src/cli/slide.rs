//! `tribofe slide`: the frictional interface loaded by N then X at height H, event by event.

use super::scene_args::{scene as scene_from, SceneArgs};
use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use tribofe::interface::law::Law;
use tribofe::studies::slide::SlideOptions;
use tribofe::Error;

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Friction law: coulomb, static-kinetic or slip-weakening.
    #[arg(long, default_value = "coulomb")]
    pub law: String,
    /// Coulomb coefficient (coulomb; default 0.5).
    #[arg(long)]
    pub mu: Option<f64>,
    /// Static and kinetic coefficients (static-kinetic).
    #[arg(long)]
    pub mu_s: Option<f64>,
    #[arg(long)]
    pub mu_d: Option<f64>,
    /// The paper's r = mu_d/mu_s and g = 6 mu_d H/L instead of the coefficients
    /// (static-kinetic default: r = 0.9, g = 0.35; coulomb takes --g alone: mu = g L/(6 H)).
    #[arg(long)]
    pub r: Option<f64>,
    #[arg(long)]
    pub g: Option<f64>,
    /// Event rule of static-kinetic: paper or overdamped.
    #[arg(long, default_value = "paper")]
    pub rule: String,
    /// Slip-weakening distance D_c, m (slip-weakening; the coefficients as for static-kinetic).
    #[arg(long)]
    pub dc: Option<f64>,
    /// Normal force N, N/m (results are reported per unit N where that makes them independent of it).
    #[arg(long, default_value_t = 1.0)]
    pub n_force: f64,
    /// Largest plate displacement X at height H, m (default: 5 % past the first whole-interface
    /// slip for coulomb; the cycles for static-kinetic).
    #[arg(long)]
    pub x_max: Option<f64>,
    /// Whole-interface slips (stick-slip cycles) to run, static-kinetic and slip-weakening.
    #[arg(long, default_value_t = 10)]
    pub cycles: usize,
    /// Cap on events (each keeps the interface state: ~40 bytes per node).
    #[arg(long, default_value_t = 50_000)]
    pub max_events: usize,
    /// Slip weakening: each relaxation's coefficients by Newton where a stable equilibrium is
    /// near (the same equilibria, fewer updates; validation/friction/README.md). Default: fixed
    /// point, the reference (Newton only where a relaxation is unsettled after 10^4 iterates).
    #[arg(long)]
    pub newton: bool,
    /// Write the whole block's fields for this many states spread evenly over the drive X, one
    /// per X (the settled state), first and last included (0: none); fields.pvd is indexed by
    /// X in m, each file holds its `event` (docs/outputs.md).
    #[arg(long, default_value_t = 0)]
    pub fields: usize,
    /// Format of the --fields files: vtu (fields_<event>.vtu + fields.pvd, ParaView), msh
    /// (fields_<event>.msh, Gmsh) or both.
    #[arg(long, default_value = "vtu", value_parser = ["vtu", "msh", "both"])]
    pub field_format: String,
    /// Output directory.
    #[arg(long, default_value = "out/slide")]
    pub out: PathBuf,
    /// Replace the --out folder even if it holds files tribofe did not write (they are deleted).
    #[arg(long)]
    pub force: bool,
}

fn law(a: &Args, scene: &tribofe::scene::Scene) -> tribofe::Result<Law> {
    tribofe::studies::slide::LawChoice {
        law: a.law.clone(),
        mu: a.mu,
        mu_s: a.mu_s,
        mu_d: a.mu_d,
        r: a.r,
        g: a.g,
        rule: a.rule.clone(),
        dc: a.dc,
    }
    .law(scene)
}

pub fn run(a: Args) -> tribofe::Result<()> {
    // The scene flags (shared with check and sweep) are applied and validated in scene_from;
    // two of them belong to the bonded check and cannot act here.
    super::scene_args::refuse_inapplicable(
        &a.scene,
        &["--fn-ratios", "--tol"],
        "`slide` loads N then X until the interface slides (--n-force, --x-max); the load ratios and the edge-zone tolerance belong to `check`",
    )?;
    let scene = scene_from(&a.scene)?;
    let field_format: tribofe::io::FieldFormat = a.field_format.parse()?;
    if a.fields == 0 && field_format != tribofe::io::FieldFormat::Vtu {
        return Err(Error::input("--field-format", "acts only with --fields N (N > 0 states to write)"));
    }
    tribofe::io::outdir::check(&a.out, a.force)?;
    if a.dc.is_some() && a.law != "slip-weakening" {
        return Err(Error::input("dc", "--dc belongs to --law slip-weakening"));
    }
    if super::given("rule") && a.law != "static-kinetic" {
        return Err(Error::input("--rule", "the event rule belongs to --law static-kinetic"));
    }
    if a.newton && a.law != "slip-weakening" {
        return Err(Error::input("newton", "--newton cannot act without --law slip-weakening"));
    }
    if a.fields > a.max_events {
        return Err(Error::input(
            "--fields",
            format!(
                "{}: a run records at most --max-events = {} states, so at most that many can be written",
                a.fields, a.max_events
            ),
        ));
    }
    let law = law(&a, &scene)?;
    let o = SlideOptions {
        law,
        n_force: a.n_force,
        x_max: a.x_max,
        cycles: a.cycles,
        max_events: a.max_events,
        newton: a.newton,
        ..Default::default()
    };
    tribofe::studies::slide::check_options(&scene, &o)?;
    let bar = ProgressBar::new(1000).with_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {percent}% {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(format!("slide {}", law.name()));
    let tick = |t: &tribofe::Tick| bar.set_position((t.fraction.unwrap_or(0.0) * 1000.0) as u64);
    let res = tribofe::studies::slide::run(&scene, &o, tribofe::Progress::new(&tick))?;
    bar.finish_and_clear();
    let results = [
        ("law", toml::Value::from(law.name())),
        ("mu_s", toml::Value::from(law.mu_s())),
        ("mu_d", toml::Value::from(law.mu_d())),
        ("n_force_N_per_m", toml::Value::from(a.n_force)),
        ("interface_nodes", toml::Value::from(res.condensed.n as i64)),
        ("k_bonded_N_per_m_per_m", toml::Value::from(res.run.k_bonded)),
    ];
    let header = tribofe::report::run_toml(super::invocation(), &results, &scene)?;
    let dir = super::begin_out(&a.out, a.force)?;
    tribofe::report::slide::write(&res, dir.path(), &header, true)?;
    if a.fields > 0 {
        let picks = tribofe::report::slide::field_states(&res, a.fields);
        tribofe::report::slide::write_fields(&res, &picks, dir.path(), &Default::default(), field_format)?;
    }
    dir.commit()?;
    let worst = res.run.max_violation;
    let last = res.run.states.last().ok_or_else(|| Error::input("slide", "the run recorded no state"))?;
    outln!(
        "{}: {} interface nodes, {} events ({}), {} whole-interface slips",
        law.name(),
        res.condensed.n,
        res.run.events.len(),
        tribofe::report::slide::kind_counts(&res)
            .iter()
            .map(|(k, c)| format!("{c} {k}"))
            .collect::<Vec<_>>()
            .join(", "),
        res.run.sliding_events
    );
    outln!(
        "final F/N = {:.6} at X = {:.4e} m; largest violation (equilibrium, p >= 0, gap >= 0, p gap = 0, friction) {:.1e} of N/n",
        last.f / a.n_force,
        last.x,
        worst
    );
    outln!(
        "condensation {:.3} s (S symmetric to {:.1e}, rigid motions to {:.1e}); events {:.3} s ({} bordering updates, {} full LU)",
        res.condense_s,
        res.condensed.asymmetry,
        res.condensed.rigid_residual,
        res.events_s,
        res.run.updates,
        res.run.refreshes
    );
    if let Some(o) = tribofe::studies::slide::front_offset(&res) {
        outln!(
            "slip front vs thin-layer closed form (|x_s| < 0.3 L, {} states): offset {:.3} t (range {:.3} .. {:.3} t)",
            o.samples, o.mean_t, o.min_t, o.max_t
        );
    }
    if let Some(c) = tribofe::studies::slide::compare_paper(&res) {
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
        outln!(
            "paper's iteration (r = {:.4}, g = {:.4}): n = {}, F_1 = {:.4}, x_1 = {:.4}, F_max = {:.4}",
            c.r,
            c.g,
            c.n,
            c.f1,
            c.x1,
            c.f_max
        );
        outln!(
            "FE: {} precursors before the first whole slip ({} longer than 5 t, {} advancing the front by more than 5 t), first long one F = {}, x = {}; last peak F = {}",
            c.n_fe,
            c.n_fe_long,
            c.n_fe_advancing,
            f(c.f1_fe),
            f(c.x1_fe),
            f(c.f_max_fe)
        );
    }
    outln!(
        "wrote {}/{{loading.csv, events.csv, states.csv, fig4_fe.svg, fronts.svg, run.toml{}}}",
        a.out.display(),
        match (a.fields, field_format) {
            (0, _) => "",
            (_, tribofe::io::FieldFormat::Msh) => ", fields_*.msh",
            (_, tribofe::io::FieldFormat::Both) => ", fields_*.vtu/.msh, fields.pvd",
            _ => ", fields_*.vtu, fields.pvd",
        }
    );
    Ok(())
}
