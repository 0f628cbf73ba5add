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

/// The run of consecutive indices around `center` (included whatever `inside` says of it)
/// whose every member is `inside`, as (first, last) of 0..n: the slipped region grown from its
/// nucleation or its largest jump, one rule for the event solver, the model and the dynamics.
pub fn run_around(center: usize, n: usize, inside: impl Fn(usize) -> bool) -> (usize, usize) {
    let (mut first, mut last) = (center, center);
    while first > 0 && inside(first - 1) {
        first -= 1;
    }
    while last + 1 < n && inside(last + 1) {
        last += 1;
    }
    (first, last)
}

#[cfg(test)]
mod tests {
    use super::run_around;

    #[test]
    fn the_run_stops_at_the_first_node_outside_on_each_side() {
        let inside = [true, false, true, true, false, true, true];
        let f = |i: usize| inside[i];
        assert_eq!(run_around(2, 7, f), (2, 3));
        assert_eq!(run_around(3, 7, f), (2, 3));
        // The centre belongs even when outside; its neighbours decide the rest.
        assert_eq!(run_around(1, 7, f), (0, 3));
        assert_eq!(run_around(4, 7, f), (2, 6));
        assert_eq!(run_around(6, 7, f), (5, 6));
        assert_eq!(run_around(0, 1, |_| false), (0, 0));
    }
}
