//! `tribofe solve`: a rectangle with one condition per side, any element; prints the reactions
//! per side and writes the fields for ParaView and Gmsh.

use clap::Args as ClapArgs;
use std::path::PathBuf;
use tribofe::io::{gmsh_post::write_msh, vtu::write_vtu, Field};
use tribofe::scene::rectangle::{self as rect, RectangleProblem, SIDES};

#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Width along x, m.
    #[arg(long, default_value_t = rect::DEFAULT_LX)]
    pub lx: f64,
    /// Height along y, m.
    #[arg(long, default_value_t = rect::DEFAULT_LY)]
    pub ly: f64,
    #[arg(long, default_value_t = rect::DEFAULT_NX)]
    pub nx: usize,
    #[arg(long, default_value_t = rect::DEFAULT_NY)]
    pub ny: usize,
    /// Element (qua4, qua4-sri, qua4-im, qua8, qua9, tri3, tri6).
    #[arg(long, default_value = rect::DEFAULT_ELEMENT)]
    pub element: String,
    /// Young's modulus, Pa.
    #[arg(long, default_value_t = rect::DEFAULT_YOUNG)]
    pub young: f64,
    #[arg(long, default_value_t = rect::DEFAULT_POISSON)]
    pub poisson: f64,
    /// Bottom side: free, clamped, roller, u=UX,UY (m) or t=TX,TY (Pa).
    #[arg(long, default_value = rect::DEFAULT_SIDES[0])]
    pub bottom: String,
    #[arg(long, default_value = rect::DEFAULT_SIDES[1])]
    pub right: String,
    #[arg(long, default_value = rect::DEFAULT_SIDES[2])]
    pub top: String,
    #[arg(long, default_value = rect::DEFAULT_SIDES[3])]
    pub left: String,
    #[arg(long, default_value = "out/solve")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
    /// Refuse meshes above this many unknowns (default: what fits in half this machine's
    /// memory at about 1.5 kB per unknown, at most 1.5e6).
    #[arg(long)]
    pub max_dofs: Option<usize>,
}

pub fn run(a: Args) -> tribofe::Result<()> {
    let p = RectangleProblem::from_inputs(
        a.lx,
        a.ly,
        a.nx,
        a.ny,
        &a.element,
        a.young,
        a.poisson,
        [&a.bottom, &a.right, &a.top, &a.left],
    )?;
    p.check_size(a.max_dofs)?;
    tribofe::io::outdir::check(&a.out, a.force)?;
    let r = p.solve()?;
    let model = tribofe::fem::assembly::Model {
        tech: p.element.tech,
        ..tribofe::fem::assembly::Model::new(&r.mesh, p.material)
    };
    let u = &r.solution.u[0];
    outln!(
        "rectangle {} x {} m, {} x {} {} elements, {} unknowns; forces in N per metre of width",
        a.lx,
        a.ly,
        a.nx,
        a.ny,
        a.element,
        r.solution.stats.n_unknowns
    );
    for (name, f) in SIDES.iter().zip(&r.side_reactions) {
        outln!("  reaction on {name:<6}: Fx = {:>12.5e}, Fy = {:>12.5e}", f[0], f[1]);
    }
    let bal = [r.total_reaction[0] + r.applied[0], r.total_reaction[1] + r.applied[1]];
    outln!(
        "  applied tractions: Fx = {:.5e}, Fy = {:.5e}; balance (reactions + applied): {:.1e}, {:.1e}",
        r.applied[0],
        r.applied[1],
        bal[0],
        bal[1]
    );
    let fields = Field::solution_fields(&model, u);
    let dir = super::begin_out(&a.out, a.force)?;
    write_vtu(&dir.path().join("fields.vtu"), &r.mesh, &fields, &[])?;
    write_msh(&dir.path().join("fields.msh"), &r.mesh, &fields, &[])?;
    let mut results = toml::Table::new();
    results.insert("unknowns".into(), (r.solution.stats.n_unknowns as i64).into());
    for (name, f) in SIDES.iter().zip(&r.side_reactions) {
        results.insert(
            format!("reaction_{name}_n_per_m"),
            toml::Value::try_from(f).map_err(|e| tribofe::Error::input("run.toml", e.to_string()))?,
        );
    }
    super::write_run_file(dir.path(), None, &results)?;
    dir.commit()?;
    outln!("wrote {}/{{fields.vtu, fields.msh, run.toml}}", a.out.display());
    Ok(())
}
