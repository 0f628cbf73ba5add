//! `tribofe converge`: the paper's scene over families of meshes and elements.

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use tribofe::studies::convergence::{study, Family, StudyOptions};

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: super::check::SceneArgs,
    /// Elements to compare, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "qua4")]
    pub elements: Vec<String>,
    /// Mesh families: uniform, graded.
    #[arg(long, value_delimiter = ',', default_value = "uniform,graded")]
    pub families: Vec<String>,
    /// The load case compared, as F/N.
    #[arg(long, default_value_t = tribofe::studies::convergence::DEFAULT_FN_RATIO)]
    pub case: f64,
    /// Target edge-zone error in units of N/L: name the cheapest run that reaches it (fewest
    /// unknowns; its time shown beside).
    #[arg(long = "target")]
    pub target: Option<f64>,
    /// Run one mesh at a time (honest per-run times) instead of concurrently.
    #[arg(long)]
    pub serial: bool,
    #[arg(long, default_value = "out/converge")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
}

pub fn run(args: Args) -> tribofe::Result<()> {
    // The study sets these for each of its runs: given, they could not act.
    let a = &args.scene;
    let fixed = [
        ("--h", a.h.is_some(), "h = t / n comes from --n-thick"),
        ("--grading", a.grading.is_some(), "the graded family has its own grading (1.15)"),
        ("--h-max", a.h_max.is_some(), "the graded family has its own largest size (4 t)"),
        ("--element", a.element.is_some(), "the elements compared are --elements"),
        ("--fn-ratios", a.fn_ratios.is_some(), "the load case compared is --case"),
        ("--mesh", a.mesh.is_some(), "the study meshes the block itself at each size"),
        ("--geometry", a.geometry.is_some(), "the study meshes the block itself at each size"),
    ];
    if let Some((flag, _, why)) = fixed.iter().find(|f| f.1) {
        return Err(tribofe::Error::input(*flag, format!("cannot act in `converge`: {why}")));
    }
    let mut flat = args.scene.clone();
    let n_thick = match flat.n_thick.take() {
        Some(v) => {
            v.0.iter()
                .map(|&n| super::scene_args::count("n-thick", n))
                .collect::<tribofe::Result<Vec<_>>>()?
        }
        None => StudyOptions::default().n_thick,
    };
    let scene = super::check::scene(&flat)?;
    tribofe::io::outdir::check(&args.out, args.force)?;
    let families = args.families.iter().map(|f| f.parse::<Family>()).collect::<tribofe::Result<Vec<_>>>()?;
    let o = StudyOptions {
        elements: args.elements.clone(),
        families,
        n_thick,
        fn_ratio: args.case,
        parallel: !args.serial,
        ..Default::default()
    };
    let total = (o.elements.len() * o.families.len() * o.n_thick.len()) as u64;
    let bar = ProgressBar::new(total).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} runs, {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let each = |t: &tribofe::Tick<'_, tribofe::studies::convergence::Run>| {
        if let Some(r) = t.item {
            bar.set_message(format!("last: {} {} t/{}", r.family.name(), r.element, r.n_thick));
        }
        bar.inc(1);
    };
    let st = study(&scene, &o, tribofe::Progress::new(&each))?;
    bar.finish_and_clear();
    let dir = super::begin_out(&args.out, args.force)?;
    tribofe::report::convergence::write(&st, dir.path())?;
    super::write_run_file(dir.path(), Some(&scene), &tribofe::report::run_file::NoResults {})?;
    dir.commit()?;
    out!("{}", tribofe::report::convergence::summary(&st, args.target));
    outln!(
        "wrote {}/{{convergence.csv, error_vs_dofs.svg, error_vs_time.svg, summary.txt, run.toml}}",
        args.out.display()
    );
    Ok(())
}
