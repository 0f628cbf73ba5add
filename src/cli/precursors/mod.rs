//! `tribofe precursors`: one subcommand per study (model, map, fe, fe-map, thin-layer,
//! heights, dc, bonded), each with its own flags; the model's iteration when none is given.
//! The earlier flag forms (`precursors --fe --map`, ...) are hidden aliases ([`old`]),
//! translated into the same subcommands, so both give the same files.

mod bonded;
mod fe;
mod model;
mod old;
mod series;

use std::path::{Path, PathBuf};
use tribofe::report::run_file::Invocation;
use tribofe::Error;

/// Events are iterated until |F - F_max| < this (or MAX_DEFAULT_EVENTS) unless --events is given.
const CONVERGED: f64 = 1e-6;
use tribofe::precursors::DEFAULT_EVENTS as MAX_DEFAULT_EVENTS;

#[derive(clap::Args, Debug)]
#[command(
    args_conflicts_with_subcommands = true,
    after_help = "Without a subcommand: `precursors model`. The earlier flag forms (--map, --fe, \
--fe --map, --fe --thin-layer LIST, --fe --heights LIST, --fe --dc LIST, --bonded-fields) still \
work and write the same files (docs/precursors.md)."
)]
pub struct Args {
    #[command(subcommand)]
    mode: Option<Mode>,
    /// The earlier flag forms, hidden from --help ([`hide_old_flags`]).
    #[command(flatten)]
    old: Box<old::Old>,
}

#[derive(clap::Subcommand, Debug)]
enum Mode {
    /// The paper's event iteration for one (r, g): events.csv, loading.csv, fig4.svg (the default).
    Model(model::ModelArgs),
    /// The model's number of precursors n over the (r, g) square (fig. 5): n_map.csv, fig5.svg.
    Map(model::MapArgs),
    /// The paper's fig. 4 from the frictional FE on the scene (rigid plate, QUA4), one run per
    /// event rule (paper, overdamped) next to the model: summary.csv, model/, paper/, overdamped/.
    #[command(allow_negative_numbers = true)]
    Fe(fe::FeArgs),
    /// The FE fig. 5: n over the (r, g) grid from the frictional FE for each rule asked for,
    /// next to the model's: fig5_fe.csv, boundary_fe.csv, fig5_fe.svg.
    #[command(allow_negative_numbers = true)]
    FeMap(fe::FeMapArgs),
    /// The thin-layer limit: the `paper` rule at (r, g) on blocks of decreasing t/L at the
    /// scene's L and H/L (h = t, 2 elements through t): thin_layer.csv, thin_layer.svg.
    #[command(allow_negative_numbers = true)]
    ThinLayer(series::ThinLayerArgs),
    /// The height of the drive: the `paper` rule with the coefficients of (r, g) at the
    /// scene's H kept fixed, over H/L: heights.csv, heights.svg.
    #[command(allow_negative_numbers = true)]
    Heights(series::HeightsArgs),
    /// The event rule: the `paper` rule and slip-weakening with each D_c at (r, g), one cycle:
    /// dc.csv, dc.svg and each run's fig. 4 in its own folder.
    #[command(allow_negative_numbers = true)]
    Dc(series::DcArgs),
    /// The earlier comparison: the 1D model fed with the bonded FE interface fields (ill-posed
    /// at the singular corners, validation/precursors/README.md): fe_events.csv, fe_extents.svg.
    #[command(allow_negative_numbers = true)]
    Bonded(bonded::BondedArgs),
}

/// The output folder of every subcommand.
#[derive(clap::Args, Debug)]
struct OutArgs {
    /// Output directory (created if needed).
    #[arg(long, default_value = "out/precursors")]
    out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    force: bool,
}

/// The paper's dimensionless (r, g).
#[derive(clap::Args, Debug)]
struct RgArgs {
    /// r = mu_d/mu_s, in (0, 1). Default: the paper's fig. 4 case.
    #[arg(long, default_value_t = tribofe::precursors::PAPER_R)]
    r: f64,
    /// g = 6 mu_d H/L, in (0, 1). Default: the paper's fig. 4 case.
    #[arg(long, default_value_t = tribofe::precursors::PAPER_G)]
    g: f64,
}

/// Hides the flags of the earlier forms from `precursors --help` (they keep working).
pub fn hide_old_flags(cmd: clap::Command) -> clap::Command {
    cmd.mut_args(|a| if a.get_id() == "help" { a } else { a.hide(true) })
}

pub fn run(args: Args) -> tribofe::Result<()> {
    let mode = match args.mode {
        Some(m) => m,
        None => (*args.old).mode()?,
    };
    match mode {
        Mode::Model(a) => model::model(a),
        Mode::Map(a) => model::map(a),
        Mode::Fe(a) => fe::fe(a),
        Mode::FeMap(a) => fe::fe_map(a),
        Mode::ThinLayer(a) => series::thin_layer(a),
        Mode::Heights(a) => series::heights(a),
        Mode::Dc(a) => series::dc(a),
        Mode::Bonded(a) => bonded::bonded(a),
    }
}

/// A progress bar over `len` items called `what`.
fn counter(len: usize, what: &str) -> indicatif::ProgressBar {
    let style = format!("{{bar:40}} {{pos}}/{{len}} {what}, {{elapsed}}");
    indicatif::ProgressBar::new(len as u64)
        .with_style(indicatif::ProgressStyle::with_template(&style).unwrap())
}

/// A spinner with elapsed time for a step that reports no fraction, turned every 200 ms by a
/// thread of its own ([`Spinner`]).
fn spinner(what: &str) -> Spinner {
    let bar = indicatif::ProgressBar::new_spinner().with_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg}, {elapsed}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    bar.set_message(what.to_string());
    let stop = std::sync::Arc::new((std::sync::Mutex::new(false), std::sync::Condvar::new()));
    let (b, s) = (bar.clone(), stop.clone());
    // thread::Builder, not indicatif's steady tick (thread::spawn): where the system refuses a
    // thread (`ulimit -v`) that panicked; here the spinner just stands still.
    let thread = std::thread::Builder::new()
        .name("tribofe-spinner".into())
        .spawn(move || {
            let (lock, cv) = &*s;
            let mut stopped = lock.lock().unwrap_or_else(|e| e.into_inner());
            while !*stopped {
                b.tick();
                stopped = cv
                    .wait_timeout(stopped, std::time::Duration::from_millis(200))
                    .unwrap_or_else(|e| e.into_inner())
                    .0;
            }
        })
        .ok();
    Spinner { bar, stop, thread }
}

/// A spinner and the thread turning it (none if the system refused it); stopped on drop.
struct Spinner {
    bar: indicatif::ProgressBar,
    stop: std::sync::Arc<(std::sync::Mutex<bool>, std::sync::Condvar)>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Spinner {
    fn finish_and_clear(mut self) {
        self.halt();
        self.bar.finish_and_clear();
    }

    fn halt(&mut self) {
        *self.stop.0.lock().unwrap_or_else(|e| e.into_inner()) = true;
        self.stop.1.notify_all();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        self.halt();
    }
}

/// Writes a study's folder whole: `write` fills a temporary sibling of `out` (given the
/// invocation for its run.toml), which replaces `out` only once everything is written.
/// Returns the files written, as paths under `out`.
fn write_whole(
    out: &Path,
    force: bool,
    write: impl FnOnce(&Path, &Invocation) -> tribofe::Result<Vec<PathBuf>>,
) -> tribofe::Result<Vec<PathBuf>> {
    let dir = super::begin_out(out, force)?;
    let tmp = dir.path().to_path_buf();
    let files = write(&tmp, super::invocation())?;
    dir.commit()?;
    Ok(files.into_iter().map(|p| p.strip_prefix(&tmp).map_or(p.clone(), |r| out.join(r))).collect())
}

/// Writes `dir/run.toml`; returns its path.
fn run_file(
    dir: &Path,
    inv: &Invocation,
    scene: Option<&tribofe::scene::Scene>,
    results: &impl serde::Serialize,
) -> tribofe::Result<PathBuf> {
    let results = toml::Value::try_from(results).map_err(|e| Error::input("run.toml", e.to_string()))?;
    let results = match results {
        toml::Value::Array(a) => a
            .into_iter()
            .filter_map(|kv| match kv.as_array().map(|a| &a[..]) {
                Some([toml::Value::String(k), v]) => Some((k.clone(), v.clone())),
                _ => None,
            })
            .collect::<toml::Table>(),
        toml::Value::Table(t) => t,
        _ => toml::Table::new(),
    };
    tribofe::report::run_file::write(dir, inv, scene, &results)?;
    Ok(dir.join(tribofe::io::outdir::RUN_FILE))
}

fn print_written(paths: &[impl AsRef<Path>]) -> tribofe::Result<()> {
    for p in paths {
        outln!("wrote {}", p.as_ref().display());
    }
    Ok(())
}

/// The scene of the FE subcommands, refusing the scene flags that cannot act there; checks
/// the output folder before any work.
fn fe_scene(scene: &super::check::SceneArgs, out: &OutArgs) -> tribofe::Result<tribofe::scene::Scene> {
    for (flag, given) in [("--fn-ratios", scene.fn_ratios.is_some()), ("--tol", scene.tol.is_some())] {
        if given {
            return Err(Error::input(
                flag,
                "cannot act in the FE precursor studies (`precursors fe`, `fe-map`, `thin-layer`, `heights`, `dc`), which load N then X until the interface slides",
            ));
        }
    }
    let scene = super::check::scene(scene)?;
    tribofe::io::outdir::check(&out.out, out.force)?;
    Ok(scene)
}
