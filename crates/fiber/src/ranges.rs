//! Every parameter's range, in one place: the fiber models, the simulator, the renderer's scene
//! and the command line all check a value against the same [`Range`] (or [`CountRange`]), so a
//! value one of them accepts is one every other accepts too. Each range is written in the units
//! a user types (angles of the hair in degrees, θ_i in radians), and checks a value stored in
//! radians with [`Range::check_radians`] against the same bounds.
//!
//! A refused value is reported as a [`RangeError`] naming the parameter, the value (in short
//! form, [`short`]) and the range, in one line.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, SQRT_2};
use std::fmt;
use thiserror::Error;

/// One end of a range: included or not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum End {
    Closed(f64),
    Open(f64),
}

impl End {
    fn value(self) -> f64 {
        match self {
            End::Closed(v) | End::Open(v) => v,
        }
    }
}

/// The interval a real parameter must lie in (NaN and ±∞ never do).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// The parameter's name, as a scene key and (with dashes) as a flag.
    pub name: &'static str,
    pub min: End,
    pub max: End,
    /// Appended to the bounds when printed, e.g. `" degrees"`.
    pub unit: &'static str,
}

/// The interval a count must lie in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CountRange {
    pub name: &'static str,
    pub min: u64,
    pub max: u64,
}

/// A value outside its range.
#[derive(Clone, Debug, Error, PartialEq)]
#[error("{name} must be {rule}, got {value}", value = short(*.value))]
pub struct RangeError {
    pub name: &'static str,
    pub value: f64,
    /// "a finite number in (1, 10]", "a count in 1..=512", …
    pub rule: String,
}

impl Range {
    /// The same range under another name (a second key with the same meaning).
    pub const fn named(self, name: &'static str) -> Self {
        Self { name, ..self }
    }

    /// Whether `v` lies in the range (never for NaN or ±∞).
    pub fn contains(&self, v: f64) -> bool {
        self.contains_scaled(v, 1.0)
    }

    /// Whether `v` lies in the range with both ends multiplied by `k` > 0.
    fn contains_scaled(&self, v: f64, k: f64) -> bool {
        let above = match self.min {
            End::Closed(m) => v >= m * k,
            End::Open(m) => v > m * k,
        };
        let below = match self.max {
            End::Closed(m) => v <= m * k,
            End::Open(m) => v < m * k,
        };
        v.is_finite() && above && below
    }

    /// `v` if it lies in the range, else the error naming it.
    pub fn check(&self, v: f64) -> Result<f64, RangeError> {
        if self.contains(v) {
            Ok(v)
        } else {
            Err(self.error(v))
        }
    }

    /// Checks `radians` against this range of degrees (both ends converted as `to_radians`
    /// converts a value, so a value typed at a bound passes); the error reports degrees.
    pub fn check_radians(&self, radians: f64) -> Result<f64, RangeError> {
        if self.contains_scaled(radians, 1f64.to_radians()) {
            Ok(radians)
        } else {
            Err(self.error(radians.to_degrees()))
        }
    }

    /// Each of `values` checked in turn; the error names the first one outside.
    pub fn check_all(&self, values: &[f64]) -> Result<(), RangeError> {
        values.iter().try_for_each(|&v| self.check(v).map(|_| ()))
    }

    fn error(&self, value: f64) -> RangeError {
        RangeError {
            name: self.name,
            value,
            rule: format!("a finite number in {self}"),
        }
    }

    /// The smallest and largest values the range admits, as written.
    pub fn bounds(&self) -> (f64, f64) {
        (self.min.value(), self.max.value())
    }
}

impl fmt::Display for Range {
    /// `(1, 10]`, `[-20, 20] degrees`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (open, lo) = match self.min {
            End::Closed(v) => ('[', v),
            End::Open(v) => ('(', v),
        };
        let (close, hi) = match self.max {
            End::Closed(v) => (']', v),
            End::Open(v) => (')', v),
        };
        write!(f, "{open}{}, {}{close}{}", bound(lo), bound(hi), self.unit)
    }
}

impl CountRange {
    pub const fn named(self, name: &'static str) -> Self {
        Self { name, ..self }
    }

    pub fn contains(&self, n: u64) -> bool {
        (self.min..=self.max).contains(&n)
    }

    /// `n` if it lies in the range, else the error naming it.
    pub fn check(&self, n: u64) -> Result<u64, RangeError> {
        if self.contains(n) {
            Ok(n)
        } else {
            Err(self.error(n as f64))
        }
    }

    fn error(&self, value: f64) -> RangeError {
        RangeError {
            name: self.name,
            value,
            rule: format!("a whole number in {self}"),
        }
    }

    /// [`Self::check`] for a signed count (as a language without unsigned integers passes
    /// one): a negative `n` is refused as any other outside the range.
    pub fn check_signed(&self, n: i64) -> Result<u64, RangeError> {
        u64::try_from(n)
            .map_err(|_| self.error(n as f64))
            .and_then(|n| self.check(n))
    }

    /// [`Self::check`] for a `usize`.
    pub fn check_usize(&self, n: usize) -> Result<usize, RangeError> {
        self.check(n as u64).map(|_| n)
    }
}

impl fmt::Display for CountRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..={}", self.min, self.max)
    }
}

/// A bound as printed: five significant digits at most (1/√2 prints as 0.70711).
fn bound(v: f64) -> String {
    let rounded: f64 = format!("{v:.4e}").parse().unwrap_or(v);
    short(rounded)
}

/// A number in a form a person reads in one glance: plain for 1e-5 ≤ |v| < 1e7 (and 0), as
/// `1e300` or `2.5e-9` beyond, `NaN`, `inf`, `-inf` for the rest — never hundreds of digits.
pub fn short(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else if v == 0.0 || (1e-5..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Relative index of refraction η (fiber over surroundings): denser than the surroundings, and
/// no denser than any real material (beyond 10 the Fresnel factors of every model saturate).
pub const ETA: Range = Range {
    name: "eta",
    min: End::Open(1.0),
    max: End::Closed(10.0),
    unit: "",
};

/// The smallest roughness: the simulator's smooth limit. Below it the deterministic
/// quadratures of the models (lobe energies, the white furnace) would need panels finer than
/// they bound their time by (`furnace`'s `MAX_FINE_PANELS`).
pub const MIN_BETA: f64 = 1e-4;

/// Longitudinal roughness β (Beckmann, as the simulator uses it), radians.
pub const BETA: Range = Range {
    name: "beta",
    min: End::Closed(MIN_BETA),
    max: End::Closed(1.0),
    unit: "",
};

/// Scale tilt α, degrees (human hair: about −2 to −4; the R cone moves by 2α).
pub const ALPHA_DEG: Range = Range {
    name: "alpha_deg",
    min: End::Closed(-20.0),
    max: End::Closed(20.0),
    unit: " degrees",
};

/// Interior absorption per unit radius, each channel (beyond 1000 every internal lobe is black
/// to f64).
pub const MU_A: Range = Range {
    name: "mu_a",
    min: End::Closed(0.0),
    max: End::Closed(1000.0),
    unit: "",
};

/// Melanin concentrations (eumelanin, pheomelanin), which map to μ_a within [`MU_A`].
pub const MELANIN: Range = Range {
    name: "melanin",
    min: End::Closed(0.0),
    max: End::Closed(50.0),
    unit: "",
};

/// Incident inclination θ_i, radians.
pub const THETA_I: Range = Range {
    name: "theta_i",
    min: End::Open(-FRAC_PI_2),
    max: End::Open(FRAC_PI_2),
    unit: " radians",
};

/// Marschner 2003's longitudinal shift α_R, degrees (its Table 1: −10° to −5°); the largest
/// |α_R| is the largest scale tilt, which `Marschner2003::from_fiber` maps to it.
pub const ALPHA_R_DEG: Range = ALPHA_DEG.named("alpha_r_deg");

/// Marschner 2003's longitudinal width β_R, degrees (its Table 1: 5° to 10°). The smallest is
/// what `Marschner2003::from_fiber` makes of [`MIN_BETA`] (β_R = β/√2) and a little less; the
/// largest a little above 1 radian, the widest the model is tested at.
pub const BETA_R_DEG: Range = Range {
    name: "beta_r_deg",
    min: End::Closed(0.004),
    max: End::Closed(60.0),
    unit: " degrees",
};

/// Eccentricity a of the cross section: η* stays above 1 for every η > 1 exactly when
/// 1/√2 < a < √2 (Xu et al. 2011 eq. 24).
pub const ECCENTRICITY: Range = Range {
    name: "eccentricity",
    min: End::Open(FRAC_1_SQRT_2),
    max: End::Open(SQRT_2),
    unit: "",
};

/// Azimuthal width w_c of the TRT caustic glint, degrees (Marschner 2003 Table 1: 10° to 25°).
pub const CAUSTIC_WIDTH_DEG: Range = Range {
    name: "caustic_width_deg",
    min: End::Closed(0.01),
    max: End::Closed(90.0),
    unit: " degrees",
};

/// Fade range Δη′ over which the glint vanishes once the caustics merge (Table 1: 0.2 to 0.4).
pub const CAUSTIC_FADE: Range = Range {
    name: "caustic_fade",
    min: End::Open(0.0),
    max: End::Closed(2.0),
    unit: "",
};

/// Glint scale factor k_G (Table 1: 0.5 to 5).
pub const GLINT_SCALE: Range = Range {
    name: "glint_scale",
    min: End::Closed(0.0),
    max: End::Closed(100.0),
    unit: "",
};

/// Caustic intensity limit Δh_M (Table 1: 0.5).
pub const CAUSTIC_LIMIT: Range = Range {
    name: "caustic_limit",
    min: End::Open(0.0),
    max: End::Closed(2.0),
    unit: "",
};

/// Fixed-point iterations per sample of the non-separable model (d'Eon et al. 2014 uses 6).
pub const ITERATIONS: CountRange = CountRange {
    name: "iterations",
    min: 1,
    max: 1000,
};

/// Importance samples one command draws (the simulator's `MAX_RAYS` too): minutes of work.
pub const SAMPLES: CountRange = CountRange {
    name: "samples",
    min: 1,
    max: 1_000_000_000,
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_refuse_non_finite_values_and_name_them() {
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = ETA.check(v).unwrap_err();
            assert_eq!(e.name, "eta");
            assert!(
                e.to_string()
                    .starts_with("eta must be a finite number in (1, 10]")
            );
        }
        assert_eq!(
            ETA.check(1e300).unwrap_err().to_string(),
            "eta must be a finite number in (1, 10], got 1e300"
        );
        assert!(ETA.check(1.0).is_err() && ETA.check(10.0).is_ok());
        assert_eq!(
            ECCENTRICITY.to_string(),
            "(0.70711, 1.4142)",
            "five significant digits"
        );
    }

    #[test]
    fn degrees_stored_as_radians_pass_at_the_bounds_and_report_degrees() {
        for deg in [-20.0, 20.0, 0.0, 19.999] {
            assert!(
                ALPHA_DEG.check_radians(f64::to_radians(deg)).is_ok(),
                "{deg}"
            );
        }
        let e = ALPHA_DEG
            .check_radians(f64::to_radians(20.001))
            .unwrap_err();
        assert!((e.value - 20.001).abs() < 1e-9, "{e}");
        assert!(e.to_string().contains("[-20, 20] degrees"), "{e}");
    }

    #[test]
    fn short_numbers_stay_short() {
        assert_eq!(short(1.55), "1.55");
        assert_eq!(short(0.0025), "0.0025");
        assert_eq!(short(-2.0), "-2");
        assert_eq!(short(1e300), "1e300");
        assert_eq!(short(1e-300), "1e-300");
        assert_eq!(short(f64::NAN), "NaN");
        assert_eq!(short(f64::NEG_INFINITY), "-inf");
        assert!(short(f64::MAX).len() < 30);
    }

    #[test]
    fn counts_name_their_bounds() {
        assert_eq!(
            SAMPLES.check(0).unwrap_err().to_string(),
            "samples must be a whole number in 1..=1000000000, got 0"
        );
        assert_eq!(SAMPLES.check(5), Ok(5));
        assert_eq!(SAMPLES.check_signed(5), Ok(5));
        assert_eq!(
            SAMPLES.check_signed(-3).unwrap_err().to_string(),
            "samples must be a whole number in 1..=1000000000, got -3"
        );
    }
}
