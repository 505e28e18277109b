//! The product integral of a 1D Gaussian with a smooth function by piecewise-linear
//! quadrature (Xu et al. 2011 §4.2.2): f is sampled at m + 1 points — the two ends ±π/2 and m − 1
//! points spread uniformly over μ ± (m − 2)λ/2 — and ∫ g · (b_s x + c_s) is exact on each piece.

use crate::angles::{Incident, Outgoing};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};

/// The most segments m the quadrature accepts.
pub const MAX_SEGMENTS: usize = 256;

/// scale · exp(−(x − μ)²/(2σ²)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Window {
    pub scale: f64,
    pub mu: f64,
    pub sigma: f64,
}

impl Window {
    /// The product of an SRBF's longitudinal Gaussian exp(−(x − θ_j)²/λ²) (Xu et al. 2011 eq. 11)
    /// and the unit normal density of mean `mean`, deviation `dev`.
    pub fn product(theta_j: f64, lambda: f64, mean: f64, dev: f64) -> Self {
        let va = 0.5 * lambda * lambda;
        let vb = dev * dev;
        let var = va * vb / (va + vb);
        Self {
            scale: (-(theta_j - mean).powi(2) / (2.0 * (va + vb))).exp()
                / (dev * (2.0 * PI).sqrt()),
            mu: (theta_j * vb + mean * va) / (va + vb),
            sigma: var.sqrt(),
        }
    }

    /// The product of a unit normal density N(x; a, μ_a) with another N(x; b, σ_b).
    pub fn normal_product(a: f64, dev_a: f64, b: f64, dev_b: f64) -> Self {
        let (va, vb) = (dev_a * dev_a, dev_b * dev_b);
        let s = va + vb;
        Self {
            scale: (-(a - b).powi(2) / (2.0 * s)).exp()
                / (2.0 * PI * s).sqrt()
                / (2.0 * PI * va * vb / s).sqrt(),
            mu: (a * vb + b * va) / s,
            sigma: (va * vb / s).sqrt(),
        }
    }

    /// The Gaussian's bandwidth in the paper's sense, λ = √2 σ.
    pub fn bandwidth(&self) -> f64 {
        SQRT_2 * self.sigma
    }

    /// The window's erfc and exponential at `x`, which the two segments meeting there share.
    fn edge(&self, x: f64) -> Edge {
        let u = (x - self.mu) / (SQRT_2 * self.sigma);
        // Beyond |u| = 27 both vanish in f64; skipping exp's slow underflow path there matters
        // because the ends ±π/2 of a narrow window usually lie that far out.
        let gauss = if u * u < 729.0 { (-u * u).exp() } else { 0.0 };
        Edge {
            x,
            u,
            // erfc_from_gauss is a factor times `gauss`: zero where that is, without its
            // division (the same test as gauss's, so a NaN still propagates).
            erfc_abs: if u * u >= 729.0 {
                0.0
            } else {
                erfc_from_gauss(u.abs(), gauss)
            },
            gauss,
        }
    }

    /// ∫ over [a.x, b.x] of this window times the line through (a.x, f0) and (b.x, f1).
    fn segment(&self, a: &Edge, b: &Edge, f0: DVec3, f1: DVec3) -> DVec3 {
        let i0 = self.sigma * (PI / 2.0).sqrt() * erf_difference(a, b);
        let i1 = self.sigma * self.sigma * (a.gauss - b.gauss);
        let slope = (f1 - f0) / (b.x - a.x);
        self.scale * (f0 * i0 + slope * (i1 + (self.mu - a.x) * i0))
    }

    /// The m + 1 sample points of §4.2.2 over [−π/2, π/2]: the ends, and m − 1 points spread
    /// uniformly over μ ± (m − 2)λ/2 clipped to the interval (clipping the span rather than
    /// each point keeps all m − 1 inside when the window is wide).
    pub fn nodes(&self, m: usize) -> Nodes {
        let m = m.clamp(2, MAX_SEGMENTS);
        let half = (m - 2) as f64 * 0.5 * self.bandwidth();
        Nodes {
            m,
            lo: (self.mu - half).clamp(-FRAC_PI_2, FRAC_PI_2),
            hi: (self.mu + half).clamp(-FRAC_PI_2, FRAC_PI_2),
        }
    }

    /// ∫_{−π/2}^{π/2} window · f with f piecewise linear through m + 1 samples. `f` is not
    /// called at the ends ±π/2 (nodes 0 and m), where every integrand of the renderer vanishes
    /// (cos²θ_i), but an interior node clipped to ±π/2 is passed to it: integrands must give
    /// their limit there.
    pub fn integrate(&self, m: usize, mut f: impl FnMut(f64) -> DVec3) -> DVec3 {
        let nodes = self.nodes(m);
        let mut left = self.edge(nodes.at(0));
        let mut prev = DVec3::ZERO;
        let mut sum = DVec3::ZERO;
        for s in 1..=nodes.m {
            let xs = nodes.at(s);
            let value = if s == nodes.m { DVec3::ZERO } else { f(xs) };
            let right = self.edge(xs);
            if right.x > left.x {
                sum += self.segment(&left, &right, prev, value);
            }
            (left, prev) = (right, value);
        }
        sum
    }
}

/// The nodes of [`Window::nodes`], computed on demand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nodes {
    /// Segments.
    pub m: usize,
    lo: f64,
    hi: f64,
}

impl Nodes {
    /// Node `s` of 0..=m.
    pub fn at(&self, s: usize) -> f64 {
        match s {
            0 => -FRAC_PI_2,
            s if s >= self.m => FRAC_PI_2,
            _ if self.m == 2 => self.lo,
            s => self.lo + (self.hi - self.lo) * (s - 1) as f64 / (self.m - 2) as f64,
        }
    }
}

/// A segment end in the window's variable u = (x − μ)/(√2 σ).
struct Edge {
    x: f64,
    u: f64,
    erfc_abs: f64,
    gauss: f64,
}

/// erfc(x), x ≥ 0, given e^{−x²}: Abramowitz & Stegun 7.1.26, absolute error below 1.5e-7, which
/// shares the exponential the segment's first moment needs anyway.
fn erfc_from_gauss(x: f64, gauss: f64) -> f64 {
    const P: f64 = 0.327_591_1;
    const A: [f64; 5] = [
        0.254_829_592,
        -0.284_496_736,
        1.421_413_741,
        -1.453_152_027,
        1.061_405_429,
    ];
    let t = 1.0 / (1.0 + P * x);
    t * (A[0] + t * (A[1] + t * (A[2] + t * (A[3] + t * A[4])))) * gauss
}

/// Below this scale a window contributes nothing worth integrating.
const NEGLIGIBLE_SCALE: f64 = 1e-12;

impl Window {
    /// ∫ window · n(θ_i) cos²θ_i / cos²θ_d dθ_i with θ_d = (θ_o − θ_i)/2: the outer integral of
    /// Xu et al. 2011 eqs. 11, 27 and 29, whose factor cos²θ_i/cos²θ_d every mode shares. A
    /// negligible window gives zero, and so does a grazing sample (cos θ_i ≤ 1e-6, where n may not
    /// be defined).
    pub fn integrate_incident(
        &self,
        m: usize,
        outgoing: &Outgoing,
        mut n: impl FnMut(&Incident) -> DVec3,
    ) -> DVec3 {
        if self.scale < NEGLIGIBLE_SCALE {
            return DVec3::ZERO;
        }
        self.integrate(m, |theta_i| {
            let s = outgoing.incident(theta_i);
            if s.cos_i <= 1e-6 {
                return DVec3::ZERO;
            }
            n(&s) * (s.cos_i * s.cos_i / s.cos2_d)
        })
    }
}

/// erf(u1) − erf(u0) without cancellation in the tails, from erfc(|u|) at each end.
fn erf_difference(a: &Edge, b: &Edge) -> f64 {
    if a.u >= 0.0 {
        a.erfc_abs - b.erfc_abs
    } else if b.u <= 0.0 {
        b.erfc_abs - a.erfc_abs
    } else {
        2.0 - b.erfc_abs - a.erfc_abs
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fine(w: &Window, f: impl Fn(f64) -> f64) -> f64 {
        let n = 200_000;
        let dx = PI / n as f64;
        (0..n)
            .map(|i| {
                let x = -FRAC_PI_2 + (i as f64 + 0.5) * dx;
                w.scale * (-(x - w.mu).powi(2) / (2.0 * w.sigma * w.sigma)).exp() * f(x) * dx
            })
            .sum()
    }

    /// erfc by A&S 7.1.26 against the full-precision one: 1.5e-7 absolute.
    #[test]
    fn fast_erfc_is_within_its_bound() {
        for i in 0..=600 {
            let x = 0.01 * i as f64;
            let err = (erfc_from_gauss(x, (-x * x).exp()) - cuticle_fiber::math::erfc(x)).abs();
            assert!(err < 1.5e-7, "erfc({x}): {err}");
        }
    }

    /// The window product is the pointwise product, and for m = 2, 3, 4, 7 the rule is exact on
    /// the piecewise-linear interpolant through its nodes.
    #[test]
    fn exact_for_piecewise_linear_and_product_is_pointwise() {
        let w = Window::product(0.3, 0.4, -0.1, 0.2);
        let g = |x: f64| {
            (-(x - 0.3f64).powi(2) / 0.16).exp() * (-(x + 0.1f64).powi(2) / 0.08).exp()
                / (0.2 * (2.0 * PI).sqrt())
        };
        for &x in &[-0.5, 0.0, 0.2, 0.9] {
            let v = w.scale * (-(x - w.mu).powi(2) / (2.0 * w.sigma * w.sigma)).exp();
            assert!((v - g(x)).abs() < 1e-12 * g(x).max(1e-300) + 1e-15);
        }
        // For every m the rule integrates exactly the piecewise-linear interpolant of f through
        // its own nodes (f is zero at the ends, as the renderer's integrands are).
        let f = |x: f64| x.cos() * (1.0 + 0.3 * x);
        for m in [2, 3, 4, 7] {
            let nodes = w.nodes(m);
            let x: Vec<f64> = (0..=m).map(|s| nodes.at(s)).collect();
            assert!(x.windows(2).all(|p| p[0] <= p[1]), "m {m}: {x:?}");
            assert_eq!((x[0], x[m]), (-FRAC_PI_2, FRAC_PI_2));
            let interpolant = |t: f64| {
                let k = x.partition_point(|&n| n <= t).clamp(1, m);
                let (a, b) = (x[k - 1], x[k]);
                let (fa, fb) = (
                    if k == 1 { 0.0 } else { f(a) },
                    if k == m { 0.0 } else { f(b) },
                );
                if b > a {
                    fa + (fb - fa) * (t - a) / (b - a)
                } else {
                    fa
                }
            };
            let q = w.integrate(m, |t| DVec3::splat(f(t))).x;
            let want = fine(&w, interpolant);
            assert!((q / want - 1.0).abs() < 1e-6, "m {m}: {q} vs {want}");
        }
    }

    /// The linear quadrature against a fine quadrature on smooth integrands of the renderer's
    /// kind (cos²θ times a slowly varying factor): m = 4 within 6 % (the worst case is a wide
    /// window, λ = 2, where five samples miss the cos² curvature), m = 200 within 0.1 % (the
    /// paper's reference), and for the narrow windows of the M lobes m = 2 worse than m = 4.
    #[test]
    fn linear_quadrature_converges_to_fine_quadrature() {
        let f = |x: f64| x.cos().powi(2) * (1.0 + 0.5 * (2.0 * x + 0.3).sin());
        let cases = [
            (0.2, 0.5, -0.2, 0.26),
            (-0.6, 1.2, 0.4, 0.13),
            (0.0, 2.0, 0.1, 0.5),
        ];
        for (i, &(theta_j, lambda, mean, dev)) in cases.iter().enumerate() {
            let w = Window::product(theta_j, lambda, mean, dev);
            let reference = fine(&w, f);
            let err = |m| (w.integrate(m, |x| DVec3::splat(f(x))).x / reference - 1.0).abs();
            assert!(err(4) < 0.06, "m=4: {}", err(4));
            assert!(err(200) < 0.001, "m=200: {}", err(200));
            if i < 2 {
                assert!(err(2) > err(4), "m=2 {} vs m=4 {}", err(2), err(4));
            }
        }
    }
}
