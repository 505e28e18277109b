//! Real roots of a polynomial of degree at most three inside an interval.
//!
//! Marschner et al. 2003 approximate the azimuthal deflection by a cubic in γ_i and need every
//! root of it in [−π/2, π/2]: one or three, and exactly which near a caustic, where two of
//! them merge. Closed forms (Cardano, Viète) lose the count at such double roots to rounding;
//! here the interval is cut at the cubic's critical points into pieces on which it is
//! monotone, and each piece with a sign change holds exactly one root, found by Newton's
//! method safeguarded by bisection to full precision.

/// Up to three roots, in increasing order.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Roots {
    values: [f64; 3],
    len: usize,
}

impl Roots {
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn push(&mut self, x: f64) {
        if self.len < 3 && (self.len == 0 || self.values[self.len - 1] != x) {
            self.values[self.len] = x;
            self.len += 1;
        }
    }
}

/// A polynomial c₀ + c₁x + c₂x² + c₃x³.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cubic(pub [f64; 4]);

impl Cubic {
    pub fn eval(&self, x: f64) -> f64 {
        let [c0, c1, c2, c3] = self.0;
        ((c3 * x + c2) * x + c1) * x + c0
    }

    pub fn derivative(&self, x: f64) -> f64 {
        let [_, c1, c2, c3] = self.0;
        (3.0 * c3 * x + 2.0 * c2) * x + c1
    }

    /// Every real root in [lo, hi], in increasing order (a root of even multiplicity is
    /// reported once, where the polynomial touches zero exactly).
    pub fn roots_in(&self, lo: f64, hi: f64) -> Roots {
        let mut roots = Roots::default();
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return roots;
        }
        let mut cuts = [lo; 4];
        let mut n = 1;
        for x in self.critical_points() {
            if x > cuts[n - 1] && x < hi {
                cuts[n] = x;
                n += 1;
            }
        }
        cuts[n] = hi;
        for piece in cuts[..=n].windows(2) {
            if let Some(x) = self.monotone_root(piece[0], piece[1]) {
                roots.push(x);
            }
        }
        roots
    }

    /// Zeros of the derivative 3c₃x² + 2c₂x + c₁, increasing, by the cancellation-free
    /// quadratic formula.
    fn critical_points(&self) -> impl Iterator<Item = f64> {
        let [_, c1, c2, c3] = self.0;
        let (a, b, c) = (3.0 * c3, 2.0 * c2, c1);
        let mut out = [f64::NAN; 2];
        if a == 0.0 {
            if b != 0.0 {
                out[0] = -c / b;
            }
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                let (x1, x2) = if q != 0.0 { (q / a, c / q) } else { (0.0, 0.0) };
                out = [x1.min(x2), x1.max(x2)];
            }
        }
        out.into_iter().filter(|x| x.is_finite())
    }

    /// The root on [a, b], where the polynomial is monotone: an endpoint where it vanishes
    /// (the left one wins, so a root shared by two pieces is reported once), or the single
    /// crossing inside.
    fn monotone_root(&self, a: f64, b: f64) -> Option<f64> {
        let (fa, fb) = (self.eval(a), self.eval(b));
        if fa == 0.0 {
            return Some(a);
        }
        if fb == 0.0 {
            return Some(b);
        }
        if fa.signum() == fb.signum() {
            return None;
        }
        Some(self.bracketed_newton(a, b, fa))
    }

    /// Newton's method kept inside a shrinking bracket [a, b] with f(a) of sign `fa`;
    /// bisects whenever a Newton step would leave the bracket. Stops when a step or the
    /// bracket is below the rounding of the interval's scale.
    fn bracketed_newton(&self, a: f64, b: f64, fa: f64) -> f64 {
        let tol = 2.0 * f64::EPSILON * a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
        let (mut lo, mut hi) = (a, b);
        let mut x = 0.5 * (lo + hi);
        for _ in 0..200 {
            let f = self.eval(x);
            if f == 0.0 {
                return x;
            }
            if f.signum() == fa.signum() {
                lo = x;
            } else {
                hi = x;
            }
            let d = self.derivative(x);
            let newton = x - f / d;
            let next = if d != 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if (next - x).abs() <= tol || hi - lo <= tol {
                return next;
            }
            x = next;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_three_simple_roots() {
        // (x + 1)(x − 0.5)(x − 2) = x³ − 1.5x² − 1.5x + 1
        let c = Cubic([1.0, -1.5, -1.5, 1.0]);
        let r = c.roots_in(-3.0, 3.0);
        assert_eq!(r.len(), 3);
        for (got, want) in r.as_slice().iter().zip([-1.0, 0.5, 2.0]) {
            assert!((got - want).abs() < 1e-15, "{got} vs {want}");
        }
        assert_eq!(c.roots_in(0.0, 1.0).as_slice().len(), 1);
        assert!(c.roots_in(2.5, 3.0).is_empty());
    }

    #[test]
    fn cubic_double_root_and_lower_degrees() {
        // x²(x − 1): the double root at 0 is a critical point and counted once.
        let r = Cubic([0.0, 0.0, -1.0, 1.0]).roots_in(-1.0, 2.0);
        assert_eq!(r.as_slice(), &[0.0, 1.0]);
        // Quadratic and linear cases.
        let r = Cubic([-2.0, 0.0, 1.0, 0.0]).roots_in(-2.0, 2.0);
        assert_eq!(r.len(), 2);
        assert!((r.as_slice()[1] - 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(
            Cubic([1.0, -2.0, 0.0, 0.0]).roots_in(-1.0, 1.0).as_slice(),
            &[0.5]
        );
        assert!(Cubic([1.0, 0.0, 0.0, 0.0]).roots_in(-1.0, 1.0).is_empty());
    }
}
