//! Absorption from melanin concentrations, and from a colour an artist picks.

use glam::DVec3;

/// Absorption of eumelanin per unit concentration and unit radius, RGB (d'Eon et al. 2011;
/// the values pbrt-v4's hair material also uses).
pub const EUMELANIN_SIGMA_A: DVec3 = DVec3::new(0.419, 0.697, 1.37);
/// Absorption of pheomelanin per unit concentration and unit radius, RGB (same source).
pub const PHEOMELANIN_SIGMA_A: DVec3 = DVec3::new(0.187, 0.4, 1.05);

/// μ_a from eumelanin and pheomelanin concentrations (≥ 0; about 0–8 spans black to blonde).
pub fn mu_a_from_melanin(eumelanin: f64, pheomelanin: f64) -> DVec3 {
    eumelanin.max(0.0) * EUMELANIN_SIGMA_A + pheomelanin.max(0.0) * PHEOMELANIN_SIGMA_A
}

/// Azimuthal roughness β_n at which a colour is inverted into μ_a ([`mu_a_from_color`]) where
/// no model is at hand: the window's colour editor and USD grooms' `displayColor` (Chiang et
/// al. 2016 eq. 9 is stated for their model; Marschner's caustic width plays the part there).
pub const COLOUR_BETA_N: f64 = 0.3;

/// μ_a that gives a fiber of azimuthal roughness `beta_n` the multiply scattered colour `color`
/// (each channel in (0, 1]): Chiang et al. 2016, eq. 9, μ_a = (ln c / P(β_n))² with their
/// fifth-order polynomial P.
pub fn mu_a_from_color(color: DVec3, beta_n: f64) -> DVec3 {
    let b = beta_n.clamp(0.0, 1.0);
    let poly = 5.969 - 0.215 * b + 2.532 * b.powi(2) - 10.73 * b.powi(3)
        + 5.574 * b.powi(4)
        + 0.245 * b.powi(5);
    let channel = |c: f64| (c.clamp(1e-6, 1.0).ln() / poly).powi(2);
    DVec3::new(channel(color.x), channel(color.y), channel(color.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn melanin_is_linear_and_reddens_with_pheomelanin() {
        let a = mu_a_from_melanin(1.0, 0.0);
        assert_eq!(a, EUMELANIN_SIGMA_A);
        assert_eq!(
            mu_a_from_melanin(2.0, 3.0),
            2.0 * EUMELANIN_SIGMA_A + 3.0 * PHEOMELANIN_SIGMA_A
        );
        let ph = mu_a_from_melanin(0.0, 1.0);
        assert!(ph.x < ph.z && ph.x / ph.z < a.x / a.z);
    }

    #[test]
    fn white_costs_nothing_and_darker_colours_absorb_more() {
        assert_eq!(mu_a_from_color(DVec3::ONE, 0.3), DVec3::ZERO);
        let m = mu_a_from_color(DVec3::new(0.8, 0.5, 0.2), 0.3);
        assert!(m.x < m.y && m.y < m.z);
    }
}
