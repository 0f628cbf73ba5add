//! Command-line (or programmatic) overrides of a scene's keys: every field `None` leaves the
//! scene's value. Applied by [`Scene::apply`], then checked by the same [`Scene::validate`] as a
//! scene file.

use super::{MeshGeometry, PlateModel, Rig, Scene, State, Top};
use crate::error::{Error, Result};
use std::path::PathBuf;

#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    pub length: Option<f64>,
    pub thickness: Option<f64>,
    pub young: Option<f64>,
    pub poisson: Option<f64>,
    pub height: Option<f64>,
    pub fn_ratios: Option<Vec<f64>>,
    pub plate: Option<PlateModel>,
    pub plate_thickness: Option<f64>,
    pub plate_young: Option<f64>,
    pub plate_poisson: Option<f64>,
    pub h: Option<f64>,
    pub grading: Option<f64>,
    pub h_max: Option<f64>,
    pub n_thick: Option<usize>,
    pub element: Option<String>,
    pub mesh: Option<PathBuf>,
    pub geometry: Option<MeshGeometry>,
    pub tol: Option<f64>,
    pub max_dofs: Option<usize>,
    pub state: Option<State>,
    pub width: Option<f64>,
    pub rig: Option<Rig>,
    pub push_height: Option<f64>,
    pub push_width: Option<f64>,
    pub push_stiffness: Option<f64>,
    pub top: Option<Top>,
}

macro_rules! set {
    ($src:expr, $dst:expr) => {
        if let Some(v) = &$src {
            $dst = v.clone();
        }
    };
}

impl Scene {
    /// The scene with the given overrides, validated.
    pub fn apply(&self, o: &Overrides) -> Result<Scene> {
        let mut s = self.clone();
        set!(o.length, s.block.length);
        set!(o.thickness, s.block.thickness);
        set!(o.young, s.block.young);
        set!(o.poisson, s.block.poisson);
        set!(o.height, s.loading.height);
        set!(o.fn_ratios, s.loading.fn_ratios);
        set!(o.plate, s.plate.model);
        set!(o.plate_thickness, s.plate.thickness);
        set!(o.plate_young, s.plate.young);
        set!(o.plate_poisson, s.plate.poisson);
        set!(o.h, s.mesh.h);
        if o.grading.is_some() {
            s.mesh.grading = o.grading;
        }
        if o.h_max.is_some() {
            s.mesh.h_max = o.h_max;
        }
        if o.n_thick.is_some() {
            s.mesh.n_thick = o.n_thick;
        }
        set!(o.element, s.mesh.element);
        if o.mesh.is_some() {
            s.mesh.file = o.mesh.clone();
        }
        set!(o.geometry, s.mesh.geometry);
        set!(o.tol, s.report.tol);
        if o.max_dofs.is_some() {
            s.mesh.max_dofs = o.max_dofs;
        }
        if let Some(state) = o.state {
            let turn = state != s.block.state && o.young.is_none() && o.poisson.is_none();
            s.block.state = state;
            // A file's wave speeds stay the material: turned again in the new state.
            if let (true, Some((c_p, c_s))) = (turn, s.block.wave_speeds) {
                s.block.set_young_poisson(c_p, c_s)?;
            }
        }
        if o.width.is_some() {
            s.block.width = o.width;
        }
        set!(o.rig, s.loading.rig);
        for (given, key) in [
            (o.push_height, &mut s.loading.push_height),
            (o.push_width, &mut s.loading.push_width),
            (o.push_stiffness, &mut s.loading.push_stiffness),
        ] {
            if given.is_some() {
                *key = given;
            }
        }
        if o.top.is_some() {
            s.loading.top = o.top;
        }
        if o.height.is_some() && s.loading.rig == Rig::SidePush {
            return Err(Error::input("--height", super::HEIGHT_WITH_SIDE_PUSH));
        }
        s.validate()?;
        Ok(s)
    }

    /// The scene as TOML (every key, so the file is a template to edit).
    pub fn to_toml(&self) -> Result<String> {
        let bad = |e: &dyn std::fmt::Display| Error::input("scene", format!("cannot write it as TOML: {e}"));
        if self.loading.rig == Rig::SidePush {
            // The top plate's H does not belong to a side-pushed scene (read back, it is refused).
            let mut v = toml::Value::try_from(self).map_err(|e| bad(&e))?;
            if let Some(l) = v.get_mut("loading").and_then(|l| l.as_table_mut()) {
                l.remove("height");
            }
            return toml::to_string(&v).map_err(|e| bad(&e));
        }
        toml::to_string(self).map_err(|e| bad(&e))
    }
}
