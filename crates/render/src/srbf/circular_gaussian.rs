//! 1D circular Gaussians g^c(x; μ, λ) = exp(2(cos(x − μ) − 1)/λ²) (Xu et al. 2011 Table 1), their
//! integrals over the circle and the closed-form integral of a product of two (Xu et al. 2011
//! §4.2.3, supplemental §5). With κ = 2/λ², κ₁ cos(x − μ₁) + κ₂ cos(x − μ₂) = κ cos(x − μ) with
//! κ e^{iμ} = κ₁ e^{iμ₁} + κ₂ e^{iμ₂}, and ∫_{−π}^{π} e^{κ cos x} dx = 2π I₀(κ).

use std::f64::consts::PI;

/// The polynomial of Abramowitz & Stegun 9.8.1 in t = (x/3.75)², x ≤ 3.75: I₀(x) = p.
fn i0_small(x: f64) -> f64 {
    let t = (x / 3.75).powi(2);
    1.0 + t
        * (3.5156229
            + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813)))))
}

/// The polynomial of Abramowitz & Stegun 9.8.2 in t = 3.75/x, x > 3.75: I₀(x) = e^x q / √x.
fn i0_large(x: f64) -> f64 {
    let t = 3.75 / x;
    0.39894228
        + t * (0.01328592
            + t * (0.00225319
                + t * (-0.00157565
                    + t * (0.00916281
                        + t * (-0.02057706
                            + t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))))
}

/// Where Abramowitz & Stegun switch from 9.8.1 to 9.8.2.
const I0_SWITCH: f64 = 3.75;

/// I₀(κ) e^{s} for κ ≥ 0 and an exponent s ≤ 0 with κ + s ≤ 0, without a logarithm: the hot
/// path's one exponential (9.8.1 below the switch, 9.8.2 above; relative error of I₀ below
/// 2e-7).
fn i0_times_exp(kappa: f64, s: f64) -> f64 {
    if kappa + s < -745.0 {
        // e^{κ+s} underflows (and I₀ e^{−κ} ≤ 1): skip exp's slow path.
        return 0.0;
    }
    if kappa <= I0_SWITCH {
        i0_small(kappa) * s.exp()
    } else {
        i0_large(kappa) / kappa.sqrt() * (kappa + s).exp()
    }
}

/// κ = 2/λ².
pub fn sharpness(lambda: f64) -> f64 {
    2.0 / (lambda * lambda)
}

/// λ = √(2/κ).
pub fn bandwidth(kappa: f64) -> f64 {
    (2.0 / kappa).sqrt()
}

/// g^c(x; μ, λ).
pub fn eval(x: f64, mu: f64, lambda: f64) -> f64 {
    (sharpness(lambda) * ((x - mu).cos() - 1.0)).exp()
}

/// ∫_{−π}^{π} g^c(x; μ, λ) dx = 2π e^{−κ} I₀(κ) (exact; the paper's √π λ is its narrow limit).
pub fn integral(lambda: f64) -> f64 {
    let kappa = sharpness(lambda);
    2.0 * PI * i0_times_exp(kappa, -kappa)
}

/// ∫_{−π}^{π} g^c(x; 0, λ₁) g^c(δ − x; μ₂, λ₂) dx: the inner integral 𝒩 of an azimuthal lobe
/// g^c(φ; μ₂, λ₂) against a light's azimuthal Gaussian at offset δ = φ_o − φ_j (Xu et al. 2011 eq.
/// 12). As a function of x the second factor is centred at δ − μ₂, so the product has
/// κ = |κ₁ + κ₂ e^{i(δ − μ₂)}| and integral 2π exp(ln I₀(κ) − κ₁ − κ₂).
pub fn convolve(lambda1: f64, delta: f64, mu2: f64, lambda2: f64) -> f64 {
    convolve_sharp(sharpness(lambda1), sharpness(lambda2), (delta - mu2).cos())
}

/// [`convolve`] from the sharpnesses κ₁, κ₂ and c = cos(δ − μ₂), which shading shares across
/// lobes and channels.
pub fn convolve_sharp(k1: f64, k2: f64, c: f64) -> f64 {
    let kappa = (k1 * k1 + k2 * k2 + 2.0 * k1 * k2 * c).max(0.0).sqrt();
    2.0 * PI * i0_times_exp(kappa, -k1 - k2)
}

/// The bandwidth λ whose circular Gaussian integrates to `area` over the circle: the exact
/// inverse of [`integral`] (Xu et al. 2011 eq. 17 uses its narrow limit λ = area/√π, whose energy
/// is off by 5 % at λ ≈ 0.8, 9 % at λ = 1 and 17 % at λ = 1.5). By a table of the correction
/// λ/(area/√π) over ln(area/√π), built once; areas at or beyond 2π (a uniform lobe) give the
/// widest bandwidth, 20.
pub fn bandwidth_for_integral(area: f64) -> f64 {
    let naive = area / PI.sqrt();
    if naive <= WIDTH_TABLE.0 {
        return naive;
    }
    if area >= 2.0 * PI * 0.99995 {
        return 20.0;
    }
    let table = WIDTH_CORRECTION.get_or_init(build_width_table);
    let (l0, l1) = (WIDTH_TABLE.0.ln(), WIDTH_TABLE.1.ln());
    let t = ((naive.ln() - l0) / (l1 - l0)).clamp(0.0, 1.0) * (WIDTH_TABLE.2 - 1) as f64;
    let i = (t as usize).min(WIDTH_TABLE.2 - 2);
    let f = t - i as f64;
    naive * (table[i] + f * (table[i + 1] - table[i]))
}

/// The width table of [`bandwidth_for_integral`] for a back end that uploads it: the
/// correction λ/(area/√π) at `nodes` points evenly spaced in ln(area/√π) over `range`; below
/// the range the correction is 1, at or beyond an area of 2π·0.99995 the bandwidth is 20.
pub struct WidthTable {
    pub range: (f64, f64),
    pub correction: &'static [f64],
}

/// The width table [`bandwidth_for_integral`] reads.
pub fn width_table() -> WidthTable {
    WidthTable {
        range: (WIDTH_TABLE.0, WIDTH_TABLE.1),
        correction: WIDTH_CORRECTION.get_or_init(build_width_table),
    }
}

static WIDTH_CORRECTION: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();

/// Range of area/√π the width table covers, and its node count.
const WIDTH_TABLE: (f64, f64, usize) = (1e-3, 2.0 * 1.772_453_850_905_516, 512);

fn build_width_table() -> Vec<f64> {
    let (l0, l1) = (WIDTH_TABLE.0.ln(), WIDTH_TABLE.1.ln());
    (0..WIDTH_TABLE.2)
        .map(|k| {
            let naive = (l0 + (l1 - l0) * k as f64 / (WIDTH_TABLE.2 - 1) as f64).exp();
            let area = (naive * PI.sqrt()).min(2.0 * PI * 0.99995);
            let (mut lo, mut hi) = (1e-4f64, 20.0f64);
            for _ in 0..80 {
                let mid = (lo * hi).sqrt();
                if integral(mid) < area {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            (lo * hi).sqrt() / naive
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_fiber::math::{GaussLegendre, log_i0};

    /// The polynomial I₀ against the fiber crate's series, on both sides of the switch and
    /// with exponents that would overflow I₀ alone: 1e-6 relative.
    #[test]
    fn polynomial_i0_matches_series() {
        for &x in &[0.0, 0.5, 3.7, 3.8, 12.0, 400.0, 2e6] {
            for &extra in &[0.0, -0.3, -5.0] {
                let s = -x + extra;
                let want = (log_i0(x) + s).exp();
                let got = i0_times_exp(x, s);
                assert!(
                    (got / want - 1.0).abs() < 1e-6,
                    "x {x}, s {s}: {got} vs {want}"
                );
            }
        }
    }

    fn numeric(f: impl Fn(f64) -> f64) -> f64 {
        let rule = GaussLegendre::new(64);
        (0..64)
            .map(|k| {
                let a = -PI + 2.0 * PI * k as f64 / 64.0;
                rule.integrate(a, a + 2.0 * PI / 64.0, &f)
            })
            .sum()
    }

    /// Closed forms against 4096-point quadrature, to 1e-6 relative (the polynomial I₀).
    #[test]
    fn integral_and_product_match_quadrature() {
        for &lambda in &[0.05, 0.3, 1.0, 4.0] {
            let exact = numeric(|x| eval(x, 0.7, lambda));
            assert!(
                (integral(lambda) / exact - 1.0).abs() < 1e-6,
                "λ = {lambda}"
            );
        }
        for &(l1, d, mu, l2) in &[
            (0.2, 0.5, PI, 0.6),
            (1.5, -2.0, 0.3, 0.1),
            (0.05, 3.0, -3.0, 0.07),
        ] {
            let exact = numeric(|x| eval(x, 0.0, l1) * eval(d - x, mu, l2));
            let closed = convolve(l1, d, mu, l2);
            assert!((closed / exact - 1.0).abs() < 1e-6, "{closed} vs {exact}");
        }
    }

    /// The inverse width recovers the area: 0.2 % over areas from 0.01 to 6.
    #[test]
    fn bandwidth_for_integral_inverts_integral() {
        for &area in &[0.01, 0.3, 1.0, 2.5, 4.0, 6.0] {
            let l = bandwidth_for_integral(area);
            assert!(
                (integral(l) / area - 1.0).abs() < 2e-3,
                "{area}: {}",
                integral(l)
            );
        }
    }

    /// The paper's narrow-lobe integral √π λ holds within 1 % below λ = 0.3.
    #[test]
    fn narrow_integral_is_sqrt_pi_lambda() {
        for &lambda in &[0.01, 0.1, 0.3] {
            let ratio = integral(lambda) / (PI.sqrt() * lambda);
            assert!((ratio - 1.0).abs() < 0.01, "λ = {lambda}: {ratio}");
        }
    }
}
