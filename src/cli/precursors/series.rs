//! `precursors thin-layer`, `heights` and `dc`: the `paper` rule against the model over one
//! parameter (t/L, H/L, or the event rule's D_c).

use super::{counter, fe_scene, write_whole, OutArgs, RgArgs};
use tribofe::precursors::{self, Params};
use tribofe::report::precursors as report;
use tribofe::Error;

#[derive(clap::Args, Debug)]
pub struct ThinLayerArgs {
    /// The blocks' t/L, comma separated (e.g. 0.02,0.01,0.005,0.0025,0.00125); each run at the
    /// scene's L and H/L, h = t with 2 elements through t.
    #[arg(long, value_delimiter = ',', required = true, value_name = "LIST")]
    pub t_over_l: Vec<f64>,
    #[command(flatten)]
    pub rg: RgArgs,
    #[command(flatten)]
    pub scene: super::super::check::SceneArgs,
    #[command(flatten)]
    pub out: OutArgs,
}

#[derive(clap::Args, Debug)]
pub struct HeightsArgs {
    /// The heights H/L, comma separated (g = 6 mu_d H/L must stay below 1).
    #[arg(long, value_delimiter = ',', required = true, value_name = "LIST")]
    pub h_over_l: Vec<f64>,
    /// (r, g) give the coefficients mu_s, mu_d at the scene's H, kept fixed over H/L.
    #[command(flatten)]
    pub rg: RgArgs,
    #[command(flatten)]
    pub scene: super::super::check::SceneArgs,
    #[command(flatten)]
    pub out: OutArgs,
}

#[derive(clap::Args, Debug)]
pub struct DcArgs {
    /// Slip-weakening distances D_c, m, comma separated, one run each beside the `paper` rule.
    /// Resolved when the nucleation length G D_c/((mu_s - mu_d) N/L) spans h.
    #[arg(long, value_delimiter = ',', required = true, value_name = "LIST")]
    pub dc: Vec<f64>,
    #[command(flatten)]
    pub rg: RgArgs,
    /// Events per run before the run is refused.
    #[arg(long, default_value_t = tribofe::studies::precursors_fe::DEFAULT_DC_MAX_EVENTS)]
    pub max_events: usize,
    #[command(flatten)]
    pub scene: super::super::check::SceneArgs,
    #[command(flatten)]
    pub out: OutArgs,
}

/// The thin-layer limit: the `paper` rule at (r, g) over t/L against the model.
pub fn thin_layer(args: ThinLayerArgs) -> tribofe::Result<()> {
    use tribofe::studies::precursors_fe as pfe;
    let ts = args.t_over_l.clone();
    let a = &args.scene;
    for (flag, given) in [
        ("--thickness", a.thickness.is_some()),
        ("--h", a.h.is_some()),
        ("--n-thick", a.n_thick.is_some()),
        ("--grading", a.grading.is_some()),
        ("--h-max", a.h_max.is_some()),
    ] {
        if given {
            return Err(Error::input(flag, "cannot act in `precursors thin-layer`, which sets t = (t/L) L, h = t and 2 elements through t per run (--t-over-l)"));
        }
    }
    let p = Params::new(args.rg.r, args.rg.g)?;
    let scene = fe_scene(&args.scene, &args.out)?;
    let bar = counter(ts.len(), "thicknesses");
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let rows =
        pfe::thin_layer(&scene, p.r(), p.g(), &ts, &tribofe::Cancel::new(), tribofe::Progress::new(&tick))?;
    bar.finish_and_clear();
    let n = precursors::n_precursors(&p)?;
    outln!(
        "thin-layer limit, rule paper, (r, g) = ({}, {}), H/L = {:.4}; F in units of mu_s N, x in units of L",
        p.r(),
        p.g(),
        scene.loading.height / scene.block.length
    );
    outln!(
        "{:>9} {:>6} {:>9} {:>9} {:>9} {:>10} {:>11} {:>9}",
        "t/L",
        "n adv",
        "F_1",
        "x_1",
        "F_max",
        "F_corner",
        "violation",
        "time, s"
    );
    let x1 = precursors::simulate(&p, 1)[0].x;
    outln!(
        "{:>9} {n:>6} {:>9.4} {:>9.4} {:>9.4} {:>10} {:>11} {:>9}",
        "model",
        p.f1(),
        x1,
        p.f_max(),
        "-",
        "-",
        "-"
    );
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for row in &rows {
        match &row.fig4 {
            Ok(r) => outln!(
                "{:>9} {:>6} {:>9} {:>9} {:>9} {:>10} {:>11.1e} {:>9.1}",
                row.value,
                r.cmp.n_fe_advancing,
                f(r.cmp.f1_fe),
                f(r.cmp.x1_fe),
                f(r.cmp.f_max_fe),
                f(r.fields.f_corner),
                r.worst_violation,
                row.seconds
            ),
            Err(e) => outln!("{:>9} refused: {e}", row.value),
        }
    }
    outln!("{}", tribofe::precursors::definition::DEFINITION);
    outln!(
        "mesh: h = t with 2 elements through t at every t/L; the scene's own mesh (h = {:.4} t) gives other numbers at its t/L = {:.4}: `precursors fe` runs that one",
        scene.mesh.h / scene.block.thickness,
        scene.block.thickness / scene.block.length
    );
    for lim in pfe::thin_layer_limits(&rows) {
        let (name, model) = (lim.name, lim.model);
        let offset = |v: f64| {
            if name == "x_1" {
                format!("{:+.4} L", v - model)
            } else {
                format!("{:+.2} %", 100.0 * (v / model - 1.0))
            }
        };
        match (lim.order_limit, lim.finest) {
            (Some((p, v)), _) => outln!(
                "{name}: observed order {p:.2} in t/L, limit {v:.4}, offset from the model {}",
                offset(v)
            ),
            (None, Some(v)) => outln!(
                "{name}: no asymptotic range in the last three t/L; finest {v:.4}, offset from the model {}",
                offset(v)
            ),
            (None, None) => outln!("{name}: -"),
        }
    }
    write_whole(&args.out.out, args.out.force, |dir, inv| {
        report::write_thin_layer(dir, &p, &rows, inv, &scene)
    })?;
    outln!("wrote {}/{{thin_layer.csv, thin_layer.svg, run.toml}}", args.out.out.display());
    Ok(())
}

/// The height of the drive: the `paper` rule at fixed coefficients over H/L against the model.
pub fn heights(args: HeightsArgs) -> tribofe::Result<()> {
    let hs = args.h_over_l.clone();
    let p = Params::new(args.rg.r, args.rg.g)?;
    let scene = fe_scene(&args.scene, &args.out)?;
    let mu = tribofe::studies::slide::coefficients_from_rg(&scene, p.r(), p.g())?;
    let bar = counter(hs.len(), "heights");
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let rows = tribofe::studies::precursors_fe::heights(
        &scene,
        p.r(),
        p.g(),
        &hs,
        &tribofe::Cancel::new(),
        tribofe::Progress::new(&tick),
    )?;
    bar.finish_and_clear();
    outln!(
        "height of the drive, rule paper, mu_s = {:.4}, mu_d = {:.4} (r = {}), t/L = {:.4}; F in units of mu_s N, x in units of L",
        mu.0,
        mu.1,
        p.r(),
        scene.block.thickness / scene.block.length
    );
    outln!(
        "{:>7} {:>6} {:>13} {:>17} {:>17} {:>17} {:>9}",
        "H/L",
        "g",
        "n model/FE",
        "F_1 model/FE",
        "x_1 model/FE",
        "F_max model/FE",
        "violation"
    );
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for row in &rows {
        match &row.fig4 {
            Ok(r) => {
                let c = &r.cmp;
                outln!(
                    "{:>7.4} {:>6.4} {:>6}/{:<6} {:>8.4}/{:<8} {:>8.4}/{:<8} {:>8.4}/{:<8} {:>9.1e}",
                    row.value,
                    c.g,
                    c.n,
                    c.n_fe_advancing,
                    c.f1,
                    f(c.f1_fe),
                    c.x1,
                    f(c.x1_fe),
                    c.f_max,
                    f(c.f_max_fe),
                    r.worst_violation
                );
            }
            Err(e) => outln!("{:>7.4} refused: {e}", row.value),
        }
    }
    outln!("n: the count to compare with the model's n; {}", tribofe::precursors::definition::DEFINITION);
    write_whole(&args.out.out, args.out.force, |dir, inv| {
        report::write_heights(dir, mu, &rows, inv, &scene)
    })?;
    outln!("wrote {}/{{heights.csv, heights.svg, run.toml}}", args.out.out.display());
    Ok(())
}

/// Event rule and D_c: the `paper` rule and slip-weakening with each D_c at (r, g).
pub fn dc(args: DcArgs) -> tribofe::Result<()> {
    let dcs = args.dc.clone();
    let p = Params::new(args.rg.r, args.rg.g)?;
    let scene = fe_scene(&args.scene, &args.out)?;
    let (ms, md) = tribofe::studies::slide::coefficients_from_rg(&scene, p.r(), p.g())?;
    let bar = counter(dcs.len() + 1, "runs");
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let rows = tribofe::studies::precursors_fe::dc_series(
        &scene,
        p.r(),
        p.g(),
        &dcs,
        args.max_events,
        &tribofe::Cancel::new(),
        tribofe::Progress::new(&tick),
    )?;
    bar.finish_and_clear();
    let b = &scene.block;
    // dc_series runs at the default normal force.
    let n_force = tribofe::studies::slide::SlideOptions::default().n_force;
    outln!(
        "event rule and D_c at (r, g) = ({}, {}): mu_s = {ms:.4}, mu_d = {md:.4}, t/L = {:.4}, h = {:e} m; F in units of mu_s N, x in units of L",
        p.r(),
        p.g(),
        b.thickness / b.length,
        scene.mesh.h
    );
    outln!(
        "{:>9} {:>8} {:>7} {:>10} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8}",
        "D_c, m",
        "kappa",
        "L_c/h",
        "Appendix",
        "n adv",
        "F_1",
        "x_1",
        "F_max",
        "events",
        "time, s"
    );
    let x1 = precursors::simulate(&p, 1)[0].x;
    outln!(
        "{:>9} {:>8} {:>7} {:>10} {:>6} {:>8.4} {:>8.4} {:>8.4} {:>8} {:>8}",
        "model",
        "-",
        "-",
        "-",
        precursors::n_precursors(&p)?,
        p.f1(),
        x1,
        p.f_max(),
        "-",
        "-"
    );
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for row in &rows {
        let d = row.value;
        let (name, kappa, lch, appendix) = if d == 0.0 {
            ("paper".to_string(), "-".to_string(), "-".to_string(), "-".to_string())
        } else {
            let (kappa, lch, appendix) =
                tribofe::studies::precursors_fe::dc_scales(&scene, ms, md, n_force, d);
            (format!("{d:.1e}"), format!("{kappa:.3}"), format!("{lch:.2}"), format!("{appendix:.2e}"))
        };
        match &row.fig4 {
            Ok(r) => outln!(
                "{name:>9} {kappa:>8} {lch:>7} {appendix:>10} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8.1}",
                r.cmp.n_fe_advancing,
                f(r.cmp.f1_fe),
                f(r.cmp.x1_fe),
                f(r.cmp.f_max_fe),
                r.run.run.events.len(),
                row.seconds
            ),
            Err(e) => outln!("{name:>9} {kappa:>8} {lch:>7} {appendix:>10} refused: {e}"),
        }
    }
    outln!("{}", tribofe::precursors::definition::DEFINITION);
    outln!("kappa = G D_c/((mu_s - mu_d) p t) (stable above 1); L_c = kappa t, the nucleation length; Appendix: (E/p)(D_c/t)(mu_s - mu_d)/(2 mu_d), the excess mu(x) - mu_d below which the Appendix's Griffith argument lets a front arrest");
    write_whole(&args.out.out, args.out.force, |dir, inv| report::write_dc(dir, &rows, inv, &scene))?;
    outln!("wrote {}/{{dc.csv, dc.svg, run.toml, paper/, dc_<D_c>/}}", args.out.out.display());
    Ok(())
}
