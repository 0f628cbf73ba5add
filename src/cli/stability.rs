//! `tribofe stability`: the numerical stability studies of the paper's check (issue 7).

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use tribofe::studies::stability::{self as st, run as run_studies, Options, STUDIES};

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: super::check::SceneArgs,
    /// Studies to run, comma separated: plate, nu, shape, thin, corners (default: all).
    #[arg(long, value_delimiter = ',')]
    pub study: Vec<String>,
    /// Finest corner mesh: elements through the thickness (1, 2, 4, .. up to this).
    #[arg(long, default_value_t = st::DEFAULT_CORNER_MAX)]
    pub corner_max: usize,
    /// Reference qua9 mesh of the nu and shape studies: elements through the thickness.
    #[arg(long, default_value_t = st::DEFAULT_N_REF)]
    pub n_ref: usize,
    /// Output directory (`validation/stability` refreshes the committed results).
    #[arg(long, default_value = "out/stability")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
}

pub fn run(args: Args) -> tribofe::Result<()> {
    // Every study sets its own mesh sizes and load case: these flags could not act.
    super::scene_args::refuse_inapplicable(
        &args.scene,
        &["--h", "--n-thick", "--fn-ratios", "--mesh", "--geometry"],
        "each `stability` study sets its own meshes (--n-ref, --corner-max) and load case",
    )?;
    let scene = super::check::scene(&args.scene)?;
    tribofe::io::outdir::check(&args.out, args.force)?;
    let studies: Vec<String> = if args.study.is_empty() {
        STUDIES.iter().map(|s| s.to_string()).collect()
    } else {
        args.study.clone()
    };
    st::refuse_idle(
        &studies,
        super::given("n_ref").then_some("--n-ref"),
        super::given("corner_max").then_some("--corner-max"),
    )?;
    let o = Options {
        n_ref: args.n_ref,
        corner_n_thick: st::corner_meshes(args.corner_max),
        ..Default::default()
    };
    let bar = ProgressBar::new_spinner().with_style(
        ProgressStyle::with_template("{spinner} {pos} runs, {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let tick = |t: &tribofe::Tick| {
        bar.set_message(format!("last: {}", t.message));
        bar.inc(1);
    };
    let res = run_studies(&scene, &studies, &o, tribofe::Progress::new(&tick))?;
    bar.finish_and_clear();
    let dir = super::begin_out(&args.out, args.force)?;
    let mut files = tribofe::report::stability::write(&res, dir.path())?;
    super::write_run_file(dir.path(), Some(&scene), &tribofe::report::run_file::NoResults {})?;
    files.push("run.toml".into());
    dir.commit()?;
    out!("{}", tribofe::report::stability::summary(&res));
    outln!("wrote {}/{{{}}}", args.out.display(), files.join(", "));
    Ok(())
}
