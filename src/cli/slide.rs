//! `tribofe slide`: the frictional interface loaded by N then X at height H, event by event.

use super::scene_args::SceneArgs;
use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use tribofe::law::Law;
use tribofe::report::dynamic_slide::Spacetime;
use tribofe::studies::dynamic_slide as ds;
use tribofe::studies::slide::{LawChoice, SlideOptions};
use tribofe::Error;

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Friction law: coulomb, static-kinetic, slip-weakening or rate-state (rate-and-state:
    /// --dynamics --drive-velocity only; the quasi-static solver is rate-independent).
    #[arg(long, default_value = tribofe::studies::slide::DEFAULT_LAW)]
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
    #[arg(long, default_value = tribofe::studies::slide::DEFAULT_RULE)]
    pub rule: String,
    /// Rule paper: where the slipped region's residual shear mu_d p is taken, `relaxed` (p of
    /// the relaxed equilibrium) or `pre-event` (p before the event, the paper's mu_d p(x, F_i));
    /// docs/precursors.md.
    #[arg(long, default_value = "relaxed", value_parser = ["relaxed", "pre-event"])]
    pub residual: String,
    /// Rule paper: `allowed` (a region node may end its relaxation behind where it started,
    /// counted in events.csv's backslip) or `forbidden` (such a node sticks where it started).
    #[arg(long, default_value = "allowed", value_parser = ["allowed", "forbidden"])]
    pub backslip: String,
    /// Slip-weakening distance D_c, m (slip-weakening; the coefficients as for static-kinetic).
    #[arg(long)]
    pub dc: Option<f64>,
    /// Rate-and-state (rate-state): the direct effect a, the evolution effect b (b > a: rate
    /// weakening at steady state), the state-evolution distance L (m) and the steady-state
    /// coefficient f_0 at V_0; mu = a asinh(V / (2 V_0) exp((f_0 + b ln(V_0 theta / L)) / a)).
    #[arg(long)]
    pub a: Option<f64>,
    #[arg(long)]
    pub b: Option<f64>,
    #[arg(long)]
    pub l_rs: Option<f64>,
    #[arg(long)]
    pub f0: Option<f64>,
    /// Rate-and-state's reference slip rate V_0, m/s (default 1e-6).
    #[arg(long)]
    pub v0: Option<f64>,
    /// Rate-and-state's state evolution: aging (d theta/dt = 1 - V theta / L; heals at rest)
    /// or slip (-(V theta / L) ln(V theta / L)). Default aging.
    #[arg(long)]
    pub state_law: Option<String>,
    /// Rate-and-state's initial state theta_0 on every node, s (default L / V_0: steady
    /// sliding at V_0; a hold of t_h at rest under the aging law gives about t_h).
    #[arg(long)]
    pub theta0: Option<f64>,
    /// The explicit base's normal response (--dynamics): Prakash-Clifton with a time scale T,
    /// s (d p*/dt = -(p* - p) / T). Default: instantaneous.
    #[arg(long)]
    pub normal_lag: Option<f64>,
    /// Prakash-Clifton with a slip length L, m (d p*/dt = -(p* - p)(|V| + V*) / L), in place
    /// of --normal-lag (--dynamics).
    #[arg(long, conflicts_with = "normal_lag")]
    pub normal_lag_length: Option<f64>,
    /// The length form's reference slip rate V*, m/s (default 0).
    #[arg(long)]
    pub normal_lag_v_star: Option<f64>,
    /// Normal force N, N/m (results are reported per unit N where that makes them independent of it).
    #[arg(long, default_value_t = tribofe::studies::slide::DEFAULT_N_FORCE)]
    pub n_force: f64,
    /// Largest plate displacement X at height H, m (default: 5 % past the first whole-interface
    /// slip for coulomb; the cycles for static-kinetic).
    #[arg(long)]
    pub x_max: Option<f64>,
    /// Stick-slip cycles to run, static-kinetic and slip-weakening: whole-interface slips, or
    /// also front crossings with `--cycle-end crossing` (default 10; 1 with --dynamics).
    #[arg(long)]
    pub cycles: Option<usize>,
    /// What ends a cycle: a `whole-slip` (one event slipping every contact node), or also a
    /// `crossing` (an instability completing the run of nodes slipped by instabilities since
    /// the last cycle end, trailing edge to leading edge: what `precursors fe` uses). Default
    /// whole-slip; crossing with --dynamics.
    #[arg(long, value_parser = ["whole-slip", "crossing"])]
    pub cycle_end: Option<String>,
    /// Cap on events. Each event keeps in memory its row (~0.2 kB, plus 8 bytes per run of
    /// slipping nodes) and, unless `--states none`, the interface state after it (~48 bytes
    /// per node); the cap is refused up front if that cannot fit in half the memory.
    #[arg(long, default_value_t = tribofe::studies::slide::DEFAULT_MAX_EVENTS)]
    pub max_events: usize,
    /// Slip weakening: each relaxation's coefficients by Newton where a stable equilibrium is
    /// near (the same equilibria, fewer updates; validation/friction/README.md). Default: fixed
    /// point, the reference (Newton only where a relaxation is unsettled after 10^4 iterates).
    #[arg(long)]
    pub newton: bool,
    /// How each state set is solved: `dense` (the condensed S with a bordered inverse, the
    /// reference) or `banded` (the block's sparse stiffness in x order, one reused banded LU:
    /// cost per event grows like n, not n^2; equal results to round-off). Default: banded above
    /// 200 interface nodes while (node rows through t)^2 <= nodes / 2, dense otherwise and for
    /// a mesh file (docs/speed.md); banded with --dynamics (dense with the side push). The
    /// choice and its reason are printed and written to run.toml.
    #[arg(long, value_parser = ["dense", "banded"])]
    pub operator: Option<String>,
    /// Write the whole block's fields for this many states spread evenly over the drive X, one
    /// per X (the settled state), first and last included (0: none); fields.pvd is indexed by
    /// X in m, each file holds its `event` (docs/outputs.md).
    #[arg(long, default_value_t = 0)]
    pub fields: usize,
    /// Format of the --fields files: vtu (fields_<event>.vtu + fields.pvd, ParaView), msh
    /// (fields_<event>.msh, Gmsh) or both.
    #[arg(long, default_value = "vtu", value_parser = ["vtu", "msh", "both"])]
    pub field_format: String,
    /// states.csv (the interface after every event: a row of ~95 bytes per node and event):
    /// `all` or `none`. `all` also keeps every event's state in memory (48 bytes per node and
    /// event); `none` keeps only the last state and each event's summary (every other file
    /// the same bytes; --fields refused). Default: all; none with --dynamics (a first cycle
    /// keeps ~0.7 GB of states at h = 1 mm, and the drive's samples x n rows likewise).
    #[arg(long, value_parser = ["all", "none"])]
    pub states: Option<String>,
    /// Output directory.
    #[arg(long, default_value = "out/slide")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
    /// Run each instability elastodynamically (explicit, drive held; docs/dynamics.md): the
    /// loading between events stays quasi-static and exact. Takes --law coulomb or
    /// slip-weakening: --dc defaults to the D_c giving the thin-layer stability number
    /// kappa = 0.509 (the paper's scene: 2.3107e-7 m), whatever the mesh; without --h the
    /// mesh is refined until the cohesive zone spans at least 3 elements, and a given --h
    /// that does not resolve it is refused. Defaults --cycles 1 --cycle-end crossing
    /// --states none --operator banded (the paper's first cycle, docs/dynamics.md).
    #[arg(long)]
    pub dynamics: bool,
    /// Block density, kg/m^3 (--dynamics; default the scene's [block] density, 1000).
    #[arg(long)]
    pub density: Option<f64>,
    /// Kelvin-Voigt damping eta, s (--dynamics; default 10 % of critical at the block's
    /// thickness-shear mode omega = pi c_s / (2 t)).
    #[arg(long)]
    pub damping: Option<f64>,
    /// Time step as a fraction of the stable step of the mesh and damping (--dynamics).
    #[arg(long, default_value_t = ds::DEFAULT_COURANT)]
    pub courant: f64,
    /// Drive the plate at this constant velocity, m/s, through the whole drive phase
    /// (--dynamics; needs --x-max; events read off the slip rates). Default: the drive held
    /// during each event, the loading quasi-static.
    #[arg(long)]
    pub drive_velocity: Option<f64>,
    /// The rigid plate's own mass, kg/m (--dynamics; default 0, the massless plate).
    #[arg(long)]
    pub plate_mass: Option<f64>,
    /// The plate's rotational inertia about its centre of mass at the block top's mid-point,
    /// kg m^2/m (--dynamics; default 0).
    #[arg(long)]
    pub plate_inertia: Option<f64>,
    /// After an instability (--dynamics): `all` nodes heal to mu_s (the model's rule), or only
    /// the `slipped` ones (event slip above D_c/100; the others keep their slip).
    #[arg(long, default_value = "all", value_parser = ["all", "slipped"])]
    pub heal: String,
    /// Slip-weakening coefficient updates per D_c of slip in the static loading (--dynamics;
    /// default 20, the default path). Onsets lag by up to (mu_s - mu_d) / N of the strength:
    /// on the paper's scene N = 20 to 1280 move the first onset by 4e-4 mu_s N; where a
    /// weakened zone is marginally stable much more (validation/dynamics/converge/README.md).
    /// --exact-weakening follows the weakening exactly instead.
    #[arg(long, conflicts_with = "exact_weakening")]
    pub weakening_steps: Option<f64>,
    /// The held mode's static loading follows slip weakening exactly (--dynamics --law
    /// slip-weakening): continuation in X, each onset at the fold of its equilibrium branch,
    /// no lag in N. Not the default: ~10x slower than the stepped path on the paper's scene,
    /// and it fails on (r, g) = (0.7, 0.5) (docs/speed.md). run.toml's weakening_path and
    /// summary.csv's weakening_steps (0) say it ran.
    #[arg(long)]
    pub exact_weakening: bool,
    /// When a dynamic event ends (--dynamics, held drive): `energy` (the default), at rest,
    /// the kinetic energy 1e-6 of the event's dissipation; or `slip`, once no node's slip grew
    /// by D_c/1000, nor a node opened or closed, over one thickness period: what is handed
    /// back to the static loading is then frozen (docs/speed.md, "Event end"). run.toml's
    /// event_end says which ran.
    #[arg(long, value_parser = ["energy", "slip"])]
    pub event_end: Option<String>,
    /// A refinement series at fixed physics (--dynamics): run N meshes (2 to 4), h, h/2...,
    /// D_c fixed; writes refinement.csv (each summary quantity per mesh, its spread and a
    /// converged yes/no: the two finest meshes within 0.01 mu_s N for forces, 0.02 L for
    /// positions, equal for counts) instead of one run's files.
    #[arg(long, value_name = "N")]
    pub refine: Option<usize>,
    /// Space-time pictures of the slip rate (--dynamics): `none`, `all` (one per instability,
    /// spacetime_<event>.svg) or the events.csv rows N,M,... of dynamic events
    /// (dyn_events.csv's `event`). cycle.svg, every instability of the run in one picture, is
    /// always written. Default none.
    #[arg(long, value_name = "all|none|N,M,...")]
    pub spacetime: Option<String>,
}

/// run.toml's `drive` under side push: X is the pusher's displacement, or the spring's far
/// end; F the pusher's force (None: the top plate).
fn drive(scene: &tribofe::scene::Scene) -> Option<(&'static str, toml::Value)> {
    let d = match scene.loading.push_stiffness {
        _ if scene.loading.rig.is_top_plate() => return None,
        Some(_) => "X: the far end of the pusher's spring (push_stiffness), m; F: the pusher force, N/m",
        None => "X: the pusher's displacement U_p, m; F: the pusher force, N/m",
    };
    Some(("drive", toml::Value::from(d)))
}

/// Why the run is on its operator: given, or the size rule.
fn operator_reason(a: &Args, scene: &tribofe::scene::Scene) -> String {
    match (&a.operator, tribofe::interface::events::Operator::interface_nodes(scene)) {
        (Some(_), _) => "given".into(),
        (None, _) if !scene.loading.rig.is_top_plate() => "the side push's default (dense)".into(),
        (None, _) if a.dynamics => "the --dynamics default".into(),
        (None, Some(n)) => format!(
            "default for {n} interface nodes and {} node rows through t: banded above {} nodes \
             while rows^2 <= nodes / 2",
            tribofe::interface::events::Operator::band_rows(scene),
            tribofe::interface::events::AUTO_BANDED_ABOVE
        ),
        (None, None) => "default for a mesh file (dense)".into(),
    }
}

fn law(a: &Args, scene: &tribofe::scene::Scene) -> tribofe::Result<Law> {
    law_choice(a, scene).law(scene)?.with_paper_options(paper_options(a)?)
}

/// The `paper` rule's conventions as flagged (the defaults unless --residual/--backslip given).
fn paper_options(a: &Args) -> tribofe::Result<tribofe::law::PaperOptions> {
    Ok(tribofe::law::PaperOptions { residual: a.residual.parse()?, backslip: a.backslip == "allowed" })
}

pub fn run(a: Args) -> tribofe::Result<()> {
    // The scene flags (shared with check and sweep) are applied and validated in scene_any_rig;
    // two of them belong to the bonded check and cannot act here.
    super::scene_args::refuse_inapplicable(
        &a.scene,
        &["--fn-ratios", "--tol"],
        "`slide` loads N then X until the interface slides (--n-force, --x-max); the load ratios and the edge-zone tolerance belong to `check`",
    )?;
    let scene = super::scene_args::scene_any_rig(&a.scene)?;
    if !scene.loading.rig.is_top_plate() && a.fields > 0 {
        return Err(Error::input(
            "--fields",
            "the block's fields of a side-pushed run are not written yet: drop --fields",
        ));
    }
    // The scene's [law] kind and rule where the flags (which have defaults) were not given;
    // its numbers join in law_choice.
    let mut a = a;
    if let (false, Some(k)) = (super::given("law"), &scene.law.kind) {
        a.law = k.clone();
    }
    if let (false, Some(r)) = (super::given("rule"), &scene.law.rule) {
        a.rule = r.clone();
    }
    let field_format: tribofe::io::FieldFormat = a.field_format.parse()?;
    if a.fields == 0 && field_format != tribofe::io::FieldFormat::Vtu {
        return Err(Error::input("--field-format", "acts only with --fields N (N > 0 states to write)"));
    }
    tribofe::io::outdir::check(&a.out, a.force)?;
    spacetime(&a)?;
    if !a.dynamics {
        for (flag, on) in [
            ("--density", a.density.is_some()),
            ("--damping", a.damping.is_some()),
            ("--courant", super::given("courant")),
            ("--drive-velocity", a.drive_velocity.is_some()),
            ("--plate-mass", a.plate_mass.is_some()),
            ("--plate-inertia", a.plate_inertia.is_some()),
            ("--heal", super::given("heal")),
            ("--normal-lag", a.normal_lag.is_some()),
            ("--normal-lag-length", a.normal_lag_length.is_some()),
            ("--normal-lag-v-star", a.normal_lag_v_star.is_some()),
            ("--weakening-steps", a.weakening_steps.is_some()),
            ("--exact-weakening", a.exact_weakening),
            ("--event-end", a.event_end.is_some()),
            ("--refine", a.refine.is_some()),
            ("--spacetime", a.spacetime.is_some()),
        ] {
            if on {
                return Err(Error::input(flag, "acts only with --dynamics"));
            }
        }
    }
    if a.dynamics && a.law == "slip-weakening" {
        let mut a = a;
        let mut scene = scene;
        resolve_physics(&mut a, &mut scene)?;
        return run_checked(a, scene, field_format);
    }
    run_checked(a, scene, field_format)
}

/// Physics is input, resolution is checked (`--dynamics --law slip-weakening`): the library's
/// choice of D_c and h ([`tribofe::studies::dynamic_slide::physics::resolve`]), its notes on
/// stderr.
fn resolve_physics(a: &mut Args, scene: &mut tribofe::scene::Scene) -> tribofe::Result<()> {
    let given = a.scene.has("--h") || super::scene_args::file_sets(&a.scene, "mesh", "h")?;
    let r = tribofe::studies::dynamic_slide::physics::resolve(
        scene,
        &law_choice(a, scene),
        a.n_force,
        given,
        ["--dc", "--h"],
    )?;
    a.dc = r.law.dc();
    for note in &r.notes {
        errln!("{note}");
    }
    Ok(())
}

/// `--spacetime` as given (refused before any work if it does not parse).
fn spacetime(a: &Args) -> tribofe::Result<Spacetime> {
    let s = a.spacetime.as_deref().map_or(Ok(Spacetime::None), str::parse)?;
    if a.refine.is_some() && s != Spacetime::None {
        return Err(Error::input(
            "--spacetime",
            "acts on one run's files; --refine writes refinement.csv only",
        ));
    }
    Ok(s)
}

fn law_choice(a: &Args, scene: &tribofe::scene::Scene) -> LawChoice {
    LawChoice {
        law: a.law.clone(),
        mu: a.mu,
        mu_s: a.mu_s,
        mu_d: a.mu_d,
        r: a.r,
        g: a.g,
        rule: a.rule.clone(),
        dc: a.dc,
        rate_state: tribofe::studies::slide::RateStateChoice {
            a: a.a,
            b: a.b,
            l_rs: a.l_rs,
            v0: a.v0,
            f0: a.f0,
            state_law: a.state_law.clone(),
            theta0: a.theta0,
        },
        ..Default::default()
    }
    .with_scene(&scene.law, true, true)
}

fn run_checked(
    a: Args,
    mut scene: tribofe::scene::Scene,
    field_format: tribofe::io::FieldFormat,
) -> tribofe::Result<()> {
    if let Some(rho) = a.density {
        scene.block.density = rho;
        scene.validate()?;
    }
    // --write-scene: with the density and the h chosen by resolve_physics.
    super::scene_args::update_pending_scene(&scene)?;
    if a.dc.is_some() && a.law != "slip-weakening" {
        return Err(Error::input("dc", "--dc belongs to --law slip-weakening"));
    }
    law_choice(&a, &scene).check_rule_options(
        super::given("rule"),
        super::given("residual"),
        super::given("backslip"),
    )?;
    if a.newton && a.law != "slip-weakening" {
        return Err(Error::input("newton", "--newton cannot act without --law slip-weakening"));
    }
    // Whether every event's state is kept in memory: only for states.csv and --fields.
    let keep_states = a.states.as_deref().map_or(!a.dynamics, |s| s == "all");
    if a.fields > 0 && a.states.as_deref() == Some("none") {
        return Err(Error::input(
            "--fields",
            "needs every event's state, which `--states none` does not keep: drop --fields or --states none",
        ));
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
        cycles: a.cycles.unwrap_or(if a.dynamics {
            ds::DEFAULT_CYCLES
        } else {
            SlideOptions::default().cycles
        }),
        end_at_crossing: a
            .cycle_end
            .as_deref()
            .map_or(a.dynamics && ds::DEFAULT_END_AT_CROSSING, |c| c == "crossing"),
        max_events: a.max_events,
        keep_states,
        newton: a.newton,
        operator: match a.operator.as_deref() {
            Some("banded") => tribofe::interface::events::Operator::Banded,
            Some(_) => tribofe::interface::events::Operator::Dense,
            None if a.dynamics => ds::default_operator(&scene),
            None => tribofe::interface::events::Operator::for_scene(&scene),
        },
        ..Default::default()
    };
    if a.dynamics {
        // Its own checks (the quasi-static ones on the law's rate-free stand-in under the
        // constant-velocity drive) come first in the run.
        return run_dynamic(&a, &scene, o);
    }
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
        ("operator", toml::Value::from(o.operator.name())),
        ("operator_reason", toml::Value::from(operator_reason(&a, &scene))),
    ];
    let results: Vec<(&str, toml::Value)> = results.into_iter().chain(drive(&scene)).collect();
    let header = tribofe::report::run_toml(super::invocation(), &results, &scene)?;
    let dir = super::begin_out(&a.out, a.force)?;
    let states = res.options.keep_states;
    tribofe::report::slide::write(&res, dir.path(), &header, states)?;
    if a.fields > 0 {
        let picks = tribofe::report::slide::field_states(&res, a.fields);
        tribofe::report::slide::write_fields(&res, &picks, dir.path(), &Default::default(), field_format)?;
    }
    dir.commit()?;
    let worst = res.run.max_violation;
    let last = res.run.summaries.last().ok_or_else(|| Error::input("slide", "the run recorded no state"))?;
    outln!(
        "{}: {} interface nodes, {} events ({}), {} cycles ended (whole-interface slips, or crossings with --cycle-end crossing)",
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
    outln!("operator: {} ({})", res.options.operator.name(), operator_reason(&a, &scene));
    if res.options.operator == tribofe::interface::events::Operator::Banded {
        outln!(
            "banded operator {:.3} s (K symmetric to {:.1e}, rigid motions to {:.1e}); events {:.3} s ({} banded factorisations, {} low-rank row updates)",
            res.condense_s,
            res.condensed.asymmetry,
            res.condensed.rigid_residual,
            res.events_s,
            res.run.refreshes,
            res.run.updates
        );
    } else {
        outln!(
            "condensation {:.3} s (S symmetric to {:.1e}, rigid motions to {:.1e}); events {:.3} s ({} bordering updates, {} full LU)",
            res.condense_s,
            res.condensed.asymmetry,
            res.condensed.rigid_residual,
            res.events_s,
            res.run.updates,
            res.run.refreshes
        );
    }
    if let Some(o) = tribofe::studies::slide::front_offset(&res) {
        outln!(
            "slip front vs thin-layer closed form (|x_s| < 0.3 L, {} states): offset {:.3} t (range {:.3} .. {:.3} t)",
            o.samples, o.mean_t, o.min_t, o.max_t
        );
    }
    print_paper_comparison("FE", &res)?;
    outln!(
        "wrote {}/{{loading.csv, events.csv, {}{}fig4_fe.svg, fronts.svg, run.toml{}}}",
        a.out.display(),
        if law.weakens() { "advances.csv, " } else { "" },
        if states { "states.csv, " } else { "" },
        match (a.fields, field_format) {
            (0, _) => "",
            (_, tribofe::io::FieldFormat::Msh) => ", fields_*.msh",
            (_, tribofe::io::FieldFormat::Both) => ", fields_*.vtu/.msh, fields.pvd",
            _ => ", fields_*.vtu, fields.pvd",
        }
    );
    Ok(())
}

/// `slide --dynamics`: the library's dynamic run, its files and a summary.
fn run_dynamic(a: &Args, scene: &tribofe::scene::Scene, o: SlideOptions) -> tribofe::Result<()> {
    if a.fields > 0 {
        return Err(Error::input("--fields", "not written by --dynamics yet"));
    }
    let base = ds::DynamicOptions::default();
    // The held mode's stepped coefficients unless --exact-weakening (docs/speed.md).
    let o = SlideOptions {
        weakening: ds::weakening(a.exact_weakening, a.weakening_steps.is_some(), &o, a.drive_velocity)?,
        ..o
    };
    let d = ds::DynamicOptions {
        damping: a.damping,
        courant: a.courant,
        drive_velocity: a.drive_velocity,
        plate_mass: a.plate_mass.unwrap_or(base.plate_mass),
        plate_inertia: a.plate_inertia.unwrap_or(base.plate_inertia),
        heal_slipped_only: a.heal == "slipped",
        weakening_steps: ds::weakening_steps(a.weakening_steps, &o, a.drive_velocity)?,
        event_end: ds::event_end(a.event_end.as_deref().map(str::parse).transpose()?, a.drive_velocity)?,
        normal: scene.law.normal([a.normal_lag, a.normal_lag_length, a.normal_lag_v_star])?,
        ..Default::default()
    };
    if let Some(levels) = a.refine {
        return run_refinement(a, scene, &o, &d, levels);
    }
    let clock = std::time::Instant::now();
    let shown = std::sync::atomic::AtomicI64::new(-1);
    // The fraction redraws one line: only on a terminal (a log gets the messages alone).
    let tty = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let tick = |t: &tribofe::Tick| match t.fraction {
        Some(_) if !tty => {}
        Some(f) => {
            let pm = (1000.0 * f) as i64;
            if shown.swap(pm, std::sync::atomic::Ordering::Relaxed) != pm {
                err!("\rslide --dynamics {:5.1} %", 0.1 * pm as f64);
            }
        }
        None => errln!("\r{}", t.message),
    };
    let res = ds::run(scene, &o, &d, tribofe::Progress::new(&tick))?;
    if tty {
        errln!();
    }
    let law = o.law;
    let results = [
        ("law", toml::Value::from(law.name())),
        ("mu_s", toml::Value::from(law.mu_s())),
        ("mu_d", toml::Value::from(law.mu_d())),
        ("n_force_N_per_m", toml::Value::from(a.n_force)),
        ("interface_nodes", toml::Value::from(res.slide.condensed.n as i64)),
        ("k_bonded_N_per_m_per_m", toml::Value::from(res.slide.run.k_bonded)),
        ("operator", toml::Value::from(o.operator.name())),
        ("operator_reason", toml::Value::from(operator_reason(a, scene))),
        ("dynamics", toml::Value::from(true)),
        ("density_kg_per_m3", toml::Value::from(scene.block.density)),
        ("damping_eta_s", toml::Value::from(res.eta)),
        ("damping_ratio_thickness_mode", toml::Value::from(res.xi_thickness)),
        ("dt_s", toml::Value::from(res.dt)),
        ("dt_stable_s", toml::Value::from(res.dt_stable)),
        ("dynamic_steps", toml::Value::from(res.steps as i64)),
        ("drive_velocity_m_per_s", toml::Value::from(a.drive_velocity.unwrap_or(0.0))),
        ("plate_mass_kg_per_m", toml::Value::from(d.plate_mass)),
        ("plate_inertia_kg_m2_per_m", toml::Value::from(d.plate_inertia)),
        ("normal_response", toml::Value::from(d.normal.name())),
        ("weakening_path", toml::Value::from(ds::held_weakening(&o, &d).map_or("none", |w| w.name()))),
        (
            "event_end",
            toml::Value::from(if a.drive_velocity.is_some() { "none" } else { d.event_end.name() }),
        ),
        // What the run cost, phase by phase (wall s; writing follows): `cargo bench --bench
        // dynamic_refine` reads them.
        ("setup_wall_s", toml::Value::from(res.setup_s)),
        ("static_wall_s", toml::Value::from(res.static_s)),
        ("dynamic_wall_s", toml::Value::from(res.dynamic_s)),
        ("static_factorisations", toml::Value::from(res.slide.run.refreshes as i64)),
    ];
    // summary.csv's row, NaN (a quantity the run does not have) left out, and the cap if met.
    let summary = ds::summary::COLUMNS.iter().zip(ds::summary::values(&res));
    let mut results: Vec<(&str, toml::Value)> = results.into_iter().chain(drive(scene)).collect();
    results.extend(summary.filter(|(_, v)| v.is_finite()).map(|(c, v)| (c.0, toml::Value::from(v))));
    if let Some(why) = &res.incomplete {
        results.push(("incomplete", toml::Value::from(why.as_str())));
    }
    let header = tribofe::report::run_toml(super::invocation(), &results, scene)?;
    let dir = super::begin_out(&a.out, a.force)?;
    let writing = std::time::Instant::now();
    // states.csv whenever the run kept its states (`--states`; the constant-velocity drive's
    // ~2000 samples x n rows are kept only when asked for, see run_checked).
    let states = o.keep_states;
    let pictures = spacetime(a)?;
    tribofe::report::dynamic_slide::write(&res, dir.path(), &header, states, &pictures)?;
    dir.commit()?;
    let missing = pictures.missing(&res);
    if !missing.is_empty() {
        eprintln!(
            "--spacetime: events.csv rows {missing:?} are no dynamic event of this run (dyn_events.csv's `event` lists them); not drawn"
        );
    }
    let written_s = writing.elapsed().as_secs_f64();
    let run = &res.slide.run;
    let inst = res.events.iter().filter(|e| e.record.weakened).count();
    outln!(
        "{} --dynamics: {} interface nodes, {} events ({}), {} dynamic ({} instabilities), {} cycles ended (whole-interface slips, or crossings with --cycle-end crossing)",
        law.name(),
        res.slide.condensed.n,
        run.events.len(),
        tribofe::report::slide::kind_counts(&res.slide)
            .iter()
            .map(|(k, c)| format!("{c} {k}"))
            .collect::<Vec<_>>()
            .join(", "),
        res.events.len(),
        inst,
        run.sliding_events
    );
    outln!(
        "dt = {:.4e} s ({:.2} of the stable {:.4e} s), eta = {:.4e} s ({:.3} of critical at the thickness mode), {} DOFs, {} explicit steps",
        res.dt,
        a.courant,
        res.dt_stable,
        res.eta,
        res.xi_thickness,
        res.dofs,
        res.steps
    );
    print_paper_comparison("dynamics", &res.slide)?;
    if let Some(v) = a.drive_velocity {
        outln!(
            "drive at V = {v:e} m/s: events where some slip rate exceeds {:.3e} m/s; wall time {:.2} s (setup {:.2} s, normal phase {:.2} s, explicit drive {:.2} s, {:.3e} DOF-updates/s wall)",
            ds::velocity::event_threshold(scene, &o, v)?,
            clock.elapsed().as_secs_f64(),
            res.setup_s,
            res.static_s,
            res.dynamic_s,
            res.steps as f64 * res.dofs as f64 / res.dynamic_s.max(f64::MIN_POSITIVE)
        );
    } else {
        let worst_gap = res.events.iter().map(|e| e.f_gap).fold(0.0, f64::max);
        outln!(
            "largest |F_dynamic - F_static| at an event's end {:.2e} mu_s N; wall time {:.2} s (setup {:.2} s, static loading {:.2} s on the {} operator: {}, dynamic events {:.2} s, writing {:.2} s)",
            worst_gap,
            clock.elapsed().as_secs_f64(),
            res.setup_s,
            res.static_s,
            o.operator.name(),
            match o.operator {
                tribofe::interface::events::Operator::Banded => format!("{} banded LU solves", run.refreshes),
                _ => format!("{} bordering updates, {} full LU", run.updates, run.refreshes),
            },
            res.dynamic_s,
            written_s
        );
    }
    print_summary(&res)?;
    if let Some(&(x, f)) = run.folds.first() {
        outln!(
            "exact weakening path: {} onsets at the end of their equilibrium branch; the first at X = {x:.8e} m, F/(mu_s N) = {:.8} (its dynamic event starts just past it)",
            run.folds.len(),
            f / (law.mu_s() * a.n_force)
        );
    }
    outln!(
        "wrote {}/{{summary.csv, loading.csv, events.csv, {}{}fig4_fe.svg, fronts.svg, fronts_t.csv, dyn_events.csv, cycle.svg, {}run.toml}}",
        a.out.display(),
        if law.weakens() { "advances.csv, " } else { "" },
        if states { "states.csv, " } else { "" },
        match pictures.picks(&res).len() {
            0 => String::new(),
            n => format!("{n} spacetime_*.svg, "),
        }
    );
    match res.incomplete {
        Some(what) => Err(Error::Incomplete { what }),
        None => Ok(()),
    }
}

/// `--refine N`: the series, refinement.csv and run.toml, and the verdicts printed.
fn run_refinement(
    a: &Args,
    scene: &tribofe::scene::Scene,
    o: &SlideOptions,
    d: &ds::DynamicOptions,
    levels: usize,
) -> tribofe::Result<()> {
    if a.drive_velocity.is_some() {
        return Err(Error::input("--refine", "runs the held mode's series; not with --drive-velocity"));
    }
    let tick = |t: &tribofe::Tick| {
        if t.fraction.is_none() && t.message.starts_with("refinement") {
            errln!("{}", t.message);
        }
    };
    let r = ds::refine::refine(scene, o, d, levels, tribofe::Progress::new(&tick))?;
    let mut results: Vec<(&str, toml::Value)> = vec![
        ("refinement_h_m", toml::Value::Array(r.h.iter().map(|&h| toml::Value::from(h)).collect())),
        ("wall_s", toml::Value::Array(r.seconds.iter().map(|&h| toml::Value::from(h)).collect())),
        ("force_tolerance_over_mu_s_N", toml::Value::from(ds::refine::FORCE_TOL)),
        ("position_tolerance_over_L", toml::Value::from(ds::refine::POSITION_TOL)),
    ];
    if let Some(why) = &r.incomplete {
        results.push(("incomplete", toml::Value::from(why.as_str())));
    }
    let header = tribofe::report::run_toml(super::invocation(), &results, scene)?;
    let dir = super::begin_out(&a.out, a.force)?;
    tribofe::report::write_atomic(
        &dir.path().join("refinement.csv"),
        tribofe::report::dynamic_slide::refinement_csv(&r)?.as_bytes(),
    )?;
    tribofe::report::write_atomic(&dir.path().join("run.toml"), header.as_bytes())?;
    dir.commit()?;
    outln!(
        "refinement at fixed physics, h = {} m (converged: the two finest within {} mu_s N for forces, {} L for positions, equal for counts):",
        r.h.iter().map(|h| format!("{h:.4e}")).collect::<Vec<_>>().join(", "),
        ds::refine::FORCE_TOL,
        ds::refine::POSITION_TOL
    );
    for v in r.verdicts() {
        outln!(
            "  {:<40} {}  spread {:.4}  converged {}",
            v.name,
            v.values
                .iter()
                .map(|&x| match x {
                    x if !x.is_finite() => format!("{:>8}", "-"),
                    x if x.fract() == 0.0 => format!("{x:>8}"),
                    x => format!("{x:>8.4}"),
                })
                .collect::<Vec<_>>()
                .join(" "),
            v.spread,
            match v.converged {
                Some(true) => "yes",
                Some(false) => "no",
                None => "-",
            }
        );
    }
    outln!("wrote {}/{{refinement.csv, run.toml}}", a.out.display());
    match r.incomplete {
        Some(what) => Err(Error::Incomplete { what }),
        None => Ok(()),
    }
}

/// summary.csv as a table, 4 significant digits, with what converges said beside each row.
fn print_summary(res: &ds::DynamicResult) -> tribofe::Result<()> {
    outln!("summary (summary.csv; converged quantities per validation/dynamics/converge):");
    for (c, v) in ds::summary::COLUMNS.iter().zip(ds::summary::values(res)) {
        let shown = match v {
            v if !v.is_finite() => "-".to_string(),
            v if v.fract() == 0.0 && v.abs() < 1e6 => format!("{v}"),
            v if v != 0.0 && (v.abs() < 1e-2 || v.abs() >= 1e4) => format!("{v:.4e}"),
            v => format!("{v:.4}"),
        };
        outln!("  {:<40} {:>12}  {}", c.0, shown, c.1);
    }
    Ok(())
}

/// The run's precursors (one definition, printed with them) beside the paper's iteration.
fn print_paper_comparison(label: &str, res: &tribofe::studies::slide::SlideResult) -> tribofe::Result<()> {
    let Some(c) = tribofe::studies::slide::compare_paper(res) else { return Ok(()) };
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
        "{label}: n = {} (advancing; of {} precursors, {} longer than 5 t), F_1 = {}, x_1 = {}; last peak F = {}",
        c.n_fe_advancing,
        c.n_fe,
        c.n_fe_long,
        f(c.f1_fe),
        f(c.x1_fe),
        f(c.f_max_fe)
    );
    outln!(
        "{label}: front advances n = {}, first at F = {}, front x = {} (counted from the {} edge, where slip nucleates)",
        c.n_front,
        f(c.f1_front),
        f(c.x1_front),
        tribofe::studies::slide::nucleating_edge(res).name()
    );
    outln!("{}", tribofe::precursors::definition::DEFINITION);
    outln!("{}", tribofe::precursors::definition::ADVANCES);
    Ok(())
}
