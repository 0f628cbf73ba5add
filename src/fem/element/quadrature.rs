//! Quadrature rules on the reference quadrilateral [-1, 1]^2 and triangle {r, s >= 0, r + s <= 1}.

/// A point in reference coordinates with its weight.
#[derive(Debug, Clone, Copy)]
pub struct QPoint {
    pub xi: [f64; 2],
    pub w: f64,
}

/// 1D Gauss-Legendre points and weights on [-1, 1], n = 1..=4.
pub fn gauss_1d(n: usize) -> &'static [(f64, f64)] {
    const G1: [(f64, f64); 1] = [(0.0, 2.0)];
    const A2: f64 = 0.577_350_269_189_625_8;
    const G2: [(f64, f64); 2] = [(-A2, 1.0), (A2, 1.0)];
    const A3: f64 = 0.774_596_669_241_483_4;
    const G3: [(f64, f64); 3] = [(-A3, 5.0 / 9.0), (0.0, 8.0 / 9.0), (A3, 5.0 / 9.0)];
    const A4: f64 = 0.861_136_311_594_052_6;
    const B4: f64 = 0.339_981_043_584_856_3;
    const W4A: f64 = 0.347_854_845_137_453_9;
    const W4B: f64 = 0.652_145_154_862_546_1;
    const G4: [(f64, f64); 4] = [(-A4, W4A), (-B4, W4B), (B4, W4B), (A4, W4A)];
    match n {
        1 => &G1,
        2 => &G2,
        3 => &G3,
        4 => &G4,
        _ => panic!("gauss_1d: n = {n} not tabulated (1..=4)"),
    }
}

/// Tensor-product Gauss rule with n x n points; point order is xi fastest.
pub fn gauss_quad(n: usize) -> Vec<QPoint> {
    let g = gauss_1d(n);
    let mut pts = Vec::with_capacity(n * n);
    for &(eta, we) in g {
        for &(xi, wx) in g {
            pts.push(QPoint { xi: [xi, eta], w: wx * we });
        }
    }
    pts
}

/// Symmetric triangle rules (Strang & Fix / Dunavant) exact to `degree` (1, 2 or 4).
pub fn gauss_tri(degree: usize) -> Vec<QPoint> {
    match degree {
        0 | 1 => vec![QPoint { xi: [1.0 / 3.0, 1.0 / 3.0], w: 0.5 }],
        2 => [[1.0 / 6.0, 1.0 / 6.0], [2.0 / 3.0, 1.0 / 6.0], [1.0 / 6.0, 2.0 / 3.0]]
            .iter()
            .map(|&xi| QPoint { xi, w: 1.0 / 6.0 })
            .collect(),
        3 | 4 => {
            let (a1, w1) = (0.445_948_490_915_965, 0.223_381_589_678_011 / 2.0);
            let (a2, w2) = (0.091_576_213_509_771, 0.109_951_743_655_322 / 2.0);
            let mut pts = Vec::with_capacity(6);
            for &(a, w) in &[(a1, w1), (a2, w2)] {
                let b = 1.0 - 2.0 * a;
                for xi in [[a, a], [b, a], [a, b]] {
                    pts.push(QPoint { xi, w });
                }
            }
            pts
        }
        _ => panic!("gauss_tri: degree {degree} not tabulated (1, 2, 4)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn rules_integrate_polynomials() {
        // int over [-1,1]^2 of x^2 y^2 = 4/9
        let s: f64 = gauss_quad(2).iter().map(|p| p.w * p.xi[0].powi(2) * p.xi[1].powi(2)).sum();
        assert!((s - 4.0 / 9.0).abs() < 1e-14);
        let s: f64 = gauss_quad(3).iter().map(|p| p.w * p.xi[0].powi(4) * p.xi[1].powi(4)).sum();
        assert!((s - 4.0 / 25.0).abs() < 1e-14);
        // int over triangle of r^2 s^2 = 2! 2! / 6! = 1/180
        let s: f64 = gauss_tri(4).iter().map(|p| p.w * p.xi[0].powi(2) * p.xi[1].powi(2)).sum();
        assert!((s - 1.0 / 180.0).abs() < 1e-12);
        let s: f64 = gauss_tri(2).iter().map(|p| p.w * p.xi[0] * p.xi[1]).sum();
        assert!((s - 1.0 / 24.0).abs() < 1e-15);
    }
}
