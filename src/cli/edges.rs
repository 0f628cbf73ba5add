//! `tribofe edges`: the block's ends on the frictional interface (pre-slip under N alone
//! against refinement; the trailing end's opening against the first precursor).

use super::scene_args::{scene as scene_from, SceneArgs};
use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::sync::LazyLock;
use tribofe::law::Rule;
use tribofe::studies::edges::{self as edges, EdgesOptions};

/// A list default of the library as the flag's text (`0.3,0.65`).
fn list<T: ToString>(v: &[T]) -> String {
    v.iter().map(T::to_string).collect::<Vec<_>>().join(",")
}
static MU: LazyLock<String> = LazyLock::new(|| list(&edges::DEFAULT_MU));
static REFINE: LazyLock<String> = LazyLock::new(|| list(&edges::DEFAULT_REFINE));
static T_OVER_L: LazyLock<String> = LazyLock::new(|| list(&edges::DEFAULT_T_OVER_L));
static OPEN_REFINE: LazyLock<String> = LazyLock::new(|| list(&edges::DEFAULT_OPEN_REFINE));
static H_OVER_L: LazyLock<String> = LazyLock::new(|| list(&edges::DEFAULT_H_OVER_L));

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Coulomb coefficients of the pre-slip study.
    #[arg(long, value_delimiter = ',', default_value = MU.as_str())]
    pub mu: Vec<f64>,
    /// Elements through the thickness (t/h, uniform mesh) of the pre-slip study.
    #[arg(long, value_delimiter = ',', default_value = REFINE.as_str())]
    pub refine: Vec<usize>,
    /// Static and kinetic coefficients of the opening study (default: the paper's r = 0.9,
    /// g = 0.35 at H/L = 0.1: mu_s = 0.6481, mu_d = 0.5833).
    #[arg(long, default_value_t = edges::DEFAULT_MU_S)]
    pub mu_s: f64,
    #[arg(long, default_value_t = edges::DEFAULT_MU_D)]
    pub mu_d: f64,
    /// Event rule of the opening study: paper or overdamped.
    #[arg(long, default_value = edges::DEFAULT_RULE.name())]
    pub rule: String,
    /// Thickness ratios t/L of the opening study.
    #[arg(long, value_delimiter = ',', default_value = T_OVER_L.as_str())]
    pub t_over_l: Vec<f64>,
    /// Elements through the thickness (t/h) of the opening study.
    #[arg(long, value_delimiter = ',', default_value = OPEN_REFINE.as_str())]
    pub open_refine: Vec<usize>,
    /// Growth ratio of the element length along x from h = t/(t/h) at both ends up to t/2 in
    /// the middle, for both studies; 1: uniform meshes with h = t/(t/h) everywhere (the
    /// committed validation/edges study).
    #[arg(long, default_value_t = edges::DEFAULT_END_GRADING)]
    pub end_grading: f64,
    /// Drive heights H/L of the opening study.
    #[arg(long, value_delimiter = ',', default_value = H_OVER_L.as_str())]
    pub h_over_l: Vec<f64>,
    #[arg(long, default_value = "out/edges")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
}

pub fn run(a: Args) -> tribofe::Result<()> {
    super::scene_args::refuse_inapplicable(
        &a.scene,
        &["--h", "--grading", "--h-max", "--n-thick", "--height", "--fn-ratios", "--tol", "--mesh", "--geometry"],
        "`edges` builds its own meshes: --refine (pre-slip) and --t-over-l (h = t/2), the heights from --h-over-l",
    )?;
    let scene = scene_from(&a.scene)?;
    let rule: Rule = a.rule.parse()?;
    let o = EdgesOptions {
        mu: a.mu.clone(),
        refine: a.refine.clone(),
        mu_s: a.mu_s,
        mu_d: a.mu_d,
        rule,
        t_over_l: a.t_over_l.clone(),
        open_refine: a.open_refine.clone(),
        h_over_l: a.h_over_l.clone(),
        end_grading: a.end_grading,
    };
    o.check(&scene)?;
    tribofe::io::outdir::check(&a.out, a.force)?;
    let grading = o.grading();
    let len = (o.refine.len() + o.runs()) as u64;
    let bar = ProgressBar::new(len).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} meshes and runs, {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let tick = |t: &tribofe::Tick| bar.set_position((t.fraction.unwrap_or(0.0) * len as f64).round() as u64);
    let (pre, open) = edges::run(&scene, &o, &tribofe::Cancel::new(), tribofe::Progress::new(&tick))?;
    bar.finish_and_clear();
    let dir = super::begin_out(&a.out, a.force)?;
    let files = [
        ("preslip.csv", tribofe::report::edges::preslip_csv(&pre)?),
        #[cfg(feature = "plots")]
        ("preslip.svg", tribofe::report::edges::preslip_svg(&pre)?),
        ("opening.csv", tribofe::report::edges::opening_csv(&open)?),
        (
            "run.toml",
            tribofe::report::run_toml(
                super::invocation(),
                &[
                    ("mu_s", toml::Value::from(a.mu_s)),
                    ("mu_d", toml::Value::from(a.mu_d)),
                    ("rule", toml::Value::from(a.rule.clone())),
                    ("end_grading", toml::Value::from(a.end_grading)),
                    (
                        "h_max_over_t",
                        if grading.is_some() {
                            toml::Value::from(edges::H_MAX_OVER_T)
                        } else {
                            toml::Value::from("uniform")
                        },
                    ),
                ],
                &scene,
            )?,
        ),
    ];
    for (name, text) in files {
        tribofe::report::write_atomic(&dir.path().join(name), text.as_bytes())?;
    }
    dir.commit()?;
    outln!("pre-slip under N alone (coulomb), extent from the left / right end in units of t:");
    outln!("    mu   t/h  nodes    left   right");
    for r in &pre {
        outln!("{:>6} {:>5} {:>6} {:>7.3} {:>7.3}", r.mu, r.t_over_h, r.nodes, r.extent_t[0], r.extent_t[1]);
    }
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    outln!("trailing end under the drive (static-kinetic mu_s = {:.4}, mu_d = {:.4}, rule {}), F in units of mu_s N:", a.mu_s, a.mu_d, a.rule);
    outln!("   t/L  t/h    H/L      g  F1 model  F open   open/t   F1 FE  max open/t  opens first  end h/t");
    // One open node: the open length lies below the end element, which is all the mesh says.
    let len = |v: f64, nodes: usize| if nodes <= 1 { "below h".to_string() } else { format!("{v:.3}") };
    for r in &open {
        outln!(
            "{:>6} {:>4} {:>6} {:>6.3} {:>9.4} {:>7} {:>8} {:>7} {:>11} {:>12} {:>8.4}",
            r.t_over_l,
            r.t_over_h,
            r.h_over_l,
            r.g,
            r.f1_model,
            f(r.f_open),
            r.open_length_t.map_or("-".into(), |v| len(v, r.open_nodes.unwrap_or(0))),
            f(r.f1_fe),
            if r.max_open_nodes == 0 { "0".into() } else { len(r.max_open_t, r.max_open_nodes) },
            r.opens_first(),
            r.end_element_t
        );
    }
    if open.iter().any(|r| r.open_nodes == Some(1) || r.max_open_nodes == 1) {
        outln!("below h: only the end node opens, the open length is below the end element (end h/t); refine with --open-refine");
    }
    outln!("wrote {}/{{preslip.csv, preslip.svg, opening.csv, run.toml}}", a.out.display());
    Ok(())
}
