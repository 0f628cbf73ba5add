//! Public-API check of the closed-form theory at the paper's scene (ν = 0.4) and at ν = 0.3;
//! `cargo test --release --test it analytical:: -- --nocapture` prints the table quoted in reports.

use std::f64::consts::FRAC_PI_2;
use tribofe::analytical::strip::{decay_distance_over_t, slowest_decay, Family};
use tribofe::analytical::williams::{clamped_free_exponent, refinement_growth, singularity_exponent};

#[test]
fn scene_values() {
    // (ν, λ, Re s t compression, s t shear) from an independent 20-digit mpmath solve.
    let expected = [
        (0.4, 0.649_910_000_949_360, 1.372_589_846_084_879, (4.280_417_305_554_925, 1.884_255_988_335_758)),
        (0.3, 0.711_172_932_971_466, 1.765_862_664_169_832, (4.330_069_931_420_756, 1.606_428_292_372_090)),
    ];
    for (nu, lambda, comp, shear) in expected {
        let l = clamped_free_exponent(FRAC_PI_2, nu).unwrap();
        let c = slowest_decay(nu, Family::Compression).unwrap();
        let s = slowest_decay(nu, Family::Shear).unwrap();
        let (dc, ds) = (
            decay_distance_over_t(nu, Family::Compression, 0.05).unwrap(),
            decay_distance_over_t(nu, Family::Shear, 0.05).unwrap(),
        );
        println!(
            "nu {nu}: lambda {:.6}{:+.6}i, 1-Re(lambda) {:.6}, growth/halving {:.6}; \
             compression s t {:.6}{:+.6}i, 5% at {:.4} t; shear s t {:.6}{:+.6}i, 5% at {:.4} t",
            l.re,
            l.im,
            singularity_exponent(l),
            refinement_growth(l),
            c.re,
            c.im,
            dc,
            s.re,
            s.im,
            ds
        );
        assert!((l.re - lambda).abs() < 1e-12 && l.im == 0.0);
        assert!((c.re - comp).abs() < 1e-12 && c.im == 0.0);
        assert!((s.re - shear.0).abs() < 1e-12 && (s.im - shear.1).abs() < 1e-12);
        assert!((dc - 20f64.ln() / comp).abs() < 1e-12 && (ds - 20f64.ln() / shear.0).abs() < 1e-12);
    }
}
