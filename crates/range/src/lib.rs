//! The range a parameter must lie in, for every crate of cuticle: a [`Range`] of reals or a
//! [`CountRange`] of whole numbers, each named as its scene key and flag. Every crate checks a
//! value against the same constant (which lives beside what it bounds: the fiber's parameters
//! in `cuticle_fiber::ranges`, the light's in `cuticle_light`, the scene's in
//! `cuticle_render::scene`), so a value one of them accepts is one every other accepts too. A
//! range is written in the units a user types (angles of the hair in degrees, θ_i in radians),
//! and checks a value stored in radians with [`Range::check_radians`] against the same bounds.
//!
//! A refused value is reported as a [`RangeError`] naming the parameter, the value (in short
//! form, [`short`]) and the range, in one line.

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

#[cfg(test)]
mod tests {
    use super::*;

    const WIDTH: Range = Range {
        name: "width",
        min: End::Open(0.0),
        max: End::Closed(2.5),
        unit: " degrees",
    };

    #[test]
    fn ends_open_and_closed_and_non_finite_values() {
        assert!(!WIDTH.contains(0.0) && WIDTH.contains(1e-300) && WIDTH.contains(2.5));
        for v in [f64::NAN, f64::INFINITY, -1.0, 2.5000001] {
            assert!(WIDTH.check(v).is_err(), "{v}");
        }
        assert_eq!(
            WIDTH.named("w").check(3.0).unwrap_err().to_string(),
            "w must be a finite number in (0, 2.5] degrees, got 3"
        );
        assert_eq!(WIDTH.bounds(), (0.0, 2.5));
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
}
