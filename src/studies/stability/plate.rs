//! The `plate` study: stiff elastic plate vs the exact rigid one: modelling error against round-off.

use super::*;

#[derive(Debug, Clone)]
pub struct PlatePoint {
    pub n_thick: usize,
    /// E_plate / E_block.
    pub ratio: f64,
    /// None when the solve itself failed (the message is in `failure`).
    pub raw: Option<PlateRaw>,
    pub failure: Option<String>,
    /// Error with forced iterative refinement (max |diff| of p and tau, N/L), and its steps.
    pub refined: Option<(f64, usize)>,
    /// tribofe's default check refuses the result (and why).
    pub refused: Option<String>,
}

#[derive(Debug, Clone)]
pub struct PlateRaw {
    /// Max |elastic - rigid| over every interface node and load case, units of N/L.
    pub err_p: f64,
    pub err_tau: f64,
    pub backward_error: f64,
    pub condition: f64,
    /// Tilt per unit normal force at the compared F/N, relative difference from the rigid plate.
    pub tilt_rel: f64,
    pub time: f64,
    pub symbolic_time: f64,
}

impl PlateRaw {
    pub fn err(&self) -> f64 {
        self.err_p.max(self.err_tau)
    }
}

/// Per mesh: where the error stops falling and where round-off takes over.
#[derive(Debug, Clone)]
pub struct PlateFinding {
    pub n_thick: usize,
    /// Ratio of the smallest error, and that error (N/L).
    pub best_ratio: f64,
    pub best_err: f64,
    /// First ratio above the best whose error is 10x the smallest.
    pub roundoff_ratio: Option<f64>,
    /// Smallest ratio the default check refuses.
    pub first_refused: Option<f64>,
    /// log10(condition) at the paper's ratio 1e12 (digits lost).
    pub digits_lost_1e12: Option<f64>,
}

#[derive(Debug, Clone)]
pub struct PlateStudy {
    pub points: Vec<PlatePoint>,
    pub findings: Vec<PlateFinding>,
    /// Share of a point's solve that the pattern + symbolic analysis (built once per mesh and
    /// reused along the sweep) would cost if redone.
    pub symbolic_share: f64,
}

/// Elastic plate at `ratio` against the rigid plate on the same block mesh.
pub fn plate(base: &Scene, o: &Options, progress: Progress) -> Result<PlateStudy> {
    let t = base.block.thickness;
    let raw_opts = SolverOptions {
        max_error_estimate: f64::INFINITY,
        residual_limit: f64::INFINITY,
        max_refinement: 0,
        ..Default::default()
    };
    let refine_opts = SolverOptions { max_refinement: 3, refine_above: 0.0, ..raw_opts.clone() };
    let mut points = Vec::new();
    let mut prepare_time = 0.0;
    for &n in &o.plate_n_thick {
        let mut s = base.clone();
        s.mesh.h = t / n as f64;
        s.mesh.n_thick = Some(n);
        s.plate.model = PlateModel::Rigid;
        o.cancel.check()?;
        let (rigid, _) = check::run(&s, &SolverOptions::default())?;
        o.done(progress, &format!("plate rigid t/{n}"))?;
        // Only the plate modulus changes along the sweep: one pattern and symbolic analysis.
        let mut e0 = s.clone();
        e0.plate.model = PlateModel::Elastic;
        let prepared = check::prepare(&e0, &SolverOptions::default())?;
        prepare_time += prepared.pattern_time + prepared.symbolic_time;
        let run =
            |e: &Scene, opts: &SolverOptions| check::run_model(e, e.build()?, 0.0, opts, Some(&prepared));
        for &ratio in &o.plate_ratios {
            let mut e = e0.clone();
            e.plate.young = ratio * base.block.young;
            o.cancel.check()?;
            let clock = Instant::now();
            let (raw, failure) = match run(&e, &raw_opts) {
                Ok((r, _)) => (Some(plate_raw(&r, &rigid, clock.elapsed().as_secs_f64(), o.fn_ratio)), None),
                Err(err) => (None, Some(err.to_string())),
            };
            let refined = if o.plate_refine && raw.is_some() {
                o.cancel.check()?;
                run(&e, &refine_opts).ok().map(|(r, _)| {
                    (plate_raw(&r, &rigid, 0.0, o.fn_ratio).err(), r.stats.report.refinement_steps)
                })
            } else {
                None
            };
            o.cancel.check()?;
            let refused = run(&e, &SolverOptions::default()).err().map(|e| e.to_string());
            o.done(progress, &format!("plate t/{n} ratio {ratio:.0e}"))?;
            points.push(PlatePoint { n_thick: n, ratio, raw, failure, refined, refused });
        }
    }
    let findings = o.plate_n_thick.iter().map(|&n| plate_finding(n, &points)).collect();
    // Share of each point's solve that the reused pattern + symbolic analysis would have cost.
    let times: Vec<f64> = points.iter().filter_map(|p| p.raw.as_ref()).map(|r| r.time).collect();
    let per_mesh = prepare_time / o.plate_n_thick.len().max(1) as f64;
    let mean = times.iter().sum::<f64>() / times.len().max(1) as f64;
    Ok(PlateStudy {
        points,
        findings,
        symbolic_share: if per_mesh + mean > 0.0 { per_mesh / (per_mesh + mean) } else { 0.0 },
    })
}

fn plate_raw(r: &CheckResult, rigid: &CheckResult, time: f64, fn_ratio: f64) -> PlateRaw {
    let (mut ep, mut et) = (0.0f64, 0.0f64);
    for (a, b) in r.cases.iter().zip(&rigid.cases) {
        ep = ep.max(max_diff(&a.p, &b.p));
        et = et.max(max_diff(&a.tau, &b.tau));
    }
    let pick = |c: &CheckResult| {
        c.cases.iter().find(|x| x.fn_ratio == fn_ratio).or(c.cases.last()).map_or(0.0, |x| x.tilt / x.n)
    };
    let (te, tr) = (pick(r), pick(rigid));
    PlateRaw {
        err_p: ep,
        err_tau: et,
        backward_error: r.stats.report.residual.iter().cloned().fold(0.0, f64::max),
        condition: r.stats.report.condition_estimate,
        tilt_rel: if tr != 0.0 { (te - tr).abs() / tr.abs() } else { (te - tr).abs() },
        time,
        symbolic_time: r.stats.timings.symbolic,
    }
}

fn plate_finding(n: usize, points: &[PlatePoint]) -> PlateFinding {
    let pts: Vec<&PlatePoint> = points.iter().filter(|p| p.n_thick == n).collect();
    let ok: Vec<(f64, f64)> = pts.iter().filter_map(|p| p.raw.as_ref().map(|r| (p.ratio, r.err()))).collect();
    let (best_ratio, best_err) =
        ok.iter().cloned().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap_or((f64::NAN, f64::NAN));
    // A failed solve above the best counts as round-off having taken over.
    let roundoff_ratio = pts
        .iter()
        .filter(|p| p.ratio > best_ratio)
        .find(|p| p.raw.as_ref().is_none_or(|r| r.err() > 10.0 * best_err))
        .map(|p| p.ratio);
    PlateFinding {
        n_thick: n,
        best_ratio,
        best_err,
        roundoff_ratio,
        first_refused: pts.iter().find(|p| p.refused.is_some()).map(|p| p.ratio),
        digits_lost_1e12: pts
            .iter()
            .find(|p| p.ratio == 1e12)
            .and_then(|p| p.raw.as_ref())
            .map(|r| r.condition.log10()),
    }
}
