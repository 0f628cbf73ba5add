//! `tribofe check`: the paper's check (Scheibert & Dysthe 2010, fig. 2) with its defaults.

use clap::Args as ClapArgs;
use std::path::PathBuf;
use tribofe::io::FieldFormat;
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::PlateModel;

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output directory.
    #[arg(long, default_value = "out/check")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
    /// Field files of the whole mesh: vtu (fields_FN*.vtu + fields.pvd, ParaView, raw binary),
    /// msh (fields_FN*.msh, Gmsh ASCII: ~1.6x larger and ~3x slower to write), both, or none.
    #[arg(long, default_value = "vtu", value_parser = ["vtu", "msh", "both", "none"])]
    pub fields: String,
    /// Same as --fields none.
    #[arg(long, conflicts_with = "fields")]
    pub no_fields: bool,
    /// Normal force N, N/m, of every load case (F = (F/N) N). Profiles are in units of N/L and
    /// do not depend on it; the absolute fields, forces and plate motions scale with it.
    /// Default: the force of pressing the rigid plate down by 0.05 t (85.438 N/m for the
    /// paper's block).
    #[arg(long, value_name = "N_PER_M")]
    pub n_force: Option<f64>,
    /// Skip the converged run (graded QUA8) printed next to the scene's mesh.
    #[arg(long)]
    pub no_converged: bool,
}

pub use super::scene_args::{scene, scene_any_rig, SceneArgs};

pub fn run(args: Args) -> tribofe::Result<()> {
    let scene = scene_any_rig(&args.scene)?;
    let fields: FieldFormat = if args.no_fields { FieldFormat::None } else { args.fields.parse()? };
    if let Some(n) = args.n_force {
        if !(n.is_finite() && n > 0.0) {
            return Err(tribofe::Error::input("--n-force", format!("{n} N/m: give a positive normal force")));
        }
    }
    tribofe::io::outdir::check(&args.out, args.force)?;
    let opts = SolverOptions::default();
    let (mut res, sm) = tribofe::studies::check::run(&scene, &opts)?;
    // The converged figures need the exact rigid plate and the structured mesh of the scene.
    // The side push's converged run is a later phase's (its pusher sets the mesh).
    let top_plate = scene.loading.rig == tribofe::scene::Rig::TopPlate;
    let mut converged = match (scene.plate.model, &scene.mesh.file, args.no_converged || !top_plate) {
        (PlateModel::Rigid, None, false) => {
            Some(tribofe::studies::check::run(&tribofe::studies::check::converged_scene(&scene), &opts)?.0)
        }
        _ => None,
    };
    if let Some(n) = args.n_force {
        tribofe::report::check::scale_to_normal_force(&mut res, n)?;
        if let Some(c) = &mut converged {
            tribofe::report::check::scale_to_normal_force(c, n)?;
        }
    }
    // A failed self-check is an error: nothing is written.
    res.self_check()?;
    if let Some(c) = &converged {
        c.self_check()?;
    }
    let dir = super::begin_out(&args.out, args.force)?;
    tribofe::report::check::write(&res, converged.as_ref(), dir.path())?;
    let clock = std::time::Instant::now();
    tribofe::report::check::write_fields(&res, &sm, dir.path(), fields)?;
    let fields_s = clock.elapsed().as_secs_f64();
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
        match fields {
            FieldFormat::Vtu => ", fields_FN*.vtu, fields.pvd",
            FieldFormat::Msh => ", fields_FN*.msh",
            FieldFormat::Both => ", fields_FN*.vtu/.msh, fields.pvd",
            FieldFormat::None => "",
        }
    );
    if fields != FieldFormat::None {
        outln!("fields ({}): {:.2} s", fields.name(), fields_s);
    }
    Ok(())
}
