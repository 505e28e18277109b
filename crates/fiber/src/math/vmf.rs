//! The von Mises–Fisher distribution on the sphere, exp(κ ω·μ) normalised: its mean cosine
//! A(κ) to the centre and the inverse. The fiber models' M is the φ-marginal of one
//! ([`crate::lobes::longitudinal`]); the preview's SRBF lights are others (`cuticle-render`).

/// A(κ) = coth κ − 1/κ: the mean cosine to the centre of the normalised exp(κ(ω·μ − 1))
/// (Banerjee et al. 2005 §2, the ratio I_{3/2}(κ)/I_{1/2}(κ) in three dimensions).
pub fn mean_cosine(kappa: f64) -> f64 {
    if kappa < 1e-4 {
        kappa / 3.0
    } else if kappa > 20.0 {
        1.0 - 1.0 / kappa
    } else {
        1.0 / kappa.tanh() - 1.0 / kappa
    }
}

/// dA/dκ = 1/κ² − 1/sinh²κ.
fn mean_cosine_slope(kappa: f64) -> f64 {
    if kappa < 1e-2 {
        1.0 / 3.0 - kappa * kappa / 15.0
    } else if kappa > 20.0 {
        1.0 / (kappa * kappa)
    } else {
        1.0 / (kappa * kappa) - 1.0 / kappa.sinh().powi(2)
    }
}

/// A⁻¹(r): the concentration whose mean cosine is `r` ∈ [0, 1): Banerjee et al. 2005's
/// estimate κ ≈ r(d − r²)/(1 − r²) (§4.1, here d = 3), refined by Newton steps.
pub fn concentration(r: f64) -> f64 {
    let r = r.clamp(1e-9, 1.0 - 1e-12);
    let mut kappa = r * (3.0 - r * r) / (1.0 - r * r);
    for _ in 0..8 {
        let step = (mean_cosine(kappa) - r) / mean_cosine_slope(kappa);
        kappa = (kappa - step).max(0.5 * kappa);
        if step.abs() < 1e-12 * kappa {
            break;
        }
    }
    kappa
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn concentration_inverts_the_mean_cosine() {
        for kappa in [1e-3, 0.125, 1.0, 8.0, 19.9, 20.1, 800.0, 8e5] {
            let back = concentration(mean_cosine(kappa));
            assert!((back / kappa - 1.0).abs() < 1e-6, "{kappa}: {back}");
        }
    }
}
