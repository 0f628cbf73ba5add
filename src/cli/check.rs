//! `tribofe check`: the paper's check (Scheibert & Dysthe 2010, fig. 2) with its defaults.

use clap::Args as ClapArgs;
use std::path::PathBuf;
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::PlateModel;

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output directory.
    #[arg(long, default_value = "out/check")]
    pub out: PathBuf,
    /// Replace the --out folder even if it holds files tribofe did not write (they are deleted).
    #[arg(long)]
    pub force: bool,
    /// Skip the field files (fields_FN*.vtu/.msh, fields.pvd) of the whole mesh.
    #[arg(long)]
    pub no_fields: bool,
    /// Skip the converged run (graded QUA8) printed next to the scene's mesh.
    #[arg(long)]
    pub no_converged: bool,
}

pub use super::scene_args::{scene, SceneArgs};

pub fn run(args: Args) -> tribofe::Result<()> {
    let scene = scene(&args.scene)?;
    tribofe::io::outdir::check(&args.out, args.force)?;
    let opts = SolverOptions::default();
    let (res, sm) = tribofe::studies::check::run(&scene, &opts)?;
    // The converged figures need the exact rigid plate and the structured mesh of the scene.
    let converged = match (scene.plate.model, &scene.mesh.file, args.no_converged) {
        (PlateModel::Rigid, None, false) => {
            Some(tribofe::studies::check::run(&tribofe::studies::check::converged_scene(&scene), &opts)?.0)
        }
        _ => None,
    };
    // A failed self-check is an error: nothing is written.
    res.self_check()?;
    if let Some(c) = &converged {
        c.self_check()?;
    }
    let dir = tribofe::io::outdir::OutDir::begin(&args.out, args.force)?;
    tribofe::report::check::write(&res, converged.as_ref(), dir.path())?;
    if !args.no_fields {
        tribofe::report::check::write_fields(&res, &sm, dir.path())?;
    }
    tribofe::report::write_atomic(
        &dir.path().join("run.toml"),
        tribofe::report::check::run_toml(&res, super::invocation())?.as_bytes(),
    )?;
    dir.commit()?;
    out!("{}", tribofe::report::check::table(&res));
    if let Some(c) = &converged {
        out!("{}", tribofe::report::check::converged_table(&res, c));
    }
    outln!(
        "wrote {}/{{profile_FN*.csv, summary.csv, fig2.svg, run.toml{}}}",
        args.out.display(),
        if args.no_fields { "" } else { ", fields_FN*.vtu/.msh, fields.pvd" }
    );
    Ok(())
}
