//! The files of `tribofe rupture` (docs/dynamics.md): arrival.csv and summary.csv with the
//! shared spec's columns, energy.csv and zone.csv.

use super::{csv, write_atomic};
use crate::dynamics::rupture::RuptureResult;
use crate::error::Result;
use std::path::Path;

/// Writes arrival.csv, summary.csv (the spec's columns), energy.csv and zone.csv into `dir`.
pub fn write(r: &RuptureResult, dir: &Path) -> Result<()> {
    let rows: Vec<Vec<f64>> = r.arrivals().into_iter().map(|(x, t)| vec![x, t]).collect();
    write_atomic(&dir.join("arrival.csv"), csv("x_m,t_arrival_s", &rows)?.as_bytes())?;
    let speed = r.front_speed.map_or(String::new(), |s| format!("{s:.12e}"));
    let summary = format!(
        "force_drop_n_per_m,min_sigma_pa,steps,dt_s,front_speed_m_per_s\n{:.12e},{:.12e},{},{:.12e},{speed}\n",
        r.force_drop, r.min_sigma, r.steps, r.dt
    );
    write_atomic(&dir.join("summary.csv"), summary.as_bytes())?;
    let e = &r.energy;
    let energy = csv(
        "kinetic_j_per_m,strain_j_per_m,background_work_j_per_m,friction_dissipation_j_per_m,friction_path_j_per_m,contact_work_j_per_m,damping_dissipation_j_per_m,balance_residual_j_per_m",
        &[vec![e.kinetic, e.strain, e.background_work, e.friction, e.friction_path, e.contact, e.damping, e.residual]],
    )?;
    write_atomic(&dir.join("energy.csv"), energy.as_bytes())?;
    let zone: Vec<Vec<f64>> = r.cohesive_zone().into_iter().map(|(x, z)| vec![x, z, z / r.lambda0]).collect();
    write_atomic(&dir.join("zone.csv"), csv("x_m,zone_m,zone_over_lambda0", &zone)?.as_bytes())?;
    Ok(())
}
