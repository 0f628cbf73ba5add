//! `tribofe check`: the paper's check (Scheibert & Dysthe 2010, fig. 2) with its defaults.

use clap::Args as ClapArgs;
use std::path::PathBuf;
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::{PlateModel, Scene};

/// The scene options shared by every subcommand that runs the paper's scene.
#[derive(ClapArgs, Debug)]
pub struct SceneArgs {
    /// Scene file (TOML); every key defaults to the paper's value.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Element size in the block, m (paper: 0.001).
    #[arg(long)]
    pub h: Option<f64>,
    /// Plate model: exact rigid body, or meshed elastic plate as in the paper.
    #[arg(long, value_enum)]
    pub plate: Option<PlateModel>,
    /// Young's modulus of the elastic plate, Pa (paper: 2e15).
    #[arg(long)]
    pub plate_modulus: Option<f64>,
    /// Load cases as F/N ratios, comma separated (paper: 0,0.41,0.82).
    #[arg(long, value_delimiter = ',')]
    pub fn_ratios: Option<Vec<f64>>,
    /// Element formulation (qua4, qua4-sri, qua4-im, qua8, qua9, tri3, tri6).
    #[arg(long)]
    pub element: Option<String>,
    /// Edge-zone tolerance, relative to the local model value (default 0.05).
    #[arg(long)]
    pub tol: Option<f64>,
    /// A Gmsh mesh (.msh 4.1 or 2.2) of the block with physical groups interface, top, block.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
}

#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output directory.
    #[arg(long, default_value = "out/check")]
    pub out: PathBuf,
    /// Skip the field files (fields_FN*.vtu/.msh, fields.pvd) of the whole mesh.
    #[arg(long)]
    pub no_fields: bool,
    /// Skip the converged run (graded QUA8) printed next to the scene's mesh.
    #[arg(long)]
    pub no_converged: bool,
}

/// Applies the command-line overrides to the scene (file or defaults).
pub fn scene(args: &SceneArgs) -> tribofe::Result<Scene> {
    let s = scene_unvalidated(args)?;
    s.validate()?;
    Ok(s)
}

/// [`scene`] without the final validation, for subcommands that override more keys first.
pub fn scene_unvalidated(args: &SceneArgs) -> tribofe::Result<Scene> {
    let mut s = match &args.scene {
        Some(p) => Scene::from_file(p)?,
        None => Scene::default(),
    };
    if let Some(h) = args.h {
        s.mesh.h = h;
    }
    if let Some(p) = args.plate {
        s.plate.model = p;
    }
    if let Some(e) = args.plate_modulus {
        s.plate.young = e;
    }
    if let Some(r) = &args.fn_ratios {
        s.loading.fn_ratios = r.clone();
    }
    if let Some(e) = &args.element {
        s.mesh.element = e.clone();
    }
    if let Some(t) = args.tol {
        s.report.tol = t;
    }
    if let Some(m) = &args.mesh {
        s.mesh.file = Some(m.clone());
    }
    Ok(s)
}

pub fn run(args: Args) -> tribofe::Result<()> {
    let scene = scene(&args.scene)?;
    let opts = SolverOptions::default();
    let (res, sm) = tribofe::studies::check::run(&scene, &opts)?;
    // The converged figures need the exact rigid plate and the structured mesh of the scene.
    let converged = match (scene.plate.model, &scene.mesh.file, args.no_converged) {
        (PlateModel::Rigid, None, false) => {
            Some(tribofe::studies::check::run(&tribofe::studies::check::converged_scene(&scene), &opts)?.0)
        }
        _ => None,
    };
    tribofe::report::check::write(&res, converged.as_ref(), &args.out)?;
    if !args.no_fields {
        tribofe::report::check::write_fields(&res, &sm, &args.out)?;
    }
    out!("{}", tribofe::report::check::table(&res));
    if let Some(c) = &converged {
        out!("{}", tribofe::report::check::converged_table(&res, c));
    }
    outln!(
        "wrote {}/{{profile_FN*.csv, summary.csv, fig2.svg{}}}",
        args.out.display(),
        if args.no_fields { "" } else { ", fields_FN*.vtu/.msh, fields.pvd" }
    );
    Ok(())
}
