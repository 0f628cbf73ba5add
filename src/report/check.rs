//! Outputs of the paper's check: one profile CSV per load case, the summary CSV, a readable
//! table, and fig. 2 of the paper redrawn with zooms on both edge zones.

use super::{csv, ratio_label, write_atomic};
use crate::error::{Error, Result};
use crate::studies::check::{CaseResult, CheckResult};
#[cfg(feature = "plots")]
use plotters::coord::types::RangedCoordf64;
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

pub const PROFILE_HEADER: &str =
    "x_over_L,p_over_pmean,tau_over_pmean,p_model,tau_model,p_extrap,tau_extrap,p_corrected";
pub const SUMMARY_HEADER: &str = "FN,N,F,slope_interior,slope_model,tau_center,edge_p_left_t,edge_p_right_t,edge_tau_left_t,edge_tau_right_t,interior_dev_p,interior_dev_tau,p_end_left,p_end_right,tau_end_left,tau_end_right,tilt_rad,balance_N,balance_F,balance_moment,slope_corrected,interior_dev_p_corrected";
/// The unit of each [`SUMMARY_HEADER`] column: N and F in N/m, the tilt in rad, stresses in
/// units of N/L, edge widths in units of t, balances relative to the loads (all `1`).
pub const SUMMARY_UNITS: [&str; 22] = [
    "1", "N/m", "N/m", "1", "1", "1", "1", "1", "1", "1", "1", "1", "1", "1", "1", "1", "rad", "1", "1", "1",
    "1", "1",
];

/// Writes `profile_FN<ratio>.csv`, summary.csv and fig2.svg into `dir`, and with a converged
/// run, `summary_converged.csv` and its profiles under `converged/`.
/// The absolute loads of one case of `run.toml`.
#[derive(serde::Serialize)]
pub struct CaseLoads {
    pub fn_ratio: f64,
    pub n_force_n_per_m: f64,
    pub f_force_n_per_m: f64,
    pub mean_pressure_pa: f64,
}

/// `run.toml` of a check: version, `command`, the loads of each case, the effective scene.
pub fn run_toml(res: &CheckResult, inv: &super::run_file::Invocation) -> Result<String> {
    let l = res.scene.block.length;
    let cases: Vec<CaseLoads> = res
        .cases
        .iter()
        .map(|c| CaseLoads {
            fn_ratio: c.fn_ratio,
            n_force_n_per_m: c.n,
            f_force_n_per_m: c.f,
            mean_pressure_pa: c.n / l,
        })
        .collect();
    if let Some(sp) = res.scene.side_push()? {
        // The side push's model and arm beside the cases, so the file says what it compared.
        let model = format!(
            "side push, bonded interface: p = N/L + 12 F h x / L^3, tau = F/L, the torque balance with \
             the push's arm h = push_height = {} m (corrected model: none for side push yet, \
             p_corrected repeats the model)",
            sp.height
        );
        let cases = toml::Value::try_from(&cases).map_err(|e| Error::input("run.toml", e.to_string()))?;
        let pairs = vec![("model".to_string(), toml::Value::String(model)), ("cases".to_string(), cases)];
        return super::run_toml(inv, &pairs, &res.scene);
    }
    super::run_toml(inv, &cases, &res.scene)
}

/// Rescales every case to the normal force `n` (N/m): the problem is linear, so forces,
/// plate motions and displacements scale by n / N; the profiles (in units of N/L) do not
/// change. Without it N is the force of pressing the rigid plate down by 0.05 t.
pub fn scale_to_normal_force(res: &mut CheckResult, n: f64) -> Result<()> {
    if !(n.is_finite() && n > 0.0) {
        return Err(Error::input("--n-force", format!("{n} N/m: give a positive normal force")));
    }
    for (c, u) in res.cases.iter_mut().zip(&mut res.displacements) {
        let k = n / c.n;
        (c.n, c.f, c.tilt, c.plate_u, c.plate_v) = (n, c.f * k, c.tilt * k, c.plate_u * k, c.plate_v * k);
        u.iter_mut().for_each(|v| *v *= k);
    }
    Ok(())
}

pub fn write(res: &CheckResult, converged: Option<&CheckResult>, dir: &Path) -> Result<()> {
    if let Some(c) = converged {
        write(c, None, &dir.join("converged"))?;
        write_atomic(&dir.join("summary_converged.csv"), summary_csv(c)?.as_bytes())?;
    }
    for c in &res.cases {
        let rows: Vec<Vec<f64>> = (0..c.x_over_l.len())
            .map(|i| {
                vec![
                    c.x_over_l[i],
                    c.p[i],
                    c.tau[i],
                    c.p_model[i],
                    c.tau_model[i],
                    c.p_extrap[i],
                    c.tau_extrap[i],
                    c.p_corrected[i],
                ]
            })
            .collect();
        write_atomic(
            &dir.join(format!("profile_FN{}.csv", ratio_label(c.fn_ratio))),
            csv(PROFILE_HEADER, &rows)?.as_bytes(),
        )?;
    }
    write_atomic(&dir.join("summary.csv"), summary_csv(res)?.as_bytes())?;
    #[cfg(feature = "plots")]
    write_atomic(&dir.join("fig2.svg"), fig2(res)?.as_bytes())?;
    Ok(())
}

/// One summary row (a load case) in the order of [`SUMMARY_HEADER`]: each figure with the
/// digits after the point it is printed with, None where the cell is left empty (an edge
/// width the model cannot define, an interior figure of an interior with too few nodes).
/// Refuses a non-finite figure.
pub(crate) fn summary_row(c: &CaseResult) -> Result<Vec<(Option<f64>, usize)>> {
    let m = &c.metrics;
    let nums = [c.fn_ratio, c.n, c.f, m.slope_model, m.tau_center];
    let tail = [
        m.p_ends[0],
        m.p_ends[1],
        m.tau_ends[0],
        m.tau_ends[1],
        c.tilt,
        m.balance_n,
        m.balance_f,
        m.balance_moment,
    ];
    if let Some(v) = nums.iter().chain(&tail).find(|v| !v.is_finite()) {
        return Err(Error::input(
            "summary",
            format!("F/N = {}: a figure is {v}; refusing to write it", c.fn_ratio),
        ));
    }
    let num = |v: &f64| (Some(*v), 12);
    // Interior figures are undefined (empty) when the interior holds too few nodes.
    let interior = |v: f64| (if v.is_nan() { None } else { Some(v) }, 12);
    let width = |v: Option<f64>| (v, 6);
    let mut cells = vec![num(&nums[0]), num(&nums[1]), num(&nums[2]), interior(m.slope_interior)];
    cells.extend(nums[3..].iter().map(num));
    cells.extend([m.edge_p_t[0], m.edge_p_t[1], m.edge_tau_t[0], m.edge_tau_t[1]].map(width));
    cells.extend([m.interior_dev_p, m.interior_dev_tau].map(interior));
    cells.extend(tail.iter().map(num));
    cells.extend([m.slope_corrected, m.interior_dev_p_corrected].map(interior));
    Ok(cells)
}

/// A number with `digits` after the point in exponent form; empty for None.
pub(crate) fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or(String::new(), |v| format!("{v:.digits$e}"))
}

/// Summary table, one row per load case (the figures of `summary_row`).
pub fn summary_csv(res: &CheckResult) -> Result<String> {
    let mut s = String::from(SUMMARY_HEADER);
    s.push('\n');
    for c in &res.cases {
        let cells: Vec<String> = summary_row(c)?.into_iter().map(|(v, d)| cell(v, d)).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    Ok(s)
}

/// The converged figures next to the paper-mesh ones (stresses / (N/L), widths / t).
pub fn converged_table(paper: &CheckResult, conv: &CheckResult) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "converged answer (graded {} mesh, t/16 at the ends, {} unknowns; shown by validation/convergence to match the finest meshes):",
        conv.scene.mesh.element, conv.stats.n_unknowns
    );
    let _ = writeln!(
        s,
        "{:>6} {:>10} {:>10} {:>10} {:>10} | {:>13} {:>13}",
        "F/N", "slope", "(mesh)", "tau(0)", "(mesh)", "edge p L/R", "edge tau L/R"
    );
    for (c, p) in conv.cases.iter().zip(&paper.cases) {
        let w = |v: [Option<f64>; 2]| {
            format!(
                "{}/{}",
                v[0].map_or("-".into(), |x| format!("{x:.2}")),
                v[1].map_or("-".into(), |x| format!("{x:.2}"))
            )
        };
        let (m, pm) = (&c.metrics, &p.metrics);
        let _ = writeln!(
            s,
            "{:>6} {:>10.5} {:>10.5} {:>10.5} {:>10.5} | {:>13} {:>13}",
            c.fn_ratio,
            m.slope_interior,
            pm.slope_interior,
            m.tau_center,
            pm.tau_center,
            w(m.edge_p_t),
            w(m.edge_tau_t)
        );
    }
    s
}

/// The readable summary printed by `tribofe check`.
pub fn table(res: &CheckResult) -> String {
    let sc = &res.scene;
    let mut s = String::new();
    let side = sc.side_push().ok().flatten();
    match side {
        None => {
            let _ = writeln!(
                s,
                "tribofe check: block L = {} m, t = {} m, E = {} Pa, nu = {}; {:?} plate; H = {} m; {} elements ({}), {} nodes, {} unknowns",
                sc.block.length, sc.block.thickness, sc.block.young, sc.block.poisson, sc.plate.model, sc.loading.height, res.n_elements, sc.mesh.element, res.n_nodes, res.stats.n_unknowns
            );
        }
        Some(sp) => {
            let _ = writeln!(
                s,
                "tribofe check: block L = {} m, t = {} m, E = {} Pa, nu = {}; side push (bonded interface): rigid pusher on the trailing face x = -L/2 at h = {} m, {} m wide; top: {}; {} elements ({}), {} nodes, {} unknowns",
                sc.block.length, sc.block.thickness, sc.block.young, sc.block.poisson, sp.height, sp.width, sp.top.name(), res.n_elements, sc.mesh.element, res.n_nodes, res.stats.n_unknowns
            );
        }
    }
    if let Some(note) = &res.geometry_note {
        let _ = writeln!(
            s,
            "geometry: {note}: the model, corrected and dev columns compare with a block this mesh is not"
        );
    }
    let _ = writeln!(
        s,
        "stresses in units of the mean pressure N/L; widths in units of t; forces per unit width (N/m)"
    );
    // The state and b are in the header every command prints; the table adds N in newtons.
    if let (Some(b), Some(c)) = (sc.block.width, res.cases.first()) {
        let sig4 = super::spacetime::sig4;
        let _ = writeln!(s, "width b = {} m: N = {} N/m x b = {} N", sig4(b), sig4(c.n), sig4(c.n * b));
    }
    let _ = writeln!(
        s,
        "{:>6} {:>11} {:>11} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} | {:>13} {:>13}",
        "F/N",
        "N",
        "F",
        "slope",
        "model",
        "corrected",
        "tau(0)",
        "dev p",
        "dev p c",
        "dev tau",
        "edge p L/R",
        "edge tau L/R"
    );
    for c in &res.cases {
        let m = &c.metrics;
        let w = |v: [Option<f64>; 2]| {
            format!(
                "{}/{}",
                v[0].map_or("-".into(), |x| format!("{x:.2}")),
                v[1].map_or("-".into(), |x| format!("{x:.2}"))
            )
        };
        let _ = writeln!(
            s,
            "{:>6} {:>11.4e} {:>11.4e} {:>9} {:>9.5} {:>9} {:>9.5} {:>9} {:>9} {:>9} | {:>13} {:>13}",
            c.fn_ratio,
            c.n,
            c.f,
            dash(m.slope_interior, 'f'),
            m.slope_model,
            dash(m.slope_corrected, 'f'),
            m.tau_center,
            dash(m.interior_dev_p, 'e'),
            dash(m.interior_dev_p_corrected, 'e'),
            dash(m.interior_dev_tau, 'e'),
            w(m.edge_p_t),
            w(m.edge_tau_t)
        );
    }
    let (l, t) = (sc.block.length, sc.block.thickness);
    let margin = crate::studies::check::interior_margin(l, t);
    let _ = writeln!(
        s,
        "interior (slope, dev): |x| < L/2 - {} = {:.4e} m{}",
        if margin < 10.0 * t {
            "L/4 (the middle half: L < 40 t leaves no interior 10 t from both ends)"
        } else {
            "10 t"
        },
        l / 2.0 - margin,
        if res.cases.iter().any(|c| c.metrics.slope_interior.is_nan()) {
            "; '-': fewer than two interface nodes there, refine the mesh (--h) to define it"
        } else {
            ""
        }
    );
    if side.is_some() {
        let _ = writeln!(s, "model: the torque balance with the push's arm h = push_height: p = N/L + 12 F h x / L^3, tau = F/L, slope 12 (F/N)(h/L); corrected: none for side push yet (the column repeats the model); tilt: of the top face's corners; balance_moment: against the moment of the pusher's own nodal forces (its arm is where they act, near h)");
    } else {
        let _ = writeln!(s, "model: the paper's 12 (F/N)(H/L); corrected: arm H - t/2 (the block's shear couple) and the Poisson edge deficit (analytical::thin_layer); dev p c: interior |p - corrected|");
    }
    let _ = writeln!(s, "paper (Cast3M, 1 mm QUA4): edge zones ~1 t for pressure and ~3 t for shear (tolerance here: {} of the local model value)", sc.report.tol);
    let _ = writeln!(s, "end-node values (NOT converged: the clamped-free corners are singular, they grow without bound under refinement):");
    for c in &res.cases {
        let m = &c.metrics;
        let _ = writeln!(
            s,
            "  F/N = {:<5} p ends {:.4}/{:.4}  tau ends {:.4}/{:.4}  plate tilt {:.4e} rad",
            c.fn_ratio, m.p_ends[0], m.p_ends[1], m.tau_ends[0], m.tau_ends[1], c.tilt
        );
    }
    let (worst, limit) = (res.balance_error(), res.balance_limit());
    let verdict = if worst <= limit { "ok, <=" } else { "FAILED, >" };
    let arm = if side.is_some() { "the pusher's own moment" } else { "F H" };
    let _ = writeln!(s, "global balance (sum of interface forces vs N, F; moment vs {arm}; relative to the load): worst error {worst:.1e} ({verdict} {limit:.1e} = 100 eps kappa)");
    let r = &res.stats.report;
    let _ = writeln!(
        s,
        "solver: componentwise backward error {:.1e} (after {} refinement steps), condition estimate {:.1e}; time {:.1} ms (mesh {:.1}, pattern {:.1}, assembly {:.1}, symbolic {:.1}, numeric {:.1}, solve {:.1}, recovery {:.1}, other {:.1})",
        r.residual.iter().cloned().fold(0.0, f64::max),
        r.refinement_steps,
        r.condition_estimate,
        res.stats.timings.total() * 1e3,
        res.stats.timings.mesh * 1e3,
        res.stats.timings.pattern * 1e3,
        res.stats.timings.assembly * 1e3,
        res.stats.timings.symbolic * 1e3,
        res.stats.timings.numeric * 1e3,
        res.stats.timings.solve * 1e3,
        res.stats.timings.recovery * 1e3,
        res.stats.timings.other * 1e3
    );
    s
}

/// A figure for the table, `-` where it is undefined (NaN); `style` 'e' for exponent form.
fn dash(v: f64, style: char) -> String {
    match (v.is_nan(), style) {
        (true, _) => "-".into(),
        (false, 'e') => format!("{v:.2e}"),
        _ => format!("{v:.5}"),
    }
}

/// The report layer's series colours ([`super::plot::PALETTE`]).
#[cfg(feature = "plots")]
use super::plot::{render, Area, Drawn, Legend, FONT, PALETTE as COLORS};

#[cfg(feature = "plots")]
/// Fig. 2 of the paper redrawn: p/(N/L) open symbols, tau/(N/L) full symbols, model dashed;
/// below, the two edge zones (10 t wide, L/4 for a short block). The stress axis spans the
/// profiles and the models but not the nodes within t/10 of the ends, where the clamped-free
/// corners are singular (their values grow without bound under refinement): those are drawn
/// as triangles on the frame, pointing off scale, and the end values are written in a note.
pub fn fig2(res: &CheckResult) -> Result<String> {
    let l = res.scene.block.length;
    let t = res.scene.block.thickness;
    let near_end = |x: f64| x.abs() > 0.5 - 0.1 * t / l;
    let (mut ymin, mut ymax) = (0.0f64, 1.0f64);
    for c in &res.cases {
        for i in 0..c.x_over_l.len() {
            let mut v = vec![c.p_model[i], c.tau_model[i]];
            if !near_end(c.x_over_l[i]) || c.x_over_l.len() < 3 {
                v.extend([c.p[i], c.tau[i]]);
            }
            for v in v.into_iter().filter(|v| v.is_finite()) {
                (ymin, ymax) = (ymin.min(v), ymax.max(v));
            }
        }
    }
    let pad = 0.08 * (ymax - ymin);
    let yr = (ymin - pad)..(ymax + 2.5 * pad); // room for the legend
    let mut notes = Vec::new();
    for c in &res.cases {
        let mut off = Vec::new();
        for (name, v) in [("p", &c.p), ("tau", &c.tau)] {
            for (end, i) in [("-L/2", 0), ("+L/2", v.len().saturating_sub(1))] {
                if let Some(&x) = v.get(i) {
                    if x < yr.start || x > yr.end {
                        off.push(format!("{name}({end}) = {x:.3}"));
                    }
                }
            }
        }
        if !off.is_empty() {
            notes.push(format!("F/N = {}: {}", c.fn_ratio, off.join(", ")));
        }
    }
    let height = 830 + 16 * (notes.len() as u32 + 1);
    render("fig2.svg", (1000, height), |root| {
        let (top, rest) = root.split_vertically(470);
        let (bottom, foot) = rest.split_vertically(350);
        let halves = bottom.split_evenly((1, 2));
        panel(&top, res, -0.5..0.5, yr.clone(), "Interface stresses (fig. 2 of the paper): open = pressure p/(N/L), full = shear tau/(N/L), dashed = model", 150)?;
        let zone = crate::studies::check::interior_margin(l, t) / l;
        panel(&halves[0], res, (-0.5 - 0.05 * zone)..(-0.5 + zone), yr.clone(), "Trailing edge zone", 80)?;
        panel(&halves[1], res, (0.5 - zone)..(0.5 + 0.05 * zone), yr, "Leading edge zone", 80)?;
        if !notes.is_empty() {
            let font = (FONT, 13);
            foot.draw(&Text::new(
                "Off scale (triangles on the frame): end-node values, in units of N/L; singular corners, not converged:".to_string(),
                (15, 2),
                font,
            ))?;
            for (k, n) in notes.iter().enumerate() {
                foot.draw(&Text::new(n.clone(), (30, 18 + 16 * k as i32), font))?;
            }
        }
        Ok(())
    })
}

#[cfg(feature = "plots")]
/// One panel; at most about `markers` symbols per series (every k-th node), and values outside
/// `yr` drawn as triangles on the frame pointing the way they leave it.
fn panel(
    area: &Area,
    res: &CheckResult,
    xr: std::ops::Range<f64>,
    yr: std::ops::Range<f64>,
    title: &str,
    markers_per_series: usize,
) -> Drawn {
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FONT, 15))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(xr.clone(), yr.clone())?;
    chart
        .configure_mesh()
        .x_desc("x/L (dimensionless)")
        .y_desc("stress / (N/L) (dimensionless)")
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    for (k, c) in res.cases.iter().enumerate() {
        let col = COLORS[k % COLORS.len()];
        let pts: Vec<usize> =
            (0..c.x_over_l.len()).filter(|&i| c.x_over_l[i] >= xr.start && c.x_over_l[i] <= xr.end).collect();
        let every = pts.len().div_ceil(markers_per_series.max(1)).max(1);
        // Every k-th node, and always the ends of the range (the edge values).
        let sel: Vec<usize> = pts
            .iter()
            .copied()
            .enumerate()
            .filter(|&(j, _)| j % every == 0 || j + 1 == pts.len())
            .map(|(_, i)| i)
            .collect();
        let model_p: Vec<(f64, f64)> = pts.iter().map(|&i| (c.x_over_l[i], c.p_model[i])).collect();
        let model_t: Vec<(f64, f64)> = pts.iter().map(|&i| (c.x_over_l[i], c.tau_model[i])).collect();
        chart.draw_series(DashedLineSeries::new(model_p, 6, 4, col.stroke_width(1)))?;
        chart.draw_series(DashedLineSeries::new(model_t, 6, 4, col.stroke_width(1)))?;
        let label = format!("F/N = {}", c.fn_ratio);
        for (v, filled) in [(&c.p, false), (&c.tau, true)] {
            let inside =
                sel.iter().filter(|&&i| yr.contains(&v[i])).map(|&i| (c.x_over_l[i], v[i])).collect();
            markers(&mut chart, inside, k, col, filled)?;
            // Off scale: every such node (not only every k-th), on the frame.
            let off = pts.iter().filter(|&&i| v[i].is_finite() && !yr.contains(&v[i]));
            let style = if filled { col.filled() } else { col.stroke_width(1) };
            chart.draw_series(off.map(|&i| {
                let up = v[i] > yr.end;
                let y = if up { yr.end } else { yr.start };
                let tip = if up { -7 } else { 7 };
                EmptyElement::at((c.x_over_l[i], y)) + Polygon::new(vec![(-5, 0), (5, 0), (0, tip)], style)
            }))?;
        }
        // Legend entry: the case's colour (the marker shape follows the case order).
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label(label)
            .legend(move |(x, y)| Circle::new((x, y), 4, col.filled()));
    }
    chart.legend_box(SeriesLabelPosition::UpperMiddle)
}

/// Field files of every load case for ParaView (`fields_FN<ratio>.vtu` and `fields.pvd`, whose
/// timestep is the case's F/N) and/or Gmsh (`fields_FN<ratio>.msh`), as `format` asks:
/// displacement, nodal stresses (extrapolated and averaged), von Mises, and the mean
/// integration-point stress of each element (docs/outputs.md).
pub fn write_fields(
    res: &CheckResult,
    sm: &crate::scene::SceneModel,
    dir: &Path,
    format: crate::io::FieldFormat,
) -> Result<Vec<std::path::PathBuf>> {
    use crate::fem::recovery::gauss_stresses;
    use crate::io::{gmsh_post::write_msh, vtu, Field};
    let model = sm.model();
    let mut written = Vec::new();
    let mut pvd = Vec::new();
    if format == crate::io::FieldFormat::None {
        return Ok(written);
    }
    for (c, u) in res.cases.iter().zip(&res.displacements) {
        let mean: Vec<[f64; 4]> = (0..sm.mesh.n_elements())
            .map(|e| {
                let g = gauss_stresses(&model, e, u);
                let k = g.len() as f64;
                std::array::from_fn(|i| g.iter().map(|q| q[i]).sum::<f64>() / k)
            })
            .collect();
        let point = Field::solution_fields(&model, u);
        let cell = [Field::tensor_2d("stress_mean_Pa", &mean)];
        let stem = format!("fields_FN{}", ratio_label(c.fn_ratio));
        if format.vtu() {
            let vtu_path = dir.join(format!("{stem}.vtu"));
            vtu::write_vtu(&vtu_path, &sm.mesh, &point, &cell)?;
            pvd.push((c.fn_ratio, vtu_path));
        }
        if format.msh() {
            let msh_path = dir.join(format!("{stem}.msh"));
            write_msh(&msh_path, &sm.mesh, &point, &cell)?;
            written.push(msh_path);
        }
    }
    if format.vtu() {
        let entries: Vec<(f64, &Path)> = pvd.iter().map(|(r, p)| (*r, p.as_path())).collect();
        vtu::write_pvd(&dir.join("fields.pvd"), &entries)?;
        written.extend(pvd.into_iter().map(|(_, p)| p));
        written.push(dir.join("fields.pvd"));
    }
    Ok(written)
}

#[cfg(feature = "plots")]
/// The paper's markers: circle, square, diamond for the successive load cases; open for the
/// pressure, full for the shear.
fn markers(
    chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    pts: Vec<(f64, f64)>,
    k: usize,
    col: RGBColor,
    filled: bool,
) -> Drawn {
    let style = if filled { col.filled() } else { col.stroke_width(1) };
    let diamond = [(0, -4), (4, 0), (0, 4), (-4, 0)];
    match (k % 3, filled) {
        (0, _) => chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, style))).map(|_| ()),
        (1, _) => chart
            .draw_series(
                pts.into_iter().map(|p| EmptyElement::at(p) + Rectangle::new([(-3, -3), (3, 3)], style)),
            )
            .map(|_| ()),
        (_, true) => chart
            .draw_series(pts.into_iter().map(|p| EmptyElement::at(p) + Polygon::new(diamond.to_vec(), style)))
            .map(|_| ()),
        (_, false) => chart
            .draw_series(pts.into_iter().map(|p| {
                EmptyElement::at(p) + PathElement::new([&diamond[..], &diamond[..1]].concat(), style)
            }))
            .map(|_| ()),
    }?;
    Ok(())
}
