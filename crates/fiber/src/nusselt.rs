//! Ray directions in Nusselt coordinates (d'Eon et al. 2014 §2.2): a direction relative to a surface
//! normal is kept as its components (x along the fiber axis, y across it); z = √(1 − x² − y²)
//! is implied. Tilting the normal by α is the rotation Q; reflection, refraction and the
//! propagation to the next interface are simple maps of (x, y). Square-root inputs are clamped
//! to be non-negative (d'Eon et al. 2014 §2.4), so a path that would be totally internally reflected
//! yields |x| > 1 rather than a NaN.
//!
//! Sign: with the rotations exactly as printed, R's cone comes out as −asin(x cos 2α + z sin 2α)
//! while d'Eon et al. 2014 §2.3 prints −asin(x cos 2α − z sin 2α) (expanded). The two differ only in
//! the sign of α; this module takes α in the sign of §2.3's closed form (a scale tilted so that
//! α > 0 raises the R cone, as in Marschner et al. 2003's α_R = 2α convention with α < 0 for
//! human hair tilting R toward the root), and tests that both agree.

/// A direction (x, y) in Nusselt coordinates.
pub type Nusselt = (f64, f64);

/// Q(α, x, y) = (x cos α − z sin α, y).
fn rotate(alpha: f64, (x, y): Nusselt) -> Nusselt {
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    let (s, c) = alpha.sin_cos();
    (x * c - z * s, y)
}

fn neg((x, y): Nusselt) -> Nusselt {
    (-x, -y)
}

fn scale((x, y): Nusselt, k: f64) -> Nusselt {
    (x * k, y * k)
}

/// R[α]: reflection from outside off a scale tilted by α (here α of §2.3's sign: see above).
pub fn reflect_outside(alpha: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(a, neg(rotate(-a, d)))
}

/// R′[α]: reflection from inside.
pub fn reflect_inside(alpha: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(-a, neg(rotate(a, d)))
}

/// T[α]: refraction into the fiber, a dilation by 1/η in the micro-normal's frame.
pub fn refract_in(alpha: f64, eta: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(-a, scale(neg(rotate(-a, d)), 1.0 / eta))
}

/// T′[α]: refraction out of the fiber.
pub fn refract_out(alpha: f64, eta: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(a, scale(neg(rotate(a, d)), eta))
}

/// P: from a transmitted direction to the incident direction at the next interface.
pub fn propagate(d: Nusselt) -> Nusselt {
    neg(d)
}

/// x of the R exit direction for scale tilts α₁ (F_R of §2.2).
pub fn exit_r(alpha: f64, incident: Nusselt) -> f64 {
    reflect_outside(alpha, incident).0
}

/// x of the TT exit direction for tilts α₁, α₂ (F_TT of §2.2).
pub fn exit_tt(alphas: [f64; 2], eta: f64, incident: Nusselt) -> f64 {
    let inside = propagate(refract_in(alphas[0], eta, incident));
    refract_out(alphas[1], eta, inside).0
}

/// x of the TRT exit direction for tilts α₁, α₂, α₃ (F_TRT of §2.2).
pub fn exit_trt(alphas: [f64; 3], eta: f64, incident: Nusselt) -> f64 {
    let inside = propagate(refract_in(alphas[0], eta, incident));
    let reflected = propagate(reflect_inside(alphas[1], inside));
    refract_out(alphas[2], eta, reflected).0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn untilted_paths_leave_on_the_specular_cone() {
        let d = (0.4, 0.3);
        assert!((exit_r(0.0, d) + 0.4).abs() < 1e-15);
        assert!((exit_tt([0.0; 2], 1.55, d) + 0.4).abs() < 1e-15);
        assert!((exit_trt([0.0; 3], 1.55, d) + 0.4).abs() < 1e-15);
    }

    #[test]
    fn first_order_derivatives_match_section_2_2() {
        // dx_R/dα₁ = −2z, dx_TT/dα_k = ηz′ − z, dx_TRT/dα = [ηz′ − z, 2ηz′, ηz′ − z], in the
        // rotation's own sign (α here is §2.3's, i.e. the negative: flip the expected signs).
        let (eta, x, y): (f64, f64, f64) = (1.55, 0.35, 0.5);
        let z = (1.0 - x * x - y * y).sqrt();
        let zp = (1.0 - (x * x + y * y) / (eta * eta)).sqrt();
        let e = 1e-6;
        let d = |f: &dyn Fn(f64) -> f64| (f(e) - f(-e)) / (2.0 * e);
        assert!((d(&|a| exit_r(a, (x, y))) - 2.0 * z).abs() < 1e-8);
        let tt0 = d(&|a| exit_tt([a, 0.0], eta, (x, y)));
        let tt1 = d(&|a| exit_tt([0.0, a], eta, (x, y)));
        assert!((tt0 + (eta * zp - z)).abs() < 1e-7 && (tt1 + (eta * zp - z)).abs() < 1e-7);
        let trt1 = d(&|a| exit_trt([0.0, a, 0.0], eta, (x, y)));
        assert!((trt1 + 2.0 * eta * zp).abs() < 1e-7, "{trt1}");
    }
}
