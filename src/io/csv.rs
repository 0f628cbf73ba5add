//! CSV number formatting: [`push_e12`] writes exactly the bytes of `format!("{:.12e}", v)`
//! (Rust's correctly rounded 13 significant digits) several times faster, and
//! [`surely_finite`] tells the output guard which cells need no parse.
//!
//! The fast path covers 1e-10 <= |v| < 1e12 (every ordinary column of the slide outputs):
//! y = |v| 10^s with s = 12 - floor(log10 |v|) <= 22, so 10^s is exact and the product
//! hi + lo (lo by a fused multiply-add) is exact too; its integer part and its distance to
//! the half are then known exactly enough to round, except within 1e-9 of a tie. Ties, the
//! rest of the range, zero's sign aside, go to the standard formatter, whose output is the
//! reference the tests compare every fast result with.

use std::io::Write as _;

/// Appends `v` as `{:.12e}` would format it.
pub fn push_e12(out: &mut Vec<u8>, v: f64) {
    if !fast(out, v) {
        // Writing into a Vec cannot fail.
        let _ = write!(out, "{v:.12e}");
    }
}

/// `v` as `{:.12e}` formats it (the fast path where it applies).
pub fn e12(v: f64) -> String {
    let mut b = Vec::with_capacity(24);
    push_e12(&mut b, v);
    // ASCII digits, sign, '.', 'e' only.
    String::from_utf8(b).unwrap_or_default()
}

const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18,
    1e19, 1e20, 1e21, 1e22,
];

fn fast(out: &mut Vec<u8>, v: f64) -> bool {
    if v == 0.0 {
        out.extend_from_slice(if v.is_sign_negative() { b"-0.000000000000e0" } else { b"0.000000000000e0" });
        return true;
    }
    let a = v.abs();
    if !(1e-10..1e12).contains(&a) {
        return false;
    }
    // floor(log10 a) or one less, from the binary exponent (no libm call: a normal a in
    // [1e-10, 1e12) has log10 a in [e2 log10 2, e2 log10 2 + 0.302); 78913 / 2^18 is log10 2
    // to 3e-7, far inside the 0.01 by which e2 log10 2 misses an integer for these e2).
    let e2 = ((a.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let mut e10 = (e2 * 78913) >> 18;
    // (hi, lo): y = a 10^(12 - e10) exactly; the estimate of e10 may be one off either way.
    let prod = |e10: i32| -> Option<(f64, f64)> {
        let s = 12 - e10;
        let p = *POW10.get(usize::try_from(s).ok()?)?;
        let hi = a * p;
        Some((hi, a.mul_add(p, -hi)))
    };
    let Some(mut y) = prod(e10) else { return false };
    for _ in 0..2 {
        if y.0 < 1e12 || (y.0 == 1e12 && y.1 < 0.0) {
            e10 -= 1;
        } else if y.0 > 1e13 || (y.0 == 1e13 && y.1 >= 0.0) {
            e10 += 1;
        } else {
            break;
        }
        let Some(z) = prod(e10) else { return false };
        y = z;
    }
    let (hi, lo) = y;
    if !(1e12..=1e13).contains(&hi) {
        return false;
    }
    // hi is positive: truncation is its floor.
    let mut n = hi as u64;
    let fl = n as f64;
    // hi - fl is exact (hi < 2^44 has at most 9 fraction bits); |lo| <= 2^-10.
    let mut frac = (hi - fl) + lo;
    if frac < 0.0 {
        n -= 1;
        frac += 1.0;
    } else if frac >= 1.0 {
        n += 1;
        frac -= 1.0;
    }
    if (frac - 0.5).abs() < 1e-9 {
        return false;
    }
    if frac > 0.5 {
        n += 1;
    }
    if n == 10_000_000_000_000 {
        n = 1_000_000_000_000;
        e10 += 1;
    }
    if !(1_000_000_000_000..10_000_000_000_000).contains(&n) {
        return false;
    }
    let mut d = [0u8; 13];
    for k in (0..13).rev() {
        d[k] = b'0' + (n % 10) as u8;
        n /= 10;
    }
    if v < 0.0 {
        out.push(b'-');
    }
    out.push(d[0]);
    out.push(b'.');
    out.extend_from_slice(&d[1..]);
    out.push(b'e');
    if e10 < 0 {
        out.push(b'-');
    }
    let e = e10.unsigned_abs();
    if e >= 10 {
        out.push(b'0' + (e / 10) as u8);
    }
    out.push(b'0' + (e % 10) as u8);
    true
}

/// Whether a CSV cell certainly does not parse as a non-finite f64 (so the output guard may
/// skip parsing it). Such a parse needs `inf`, `infinity` or `nan` (any case, one sign) or a
/// number too large for f64; a cell is passed when it is under 200 ASCII bytes without
/// whitespace (what `trim` would remove) and either is a word other than those three or has
/// no letter but one e/E followed by an optional sign and at most two digits (so at most
/// 10^200 10^99 < f64::MAX). Anything else is for the parse to judge.
pub fn surely_finite(cell: &[u8]) -> bool {
    if cell.len() >= 200 {
        return false;
    }
    // One pass: the first e/E, whether another letter occurs; whitespace, control and
    // non-ASCII bytes are for the parse.
    let (mut e_at, mut word) = (usize::MAX, false);
    for (k, &b) in cell.iter().enumerate() {
        match b {
            b'0'..=b'9' | b'.' | b'+' | b'-' => {}
            b'e' | b'E' => e_at = e_at.min(k),
            0x21..=0x7e => word = true,
            _ => return false,
        }
    }
    if word {
        // Only the three words parse (as non-finite values); any other word does not parse.
        let body = match cell {
            [b'+' | b'-', tail @ ..] => tail,
            _ => cell,
        };
        return ![&b"inf"[..], b"infinity", b"nan"].iter().any(|w| body.eq_ignore_ascii_case(w));
    }
    if e_at == usize::MAX {
        return true;
    }
    let mut rest = &cell[e_at + 1..];
    if let [b'+' | b'-', tail @ ..] = rest {
        rest = tail;
    }
    rest.len() <= 2 && rest.iter().all(u8::is_ascii_digit)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(v: f64) {
        let want = format!("{v:.12e}");
        let got = e12(v);
        assert_eq!(got, want, "value {v:e} (bits {:#x})", v.to_bits());
    }

    /// Deterministic 64-bit numbers (splitmix64).
    fn rng(mut s: u64) -> impl FnMut() -> u64 {
        move || {
            s = s.wrapping_add(0x9e3779b97f4a7c15);
            let mut z = s;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
            z ^ (z >> 31)
        }
    }

    #[test]
    fn equals_the_standard_formatter_on_random_values() {
        let mut r = rng(1);
        // Any bit pattern (every exponent, subnormals), then the fast path's range densely.
        for _ in 0..400_000 {
            let v = f64::from_bits(r());
            if v.is_finite() {
                check(v);
            }
        }
        for _ in 0..1_000_000 {
            let m = (r() >> 11) as f64 / (1u64 << 53) as f64 + 0.5;
            let e = (r() % 50) as i32 - 36;
            let v = m * 2f64.powi(e);
            check(if r().is_multiple_of(2) { v } else { -v });
        }
    }

    #[test]
    fn equals_the_standard_formatter_on_edge_values() {
        let mut vals = vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::from_bits(1),
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            0.5,
            1.0,
            -1.0,
            1e-10,
            1e12,
        ];
        for k in -30..=30 {
            let p = 10f64.powi(k);
            for v in [
                p,
                p.next_up(),
                p.next_down(),
                9.9999999999995 * p,
                9.99999999999949 * p,
                1.0000000000005 * p,
            ] {
                vals.extend([v, v.next_up(), v.next_down(), -v]);
            }
        }
        // Exact ties at the 13th digit: 13 digits before the point and .5, and binary
        // fractions whose decimal expansion ends in 5 at the 14th digit.
        let mut r = rng(2);
        for _ in 0..20_000 {
            let k = 1_000_000_000_000 + r() % 9_000_000_000_000;
            let t = k as f64 + 0.5;
            vals.extend([t, t.next_up(), t.next_down(), t / 1024.0, t / 2f64.powi(30), t * 1e-12]);
            let v = (r() % 100_000_000_000_000) as f64 * 2f64.powi(-((r() % 60) as i32));
            vals.extend([v, -v]);
        }
        for v in vals {
            check(v);
        }
    }

    #[test]
    fn finite_cells_are_recognised_and_the_rest_left_to_the_parse() {
        for c in [
            "1.5",
            "-2.000000000000e-7",
            "0",
            "12",
            "1e99",
            "1E+05",
            "",
            "event",
            "-",
            "stick",
            "-+inf",
            "infx",
            "1e5e5",
        ] {
            let b = c.as_bytes();
            // Whatever the guard skips parses as finite or not at all.
            if surely_finite(b) {
                assert!(c.parse::<f64>().map_or(true, f64::is_finite), "{c}");
            }
        }
        for c in ["inf", "-inf", "+NaN", "Infinity", "1e400", "1e999", " 1", "1e308", "inf\u{a0}"] {
            assert!(!surely_finite(c.as_bytes()), "{c} must be parsed");
        }
        assert!(surely_finite(b"-1.234567890123e-7"));
        assert!(surely_finite(b"42"));
        assert!(surely_finite(b"tip-advance"));
        let long = "9".repeat(250);
        assert!(!surely_finite(long.as_bytes()));
    }

    /// The CSV guard with its fast screen still refuses every non-finite cell, names its line
    /// and column, and passes words and numbers.
    #[test]
    fn the_output_guard_still_refuses_non_finite_cells() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.csv");
        crate::report::write_atomic(&p, b"event,x,state\n0,1.5e-7,stick\n1,-2.0e3,tip-advance\n").unwrap();
        for (text, line, col) in [
            (&b"a,b\n1,NaN\n"[..], 2, 2),
            (b"a,b\n1,2\r\n-inf,3\n", 3, 1),
            (b"a\n1e999\n", 2, 1),
            (b"a,b\n0, infinity\n", 2, 2),
        ] {
            let e = crate::report::write_atomic(&p, text).unwrap_err().to_string();
            assert!(e.contains(&format!("line {line} column {col}")), "{e}");
        }
    }
}
