//! The files of `tribofe rupture` (docs/dynamics.md): arrival.csv and summary.csv with the
//! shared spec's columns, energy.csv and zone.csv; the field's station files
//! (`station_x<x>.csv`), rupture_time.csv and the space-time picture spacetime.svg.

use super::table::{Column, Table};
use super::{csv, write_atomic};
use crate::dynamics::rupture::{RuptureResult, Station};
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
    write_atomic(&dir.join("energy.csv"), energy_table(r).csv()?.as_bytes())?;
    let zone: Vec<Vec<f64>> = r.cohesive_zone().into_iter().map(|(x, z)| vec![x, z, z / r.lambda0]).collect();
    write_atomic(&dir.join("zone.csv"), csv("x_m,zone_m,zone_over_lambda0", &zone)?.as_bytes())?;
    for st in &r.stations {
        write_atomic(&dir.join(station_file(st.x)), station_table(st).csv()?.as_bytes())?;
    }
    let rows: Vec<Vec<f64>> =
        r.x.iter().zip(&r.rupture_time).filter_map(|(&x, t)| t.map(|t| vec![x, t])).collect();
    write_atomic(&dir.join("rupture_time.csv"), csv("x_m,t_s", &rows)?.as_bytes())?;
    write_atomic(&dir.join("spacetime.svg"), spacetime(r).as_bytes())?;
    Ok(())
}

/// energy.csv's one row (13 significant digits): the ledger at t_end, J/m.
pub fn energy_table(r: &RuptureResult) -> Table {
    let e = &r.energy;
    let one = |name, v: f64| Column::float(name, "J/m", vec![v]);
    Table {
        columns: vec![
            one("kinetic_j_per_m", e.kinetic),
            one("strain_j_per_m", e.strain),
            one("background_work_j_per_m", e.background_work),
            one("friction_dissipation_j_per_m", e.friction),
            one("friction_path_j_per_m", e.friction_path),
            one("contact_work_j_per_m", e.contact),
            one("damping_dissipation_j_per_m", e.damping),
            one("balance_residual_j_per_m", e.residual),
        ],
        digits: 13,
    }
}

/// A station's table, `station_x<x>.csv` (13 significant digits): time, slip, slip rate,
/// shear and normal stress at the station's base node.
pub fn station_table(st: &Station) -> Table {
    Table {
        columns: vec![
            Column::float("t_s", "s", st.t.clone()),
            Column::float("slip_m", "m", st.slip.clone()),
            Column::float("slip_rate_m_per_s", "m/s", st.slip_rate.clone()),
            Column::float("shear_stress_Pa", "Pa", st.shear.clone()),
            Column::float("normal_stress_Pa", "Pa", st.normal.clone()),
        ],
        digits: 13,
    }
}

/// `station_x<x in m>.csv`, x as written in the scene (`station_x-4500.csv`).
pub fn station_file(x: f64) -> String {
    format!("station_x{}.csv", if x == 0.0 { 0.0 } else { x })
}

/// The files [`write()`] writes for `r`, for the command's closing line.
pub fn files(r: &RuptureResult) -> Vec<String> {
    let mut f: Vec<String> =
        ["arrival.csv", "summary.csv", "energy.csv", "zone.csv", "rupture_time.csv", "spacetime.svg"]
            .iter()
            .map(|s| s.to_string())
            .collect();
    f.extend(r.stations.iter().map(|s| station_file(s.x)));
    f
}

/// The run's space-time picture: the slip rate of every base node (log10, 4 decades below the
/// peak) over x (km on a block of a kilometre or more, else m) and time, cropped to the nodes
/// that ruptured, with the c_s and c_R guides from the first of them.
pub fn spacetime(r: &RuptureResult) -> String {
    use super::spacetime::{heat_map, sig4, HeatMap, Scale};
    let map = &r.map;
    let (x0, x1) = (r.x[0], r.x[r.x.len() - 1]);
    let ruptured: Vec<usize> = (0..r.x.len()).filter(|&i| r.rupture_time[i].is_some()).collect();
    let (xa, xb) = match (ruptured.first(), ruptured.last()) {
        (Some(&i), Some(&j)) => {
            let m = 0.05 * (r.x[j] - r.x[i]).max(x1 - x0);
            ((r.x[i] - m).max(x0), (r.x[j] + m).min(x1))
        }
        _ => (x0, x1),
    };
    let peak = map.rates.iter().flatten().fold(0.0f64, |a, &v| a.max(f64::from(v))).max(f64::MIN_POSITIVE);
    let first = ruptured.iter().copied().min_by(|&i, &j| {
        r.rupture_time[i].unwrap_or(f64::INFINITY).total_cmp(&r.rupture_time[j].unwrap_or(f64::INFINITY))
    });
    let km = x1 - x0 >= 1e3;
    let t_end = r.steps as f64 * r.dt;
    let t_of = |k: usize| map.t.get(k).copied().unwrap_or(t_end);
    heat_map(&HeatMap {
        title: format!("rupture: slip rate, peak {} m/s", sig4(peak)),
        x: &r.x,
        x_range: (xa, xb),
        x_unit: if km { (1e3, "position x (km)") } else { (1.0, "position x (m)") },
        t: &t_of,
        rows: map.t.len().max(1),
        t_end: t_end.max(f64::MIN_POSITIVE),
        t_label: "time (s)",
        value: &|k, i| map.rates.get(k).and_then(|row| row.get(i)).map_or(0.0, |&v| f64::from(v)),
        scale: Scale::Log { peak },
        origin: first.map(|i| (r.x[i], r.rupture_time[i].unwrap_or(0.0))),
        speeds: [r.speeds.c_s, r.speeds.c_r],
        label: "slip rate (m/s)",
    })
}
