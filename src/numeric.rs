//! Small numeric helpers on sampled profiles, shared by the studies.

/// Linear interpolation of a profile v(x) at x0 (x sorted; extrapolates linearly outside).
pub fn interpolate(x: &[f64], v: &[f64], x0: f64) -> f64 {
    let i = x.partition_point(|&a| a < x0).clamp(1, x.len() - 1);
    let s = (x0 - x[i - 1]) / (x[i] - x[i - 1]);
    v[i - 1] + s * (v[i] - v[i - 1])
}

/// Least-squares line through the points: (intercept, slope); None with fewer than two points.
pub fn line_fit(points: impl IntoIterator<Item = (f64, f64)>) -> Option<(f64, f64)> {
    let (mut m, mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (x, y) in points {
        m += 1.0;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    if m < 2.0 {
        return None;
    }
    let slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    Some(((sy - slope * sx) / m, slope))
}
