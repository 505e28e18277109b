//! The fiber models' parameter ranges (the [`Range`] type is the leaf crate `cuticle-range`'s,
//! re-exported here): the fiber models, the simulator, the renderer's hair and the command line
//! check a fiber parameter against these constants.

pub use cuticle_range::{CountRange, End, Range, RangeError, short};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, SQRT_2};

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
