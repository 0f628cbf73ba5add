//! Root finding for the entire-function eigen-equations of [`super::williams`] and
//! [`super::strip`].
//!
//! Those equations are real on the real axis, so their roots are real or come in conjugate
//! pairs and searching the upper half (Im z >= 0) of a rectangle suffices. [`find_roots`]
//! combines two seeds because neither alone is reliable:
//!
//! 1. a sign-change scan of f along the real segment, refined by bisection — this catches real
//!    roots however close they sit to another root (the clamped-strip compression root
//!    approaches z = 0 as ν → 1/2, where Newton seeds would be captured by the wrong basin);
//! 2. damped complex Newton (numerical derivative) from every node of a grid over the
//!    rectangle — this catches complex roots.
//!
//! [`count_zeros`] applies the argument principle, (1/2π) Δ arg f around a rectangle, as an
//! independent count so tests can confirm that no root was missed.

use super::Complex;

/// The search rectangle Re z in [re.0, re.1], Im z in [0, im_max], seeded by an
/// `n_re` × `n_im` grid.
#[derive(Clone, Copy, Debug)]
pub struct Region {
    pub re: (f64, f64),
    pub im_max: f64,
    pub n_re: usize,
    pub n_im: usize,
}

/// Central-difference derivative. Its O(h²) error only slows Newton from quadratic to fast
/// linear convergence; it does not move the root.
fn derivative(f: &impl Fn(Complex) -> Complex, z: Complex) -> Complex {
    let h = 1e-6 * (1.0 + z.abs());
    (f(z + h) - f(z - h)) / (2.0 * h)
}

/// Damped complex Newton from `z0`. Converged when the Newton step is below 1e-14·(1 + |z|),
/// or below 1e-8·(1 + |z|) when no damped step lowers |f| (f is at its rounding floor, as for
/// a numerically evaluated determinant). Returns `None` if it stalls elsewhere, leaves
/// |z| < 1e3 or takes over 100 steps. The step is halved until |f| decreases, because sin and
/// cos grow like e^|Im z| and an undamped step from a far seed usually lands in an unrelated
/// basin.
pub fn newton(f: &impl Fn(Complex) -> Complex, z0: Complex) -> Option<Complex> {
    let mut z = z0;
    let mut fz = f(z);
    for _ in 0..100 {
        if fz.abs() == 0.0 {
            return Some(z);
        }
        let mut step = fz / derivative(f, z);
        if !step.is_finite() {
            return None;
        }
        if step.abs() <= 1e-14 * (1.0 + z.abs()) {
            return Some(z - step);
        }
        let mut halvings = 0;
        loop {
            let zn = z - step;
            let fzn = f(zn);
            if fzn.abs() < fz.abs() {
                z = zn;
                fz = fzn;
                break;
            }
            halvings += 1;
            if halvings > 40 {
                let floor = (fz / derivative(f, z)).abs() <= 1e-8 * (1.0 + z.abs());
                return floor.then_some(z);
            }
            step = step * 0.5;
        }
        if z.abs() > 1e3 {
            return None;
        }
    }
    None
}

/// Real roots of f on [a, b] from sign changes of Re f at `n` + 1 equispaced points, each
/// bisected to machine precision. Simple roots only; even-order roots give no sign change.
pub fn real_roots(f: &impl Fn(Complex) -> Complex, a: f64, b: f64, n: usize) -> Vec<f64> {
    let g = |x: f64| f(x.into()).re;
    let mut out = Vec::new();
    let mut x0 = a;
    let mut g0 = g(a);
    for i in 1..=n {
        let x1 = a + (b - a) * i as f64 / n as f64;
        let g1 = g(x1);
        if g1 == 0.0 {
            out.push(x1);
        } else if g0 * g1 < 0.0 {
            let (mut lo, mut hi, mut glo) = (x0, x1, g0);
            while hi - lo > 4.0 * f64::EPSILON * hi.abs().max(1.0) {
                let mid = 0.5 * (lo + hi);
                let gm = g(mid);
                if gm == 0.0 {
                    lo = mid;
                    hi = mid;
                } else if gm * glo < 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                    glo = gm;
                }
            }
            out.push(0.5 * (lo + hi));
        }
        x0 = x1;
        g0 = g1;
    }
    out
}

/// All distinct roots of f found in `region` (Im >= 0 representatives), sorted by real part.
/// Roots with |Im| below 1e-12·(1+|z|) are snapped onto the real axis.
pub fn find_roots(f: &impl Fn(Complex) -> Complex, region: Region) -> Vec<Complex> {
    let Region { re: (a, b), im_max, n_re, n_im } = region;
    let mut found: Vec<Complex> = real_roots(f, a, b, 4 * n_re).into_iter().map(Complex::from).collect();
    for i in 0..=n_re {
        for j in 0..=n_im {
            let seed = Complex::new(
                a + (b - a) * (i as f64 + 0.5) / (n_re as f64 + 1.0),
                im_max * (j as f64 + 0.5) / (n_im as f64 + 1.0),
            );
            let Some(mut z) = newton(f, seed) else { continue };
            if z.im.abs() <= 1e-12 * (1.0 + z.abs()) {
                z.im = 0.0;
            }
            // The conjugate is also a root; keep the upper-half representative.
            if z.im < 0.0 {
                z = z.conj();
            }
            let inside = z.re >= a && z.re <= b && z.im <= im_max;
            let new = found.iter().all(|w| (*w - z).abs() > 1e-8 * (1.0 + z.abs()));
            if inside && new {
                found.push(z);
            }
        }
    }
    found.sort_by(|p, q| p.re.total_cmp(&q.re));
    found
}

/// The root with the smallest real part strictly above `min_re`.
pub fn smallest_re_above(roots: &[Complex], min_re: f64) -> Option<Complex> {
    roots.iter().copied().filter(|z| z.re > min_re).min_by(|p, q| p.re.total_cmp(&q.re))
}

/// Number of zeros (with multiplicity) of f inside the rectangle [re.0, re.1] × [im.0, im.1]
/// by the argument principle: (1/2π) times the change of arg f around the boundary, traced
/// counter-clockwise with `n` points per side. f must not vanish on the boundary, and `n`
/// must be large enough that arg f changes by less than π between neighbouring points.
pub fn count_zeros(f: &impl Fn(Complex) -> Complex, re: (f64, f64), im: (f64, f64), n: usize) -> i64 {
    let corners = [
        Complex::new(re.0, im.0),
        Complex::new(re.1, im.0),
        Complex::new(re.1, im.1),
        Complex::new(re.0, im.1),
    ];
    let mut total = 0.0;
    let mut prev = f(corners[0]);
    for k in 0..4 {
        let (p, q) = (corners[k], corners[(k + 1) % 4]);
        for i in 1..=n {
            let cur = f(p + (q - p) * (i as f64 / n as f64));
            total += (cur / prev).arg();
            prev = cur;
        }
    }
    (total / (2.0 * std::f64::consts::PI)).round() as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_real_and_complex_roots_of_a_polynomial() {
        // (z - 0.5)(z - (2 + i))(z - (2 - i)) = (z - 0.5)(z^2 - 4z + 5).
        let f = |z: Complex| (z - 0.5) * (z * z - z * 4.0 + 5.0);
        let roots = find_roots(&f, Region { re: (0.0, 3.0), im_max: 2.0, n_re: 10, n_im: 5 });
        assert_eq!(roots.len(), 2, "{roots:?}");
        assert!((roots[0] - Complex::new(0.5, 0.0)).abs() < 1e-14);
        assert!((roots[1] - Complex::new(2.0, 1.0)).abs() < 1e-12);
        assert_eq!(count_zeros(&f, (0.0, 3.0), (-2.0, 2.0), 400), 3);
        assert_eq!(count_zeros(&f, (1.0, 3.0), (0.2, 2.0), 400), 1);
    }
}
