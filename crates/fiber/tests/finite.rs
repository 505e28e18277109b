//! Finite everywhere (issue 2): over the whole domain — θ to ±π/2, β from 0.001 to 1, η from
//! 1.01 to 3, μ_a from 0 to 100, α to ±10° — every value eval, sample and pdf return is finite
//! and non-negative, for d'Eon 2011, the non-separable model and Chiang 2016 (far field and at an
//! offset h; Marschner 2003 has its own).

use cuticle_fiber::models::chiang2016::AtOffset;
use cuticle_fiber::{Chiang2016, DEon2011, FiberAngles, FiberModel, FiberParams, NonSeparable};
use glam::DVec3;
use proptest::prelude::*;
use std::f64::consts::FRAC_PI_2;

fn params() -> impl Strategy<Value = FiberParams> {
    (
        1.01f64..3.0,
        -3.0f64..0.0,
        -10.0f64..10.0,
        (0.0f64..100.0, 0.0f64..100.0, 0.0f64..100.0),
    )
        .prop_map(|(eta, log_beta, alpha_deg, (r, g, b))| FiberParams {
            eta,
            beta: 10f64.powf(log_beta),
            alpha: alpha_deg.to_radians(),
            mu_a: DVec3::new(r, g, b),
        })
}

fn angle() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(-FRAC_PI_2),
        Just(FRAC_PI_2),
        Just(0.0),
        -FRAC_PI_2..FRAC_PI_2
    ]
}

fn check(
    model: &dyn FiberModel,
    wi: FiberAngles,
    wo: FiberAngles,
    u: [f64; 4],
) -> Result<(), TestCaseError> {
    let s = model.eval(wi, wo);
    for v in s.0 {
        prop_assert!(
            v.is_finite() && v.min_element() >= 0.0,
            "{} eval {wi:?} {wo:?}: {v}",
            model.name()
        );
    }
    let pdf = model.pdf(wi, wo);
    prop_assert!(
        pdf.is_finite() && pdf >= 0.0,
        "{} pdf {wi:?} {wo:?}: {pdf}",
        model.name()
    );
    if let Some(sample) = model.sample(wi, u) {
        prop_assert!(
            sample.weight.is_finite() && sample.weight.min_element() >= 0.0,
            "{} weight {sample:?}",
            model.name()
        );
        prop_assert!(
            sample.pdf.is_finite() && sample.pdf > 0.0,
            "{} sample pdf {sample:?}",
            model.name()
        );
        prop_assert!(sample.wo.theta.abs() <= FRAC_PI_2 && sample.wo.phi.is_finite());
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn every_value_is_finite_and_non_negative(
        params in params(),
        theta_i in angle(),
        theta_o in angle(),
        phi in -3.2f64..3.2,
        u in proptest::array::uniform4(0.0f64..1.0),
        beta_n in 0.001f64..1.0,
        h in prop_oneof![Just(-1.0), Just(1.0), -1.0f64..1.0],
    ) {
        let wi = FiberAngles::new(theta_i, 0.0);
        let wo = FiberAngles::new(theta_o, phi);
        check(&DEon2011::new(params).unwrap(), wi, wo, u)?;
        check(&NonSeparable::new(params).unwrap(), wi, wo, u)?;
        let chiang = Chiang2016::new(params, beta_n).unwrap();
        check(&AtOffset { model: &chiang, h }, wi, wo, u)?;
        check(&chiang, wi, wo, u)?;
    }
}
