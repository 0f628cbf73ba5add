//! The scene flags shared by every subcommand that runs the paper's scene (check, converge,
//! sweep, slide, stability, precursors): each overrides one key of the scene file (or of the paper's defaults) and goes
//! through the same validation.

use clap::Args as ClapArgs;
use std::path::PathBuf;
use tribofe::scene::{MeshGeometry, Overrides, PlateModel, Rig, Scene, Top};

#[derive(ClapArgs, Debug, Clone, Default)]
pub struct SceneArgs {
    /// Scene file (TOML); every key defaults to the paper's value.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Writes the effective scene (file + flags) as TOML to FILE, a template to edit, once the
    /// run has finished; a new file, or with --force an existing regular file (never a
    /// folder, link, FIFO or device).
    #[arg(long, value_name = "FILE")]
    pub write_scene: Option<PathBuf>,
    /// Block length L, m (paper: 0.4).
    #[arg(long, value_parser = parse_values)]
    pub length: Option<Values>,
    /// Block thickness t, m (paper: 0.002).
    #[arg(long, value_parser = parse_values)]
    pub thickness: Option<Values>,
    /// Block Young's modulus E, Pa (paper: 2e3).
    #[arg(long, value_parser = parse_values)]
    pub young: Option<Values>,
    /// Block Poisson ratio nu, dimensionless, in (-1, 0.5) (paper: 0.4).
    #[arg(long, value_parser = parse_values)]
    pub poisson: Option<Values>,
    /// Height H of the tangential loading point above the interface, m (paper: 0.04).
    #[arg(long, value_parser = parse_values)]
    pub height: Option<Values>,
    /// Load cases as F/N ratios, dimensionless, comma separated (paper: 0,0.41,0.82).
    #[arg(long, value_delimiter = ',')]
    pub fn_ratios: Option<Vec<f64>>,
    /// Plate model: exact rigid body, or meshed elastic plate as in the paper.
    #[arg(long, value_parser = parse_plate, value_name = "rigid|elastic")]
    pub plate: Option<PlateModel>,
    /// Elastic plate thickness, m (default 0.048).
    #[arg(long)]
    pub plate_thickness: Option<f64>,
    /// Young's modulus of the elastic plate, Pa (paper: 2e15).
    #[arg(long, alias = "plate-young")]
    pub plate_modulus: Option<f64>,
    /// Poisson ratio of the elastic plate, dimensionless (default 0.4).
    #[arg(long)]
    pub plate_poisson: Option<f64>,
    /// Element size in the block, m (paper: 0.001); with --grading, the size at both ends.
    #[arg(long)]
    pub h: Option<f64>,
    /// Growth ratio of the element length from both ends to the middle, dimensionless, >= 1.
    #[arg(long)]
    pub grading: Option<f64>,
    /// Largest element length with --grading, m (default 2 t).
    #[arg(long)]
    pub h_max: Option<f64>,
    /// Elements through the thickness (default round(t / h)); `converge` takes a list, one
    /// mesh each (default 1,2,4,8,16,32,64).
    #[arg(long, value_parser = parse_values)]
    pub n_thick: Option<Values>,
    /// Element formulation (qua4, qua4-sri, qua4-im, qua8, qua9, tri3, tri6).
    #[arg(long)]
    pub element: Option<String>,
    /// Edge-zone tolerance, relative to the local model value, dimensionless (default 0.05).
    #[arg(long)]
    pub tol: Option<f64>,
    /// A Gmsh mesh (.msh 4.1 or 2.2) of the block with physical groups interface, top, block.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// What the --mesh file must be: the L x t block (block, the default: holes and notches
    /// refused), or its own shape (file: holes and notches accepted; the paper's model then
    /// does not describe it, and every verdict says so). Slits and hanging nodes are refused
    /// either way.
    #[arg(long, value_parser = parse_geometry, value_name = "block|file")]
    pub geometry: Option<MeshGeometry>,
    /// Refuse meshes above this many unknowns, estimated before meshing (default: what fits in
    /// half this machine's memory at about 1.5 kB per unknown, at most 1.5e6).
    #[arg(long)]
    pub max_dofs: Option<usize>,
    /// Plane stress (sigma_zz = 0: a thin plate) instead of plane strain; needs --width.
    #[arg(long)]
    pub plane_stress: bool,
    /// The plate's out-of-plane width b, m: the forces per unit width times b are the plate's
    /// newtons (run.toml, header). Required with --plane-stress.
    #[arg(long)]
    pub width: Option<f64>,
    /// Loading rig: top-plate (the paper's, default) or side-push (a rigid pusher on the
    /// trailing face x = -L/2; `tribofe check` and the quasi-static `tribofe slide` in this
    /// phase).
    #[arg(long, value_parser = parse_rig, value_name = "top-plate|side-push")]
    pub rig: Option<Rig>,
    /// Side push: the pusher's centre above the interface, m.
    #[arg(long)]
    pub push_height: Option<f64>,
    /// Side push: the pusher's contact length on the trailing face, m.
    #[arg(long)]
    pub push_width: Option<f64>,
    /// Side push: the driving spring's stiffness, N/m per metre of width (`slide`: X is then the
    /// spring's far end; `check` does not use it).
    #[arg(long)]
    pub push_stiffness: Option<f64>,
    /// Side push: the normal load on the top face, a uniform pressure N/L or a rigid plate free
    /// to slide and rotate, N at its centre (default uniform-pressure).
    #[arg(long, value_parser = parse_top, value_name = "uniform-pressure|sliding-plate")]
    pub top: Option<Top>,
}

/// The values of a sweepable flag: one number, a list `a,b,c`, or a range `a:b:n` (n points,
/// both ends included, linear) or `a:b:ng` (geometric). Commands other than `sweep` take one.
#[derive(Debug, Clone, PartialEq)]
pub struct Values(pub Vec<f64>);

// The library's enum stays free of clap: the names are parsed here.
fn parse_plate(s: &str) -> Result<PlateModel, String> {
    match s {
        "rigid" => Ok(PlateModel::Rigid),
        "elastic" => Ok(PlateModel::Elastic),
        _ => Err(format!("'{s}': use rigid or elastic")),
    }
}

fn parse_rig(s: &str) -> Result<Rig, String> {
    s.parse().map_err(|_| format!("'{s}': use {}", Rig::NAMES))
}

fn parse_top(s: &str) -> Result<Top, String> {
    s.parse().map_err(|_| format!("'{s}': use {}", Top::NAMES))
}

fn parse_geometry(s: &str) -> Result<MeshGeometry, String> {
    match s {
        "block" => Ok(MeshGeometry::Block),
        "file" => Ok(MeshGeometry::File),
        _ => Err(format!("'{s}': use block or file")),
    }
}

fn parse_values(s: &str) -> Result<Values, String> {
    tribofe::studies::sweep::parse_values(s).map(Values).map_err(|e| e.to_string())
}

fn one(flag: &str, v: &Option<Values>) -> tribofe::Result<Option<f64>> {
    match v {
        None => Ok(None),
        Some(Values(x)) if x.len() == 1 => Ok(Some(x[0])),
        Some(Values(x)) => Err(tribofe::Error::input(
            format!("--{flag}"),
            format!(
                "{} values given; this command takes one (lists and ranges are for `tribofe {}`)",
                x.len(),
                if flag == "n-thick" { "converge" } else { "sweep" }
            ),
        )),
    }
}

/// An element count given as a number: a whole number >= 1.
pub fn count(flag: &str, v: f64) -> tribofe::Result<usize> {
    if v.fract() == 0.0 && (1.0..=1e9).contains(&v) {
        Ok(v as usize)
    } else {
        Err(tribofe::Error::input(
            format!("--{flag}"),
            format!("{v} must be a whole number of elements >= 1"),
        ))
    }
}

impl SceneArgs {
    /// The overrides, each sweepable flag holding one value.
    pub fn overrides(&self) -> tribofe::Result<Overrides> {
        Ok(Overrides {
            length: one("length", &self.length)?,
            thickness: one("thickness", &self.thickness)?,
            young: one("young", &self.young)?,
            poisson: one("poisson", &self.poisson)?,
            height: one("height", &self.height)?,
            fn_ratios: self.fn_ratios.clone(),
            plate: self.plate,
            plate_thickness: self.plate_thickness,
            plate_young: self.plate_modulus,
            plate_poisson: self.plate_poisson,
            h: self.h,
            grading: self.grading,
            h_max: self.h_max,
            n_thick: one("n-thick", &self.n_thick)?.map(|n| count("n-thick", n)).transpose()?,
            element: self.element.clone(),
            mesh: self.mesh.clone(),
            geometry: self.geometry,
            tol: self.tol,
            max_dofs: self.max_dofs,
            state: self.plane_stress.then_some(tribofe::scene::State::PlaneStress),
            width: self.width,
            rig: self.rig,
            push_height: self.push_height,
            push_width: self.push_width,
            push_stiffness: self.push_stiffness,
            top: self.top,
        })
    }
}

/// Each scene flag and the scene-file key it overrides.
pub const FLAG_KEYS: &[(&str, &str)] = &[
    ("--length", "block.length"),
    ("--thickness", "block.thickness"),
    ("--young", "block.young"),
    ("--poisson", "block.poisson"),
    ("--height", "loading.height"),
    ("--fn-ratios", "loading.fn_ratios"),
    ("--plate", "plate.model"),
    ("--plate-thickness", "plate.thickness"),
    ("--plate-modulus", "plate.young"),
    ("--plate-poisson", "plate.poisson"),
    ("--h", "mesh.h"),
    ("--grading", "mesh.grading"),
    ("--h-max", "mesh.h_max"),
    ("--n-thick", "mesh.n_thick"),
    ("--element", "mesh.element"),
    ("--tol", "report.tol"),
    ("--mesh", "mesh.file"),
    ("--geometry", "mesh.geometry"),
    ("--max-dofs", "mesh.max_dofs"),
    ("--plane-stress", "block.state"),
    ("--width", "block.width"),
    ("--rig", "loading.rig"),
    ("--push-height", "loading.push_height"),
    ("--push-width", "loading.push_width"),
    ("--push-stiffness", "loading.push_stiffness"),
    ("--top", "loading.top"),
];

impl SceneArgs {
    /// Whether scene flag `flag` (a name of [`FLAG_KEYS`]) was given.
    pub fn has(&self, flag: &str) -> bool {
        match flag {
            "--length" => self.length.is_some(),
            "--thickness" => self.thickness.is_some(),
            "--young" => self.young.is_some(),
            "--poisson" => self.poisson.is_some(),
            "--height" => self.height.is_some(),
            "--fn-ratios" => self.fn_ratios.is_some(),
            "--plate" => self.plate.is_some(),
            "--plate-thickness" => self.plate_thickness.is_some(),
            "--plate-modulus" => self.plate_modulus.is_some(),
            "--plate-poisson" => self.plate_poisson.is_some(),
            "--h" => self.h.is_some(),
            "--grading" => self.grading.is_some(),
            "--h-max" => self.h_max.is_some(),
            "--n-thick" => self.n_thick.is_some(),
            "--element" => self.element.is_some(),
            "--tol" => self.tol.is_some(),
            "--mesh" => self.mesh.is_some(),
            "--geometry" => self.geometry.is_some(),
            "--max-dofs" => self.max_dofs.is_some(),
            "--plane-stress" => self.plane_stress,
            "--width" => self.width.is_some(),
            "--rig" => self.rig.is_some(),
            "--push-height" => self.push_height.is_some(),
            "--push-width" => self.push_width.is_some(),
            "--push-stiffness" => self.push_stiffness.is_some(),
            "--top" => self.top.is_some(),
            "--scene" => self.scene.is_some(),
            "--write-scene" => self.write_scene.is_some(),
            _ => false,
        }
    }

    /// Whether any scene flag (or a scene file) was given.
    pub fn any(&self) -> bool {
        FLAG_KEYS.iter().any(|(f, _)| self.has(f)) || self.scene.is_some() || self.write_scene.is_some()
    }
}

/// The value of `key` ("table.key") in `scene`, as TOML.
fn key_value(scene: &Scene, key: &str) -> Option<toml::Value> {
    let v = toml::Value::try_from(scene).ok()?;
    let (table, k) = key.split_once('.')?;
    v.get(table)?.get(k).cloned()
}

/// Refuses the scene settings of `flags` that cannot act in this command: each given as a flag,
/// or set in the --scene file to other than the paper's default. `why` says why.
pub fn refuse_inapplicable(args: &SceneArgs, flags: &[&str], why: &str) -> tribofe::Result<()> {
    for flag in flags {
        if args.has(flag) {
            return Err(tribofe::Error::input(*flag, format!("cannot act here: {why}")));
        }
    }
    let Some(file) = &args.scene else { return Ok(()) };
    let from_file = Scene::from_file(file)?;
    let default = Scene::default();
    for flag in flags {
        let Some((_, key)) = FLAG_KEYS.iter().find(|(f, _)| f == flag) else { continue };
        if key_value(&from_file, key) != key_value(&default, key) {
            return Err(tribofe::Error::input(
                format!("{key} in {}", tribofe::error::quote(&file.display().to_string())),
                format!("cannot act here: {why} (remove the key or set it back to the default)"),
            ));
        }
    }
    Ok(())
}

/// The scene file (or the paper's defaults) with the flags applied and validated; writes it
/// to `--write-scene` when asked. The top-plate rig only: a side-pushed scene is refused,
/// naming the flag or key and the command that runs it ([`scene_any_rig`]).
pub fn scene(args: &SceneArgs) -> tribofe::Result<Scene> {
    scene_with(args, false)
}

/// [`scene`] with the side-pushed rig accepted too (`tribofe check`).
pub fn scene_any_rig(args: &SceneArgs) -> tribofe::Result<Scene> {
    scene_with(args, true)
}

fn scene_with(args: &SceneArgs, side_push: bool) -> tribofe::Result<Scene> {
    let base = match &args.scene {
        Some(p) => Scene::from_file(p)?,
        None => Scene::default(),
    };
    // The rig first: a command that cannot run the side push says so before its values.
    if args.rig.unwrap_or(base.loading.rig) == Rig::SidePush && !side_push {
        let key = match (&args.scene, args.rig.is_some()) {
            (Some(f), false) => {
                format!("loading.rig in {}", tribofe::error::quote(&f.display().to_string()))
            }
            _ => "--rig".to_string(),
        };
        return Err(tribofe::Error::input(
            key,
            "side-push runs in `tribofe check` and `tribofe slide` (with or without --dynamics) \
             in this phase; this command supports rig = \"top-plate\" (remove the key or the flag)",
        ));
    }
    let s = base.apply(&args.overrides()?)?;
    if s.loading.rig == Rig::SidePush && file_sets(args, "loading", "height")? {
        return Err(tribofe::Error::input(
            format!(
                "loading.height in {}",
                tribofe::error::quote(&args.scene.clone().unwrap_or_default().display().to_string())
            ),
            tribofe::scene::HEIGHT_WITH_SIDE_PUSH,
        ));
    }
    for (table, there) in [("[interface]", s.interface.is_some()), ("[rupture]", s.rupture.is_some())] {
        if there {
            return Err(tribofe::Error::input(
                format!("{table} in {}", tribofe::error::quote(&args.scene.clone().unwrap_or_default().display().to_string())),
                "describes a rupture scene, read by `tribofe rupture --scene` only: remove the table for this command",
            ));
        }
    }
    if let Some(mesh) = &s.mesh.file {
        // The structured mesher's flags cannot act on a mesh read from a file.
        let given = [
            ("--h", args.h.is_some()),
            ("--grading", args.grading.is_some()),
            ("--h-max", args.h_max.is_some()),
            ("--n-thick", args.n_thick.is_some()),
        ];
        if let Some((flag, _)) = given.iter().find(|g| g.1) {
            return Err(tribofe::Error::input(
                *flag,
                format!(
                    "sizes the built-in mesh, but the mesh comes from {}; refine that file instead",
                    tribofe::error::quote(&mesh.display().to_string())
                ),
            ));
        }
    }
    if let Some(note) = s.block.out_of_plane_note() {
        use std::io::Write;
        let _ = writeln!(std::io::stderr(), "note: {note}");
    }
    for w in s.warnings() {
        use std::io::Write;
        let _ = writeln!(std::io::stderr(), "warning: {}", tribofe::error::quote_lines(&w.to_string()));
    }
    if s.plate.model == PlateModel::Rigid {
        refuse_inapplicable(
            args,
            &["--plate-thickness", "--plate-modulus", "--plate-poisson"],
            "it describes the elastic plate, but the plate is rigid; add --plate elastic",
        )?;
    }
    if let Some(path) = &args.write_scene {
        // Checked now, written only when the run has finished ([`write_pending_scene`]).
        let force = super::given("force");
        check_scene_target(path, force)?;
        *PENDING_SCENE.lock().unwrap_or_else(|e| e.into_inner()) = Some((path.clone(), s.to_toml()?, force));
    }
    Ok(s)
}

/// Replaces the pending `--write-scene` text with `scene` as the run will use it: a command
/// that sets scene values beyond the scene flags (`slide --density`, the mesh h that
/// `slide --dynamics` chooses) writes the scene that reproduces its run.
pub fn update_pending_scene(scene: &Scene) -> tribofe::Result<()> {
    let mut pending = PENDING_SCENE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, text, _)) = pending.as_mut() {
        *text = scene.to_toml()?;
    }
    Ok(())
}

/// Whether the --scene file sets `[table] key` itself (not the paper's default filled in).
pub fn file_sets(args: &SceneArgs, table: &str, key: &str) -> tribofe::Result<bool> {
    let Some(file) = &args.scene else { return Ok(false) };
    let text =
        tribofe::io::input::read_text(file, "scene file (--scene)", tribofe::io::input::TOML_MAX_BYTES)?;
    let v: toml::Value = toml::from_str(&text).map_err(|e| tribofe::Error::Parse {
        file: file.clone(),
        at: "scene".into(),
        msg: e.to_string(),
    })?;
    Ok(v.get(table).and_then(|t| t.get(key)).is_some())
}

/// The `--write-scene` file waiting for the run to finish: path, text, whether `--force`.
static PENDING_SCENE: std::sync::Mutex<Option<(PathBuf, String, bool)>> = std::sync::Mutex::new(None);

/// A `--write-scene` refusal naming the flag and the path.
fn refuse(path: &std::path::Path, why: &str) -> tribofe::Error {
    tribofe::Error::input(
        "--write-scene",
        format!("'{}' {why}", tribofe::error::quote(&path.display().to_string())),
    )
}

/// Refuses a `--write-scene` target that is not a new file or (with `--force`) an existing
/// regular file: a folder, a symbolic link, a FIFO, a device (/dev/null) or a socket never.
fn check_scene_target(path: &std::path::Path, force: bool) -> tribofe::Result<()> {
    if path.file_name().is_none() {
        return Err(refuse(path, "has no file name: give a file, e.g. scene.toml"));
    }
    match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(refuse(path, &format!("cannot be checked ({e}); give another file"))),
        Ok(m) if m.file_type().is_symlink() => Err(refuse(
            path,
            "is a symbolic link: --write-scene writes regular files only and does not follow links; give the file itself or a new name",
        )),
        Ok(m) if m.is_dir() => Err(refuse(path, "is a folder: give a file name, e.g. scene.toml")),
        Ok(m) if !m.is_file() => Err(refuse(
            path,
            "is not a regular file (a FIFO, device or socket): --write-scene writes regular files only; give a new file name",
        )),
        Ok(_) if !force => Err(refuse(path, "exists: give --force to replace it, or a new file name")),
        Ok(_) => Ok(()),
    }
}

/// Writes the pending `--write-scene` file, once the run has finished: a new file never
/// replaces anything (a complete temporary renamed with RENAME_NOREPLACE);
/// with `--force` it replaces a regular file only, checked again just before the rename.
pub fn write_pending_scene() -> tribofe::Result<()> {
    use std::io::Write;
    let Some((path, text, force)) = PENDING_SCENE.lock().unwrap_or_else(|e| e.into_inner()).take() else {
        return Ok(());
    };
    check_scene_target(&path, force)?;
    let name = path.file_name().unwrap_or_default().to_string_lossy().into_owned();
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| tribofe::Error::io(dir, e))?;
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let written = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .and_then(|mut f| f.write_all(text.as_bytes()).and_then(|_| f.sync_all()));
    let placed = written.map_err(|e| tribofe::Error::io(&tmp, e)).and_then(|_| {
        if force && std::fs::symlink_metadata(&path).is_ok() {
            check_scene_target(&path, true)?;
            std::fs::rename(&tmp, &path).map_err(|e| tribofe::Error::io(&path, e))
        } else {
            match tribofe::io::outdir::rename_noreplace(&tmp, &path) {
                Ok(()) => Ok(()),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Err(refuse(
                    &path,
                    "was created meanwhile: give --force to replace it, or a new file name",
                )),
                Err(e) => Err(tribofe::Error::io(&path, e)),
            }
        }
    });
    let _ = std::fs::remove_file(&tmp);
    placed
}
