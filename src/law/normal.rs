//! The normal response: the normal stress a node's strength is taken on, sigma*, against the
//! contact's normal stress sigma. On a rigid flat an instantaneous response makes sliding
//! friction ill-posed above a friction threshold (Adams 1995; Martins & Simoes 1995); the
//! Prakash-Clifton lag regularises it (Prakash & Clifton 1993; Cochard & Rice 2000; Kammer et
//! al., JMPS 2014), with a time scale or a slip-length scale:
//!
//! ```text
//! time:    d sigma*/dt = -(sigma* - sigma) / T
//! length:  d sigma*/dt = -(sigma* - sigma) (|V| + V*) / L
//! ```
//!
//! each integrated implicitly over a step (unconditionally stable, sigma* between its old
//! value and sigma). The length form relaxes with slip, not with time: a node at rest keeps
//! its sigma* unless V* > 0.

use crate::error::{positive, Error, Result};

#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Normal {
    /// sigma* = sigma.
    #[default]
    Instantaneous,
    /// Prakash-Clifton with a time scale T, s.
    Time { t: f64 },
    /// Prakash-Clifton with a slip length L (m) and a reference rate V* >= 0 (m/s).
    Length { l: f64, v_star: f64 },
}

impl Normal {
    /// The time form; `key` names the parameter in a refusal as the user typed it.
    pub fn time(t: f64, key: &str) -> Result<Normal> {
        positive(key, t)?;
        Ok(Normal::Time { t })
    }

    /// The length form; `keys` name L and V* as the user typed them.
    pub fn length(l: f64, v_star: f64, keys: (&str, &str)) -> Result<Normal> {
        positive(keys.0, l)?;
        if !(v_star.is_finite() && v_star >= 0.0) {
            return Err(Error::input(keys.1, format!("{v_star}: give a reference slip rate V* >= 0 (m/s)")));
        }
        Ok(Normal::Length { l, v_star })
    }

    /// The response as a front end takes it: the length form if `length` L (m) is given (with
    /// `v_star` V*, m/s, default 0), else the time form of `lag` T (s; 0: instantaneous),
    /// else `default`. `keys` name the three as the user typed them.
    pub fn from_inputs(
        lag: Option<f64>,
        length: Option<f64>,
        v_star: Option<f64>,
        default: Normal,
        keys: [&str; 3],
    ) -> Result<Normal> {
        match (lag, length, v_star) {
            (Some(_), Some(_), _) => {
                Err(Error::input(keys[1], format!("give {} or {}, not both", keys[0], keys[1])))
            }
            (None, Some(l), v) => Normal::length(l, v.unwrap_or(0.0), (keys[1], keys[2])),
            (_, None, Some(_)) => {
                Err(Error::input(keys[2], format!("belongs to the length form: give {} too", keys[1])))
            }
            (Some(0.0), None, None) => Ok(Normal::Instantaneous),
            (Some(t), None, None) => Normal::time(t, keys[0]),
            (None, None, None) => Ok(default),
        }
    }

    /// sigma* after a step of `dt` (s) from `s_star` towards `sigma`, at slip rate `v` (m/s).
    #[inline]
    pub fn relax(&self, s_star: f64, sigma: f64, dt: f64, v: f64) -> f64 {
        let a = match *self {
            Normal::Instantaneous => return sigma,
            Normal::Time { t } => dt / t,
            Normal::Length { l, v_star } => dt * (v.abs() + v_star) / l,
        };
        (s_star + a * sigma) / (1.0 + a)
    }

    /// Whether sigma* carries a memory (a state per node).
    pub fn lags(&self) -> bool {
        *self != Normal::Instantaneous
    }

    /// How the outputs name it.
    pub fn name(&self) -> String {
        match *self {
            Normal::Instantaneous => "instantaneous".into(),
            Normal::Time { t } => format!("prakash-clifton (T = {t:e} s)"),
            Normal::Length { l, v_star } => format!("prakash-clifton (L = {l:e} m, V* = {v_star:e} m/s)"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_form_relaxes_as_its_ode() {
        // A step change of sigma from 0 to 1: sigma*(t) = 1 - exp(-t / T) for the time form,
        // 1 - exp(-slip / L) for the length form at constant V (V* = 0); the implicit update's
        // error is O(dt), below 1 % at 200 steps per scale.
        let (t_scale, l, v) = (1e-3, 1e-6, 1e-3);
        let (time, len) = (Normal::time(t_scale, "T").unwrap(), Normal::length(l, 0.0, ("L", "V*")).unwrap());
        let dt = t_scale / 200.0;
        let (mut a, mut b) = (0.0, 0.0);
        for _ in 0..400 {
            a = time.relax(a, 1.0, dt, 0.0);
            b = len.relax(b, 1.0, dt, v);
        }
        let want = 1.0 - (-2.0f64).exp();
        assert!((a - want).abs() < 0.01 * want, "{a} vs {want}");
        assert!((b - want).abs() < 0.01 * want, "{b} vs {want} (slip 2 L)");
        // At rest the length form keeps its memory; the time form does not.
        assert_eq!(len.relax(0.3, 1.0, 1.0, 0.0), 0.3);
        assert!(time.relax(0.3, 1.0, 1.0, 0.0) > 0.99);
        assert_eq!(Normal::Instantaneous.relax(0.3, 1.0, 1.0, 0.0), 1.0);
        assert!(Normal::time(0.0, "--normal-lag").unwrap_err().to_string().contains("--normal-lag"));
        assert!(Normal::length(1e-6, -1.0, ("L", "v_star")).unwrap_err().to_string().contains("v_star"));
    }
}
