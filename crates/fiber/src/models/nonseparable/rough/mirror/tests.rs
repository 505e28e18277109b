use super::*;
use crate::models::deon2011::azimuthal::AzimuthalScattering;
use crate::models::nonseparable::cuticle::WithScales;

const ETA: f64 = 1.55;

/// At normal incidence on an untilted scale an in-plane slope ε turns the mirror by 2ε, so
/// the spread is twice the slope's standard deviation, √2 β, about the smooth mirror.
#[test]
fn untilted_spread_at_normal_incidence_is_twice_the_slope() {
    let beta = 0.02;
    let s = azimuth_spread(0.0, 0.0, beta, ETA, 0.0).unwrap();
    assert!(s.mean.abs() < 1e-12, "{s:?}");
    let want = std::f64::consts::SQRT_2 * beta;
    assert!((s.sd / want - 1.0).abs() < 0.03, "{} against {want}", s.sd);
}

/// Mirroring the fiber across its plane of incidence (γ → −γ) mirrors the azimuth.
#[test]
fn spread_is_odd_in_the_offset() {
    for gamma in [0.3, 0.9, 1.4] {
        let a = azimuth_spread(0.7, f64::to_radians(-3.0), 0.04, ETA, gamma).unwrap();
        let b = azimuth_spread(0.7, f64::to_radians(-3.0), 0.04, ETA, -gamma).unwrap();
        assert!(
            (a.mean + b.mean).abs() < 1e-12 && (a.sd - b.sd).abs() < 1e-12,
            "{a:?} {b:?}"
        );
    }
}

/// Where the offset's incidence grazes, the visible micro-normals turn the reflection
/// toward φ = 0 (the mirror of h > 0 leaves at φ < 0, so the mean offset is positive);
/// near the centre they hardly do.
#[test]
fn grazing_offsets_turn_inward() {
    let at = |h: f64| azimuth_spread(1.1, 0.0, 0.08, ETA, h.asin()).unwrap();
    assert!(at(0.98).mean > 0.05, "{:?}", at(0.98));
    assert!(at(0.5).mean.abs() < 0.05, "{:?}", at(0.5));
    assert!(at(0.98).sd > at(0.0).sd, "{:?} {:?}", at(0.98), at(0.0));
}

fn table(alpha_deg: f64, beta: f64) -> (RoughMirror, AzimuthalScattering) {
    let alpha = alpha_deg.to_radians();
    let az = AzimuthalScattering::new(ETA, beta, DVec3::ZERO)
        .with_scale_tilt(alpha)
        .with_rough_surface(beta);
    let selection = |_: f64, h: f64| 1.0 - 0.5 * h * h;
    (RoughMirror::build(alpha, beta, ETA, selection), az)
}

/// The spread moves R in φ and keeps its energy: ∫ N_R dφ = ½ ∫ A(0, h) dh with step 1's
/// albedo, where S's N_R is step 3's columns (a quadrature over micro-normals, not over
/// step 1's slope grid), and the same for the mixture under the selection weights.
#[test]
fn density_keeps_the_energy() {
    for (alpha_deg, beta) in [(-4.0, 0.04), (2.0, 0.08), (0.0, 0.02)] {
        let (table, _) = table(alpha_deg, beta);
        let alpha = f64::to_radians(alpha_deg);
        for i in [20, 80, 100] {
            let theta_i = theta_i_node(i);
            let n = 8192;
            let integrate = |f: &dyn Fn(f64) -> f64, a: f64, b: f64| {
                let step = (b - a) / n as f64;
                (0..n).map(|k| f(a + step * (k as f64 + 0.5))).sum::<f64>() * step
            };
            let albedo = |h: f64| {
                azimuth_spread(theta_i, alpha, beta, ETA, h.asin()).map_or(0.0, |s| s.albedo)
            };
            let selection = |h: f64| 1.0 - 0.5 * h * h;
            for (weighting, weight) in [
                (Weighting::Attenuation, &albedo as &dyn Fn(f64) -> f64),
                (Weighting::Selection, &selection),
            ] {
                let want =
                    0.5 * integrate(&|g: f64| weight(g.sin()) * g.cos(), -FRAC_PI_2, FRAC_PI_2);
                let got = integrate(&|phi| table.density(theta_i, phi, weighting), -PI, PI);
                assert!(
                    (got / want - 1.0).abs() < 3e-3,
                    "α {alpha_deg} β {beta} θ_i {theta_i} {weighting:?}: {got} against {want}"
                );
            }
        }
    }
}

/// Untilted and away from grazing, step 1's albedo is the rough interface's reflectance
/// that A(0, h) takes elsewhere in the model (departure 7): the two integrate Walter et al.
/// 2007's weights over the same micro-normals, one on a flat interface.
#[test]
fn albedo_is_the_rough_reflectance_away_from_grazing() {
    let (_, az) = table(0.0, 0.04);
    for (theta_i, h) in [(0.2, 0.0), (0.5, 0.5), (0.9, -0.3)] {
        let ours = azimuth_spread(theta_i, 0.0, 0.04, ETA, f64::asin(h))
            .unwrap()
            .albedo;
        let theirs = az.reflectance(theta_i, h);
        assert!(
            (ours / theirs - 1.0).abs() < 0.02,
            "θ_i {theta_i} h {h}: {ours} {theirs}"
        );
    }
}

/// The sampler's azimuths, for offsets drawn with the selection weights, follow the
/// density the table reports for them (total variation over 128 bins, 400,000 draws: the
/// histogram's own noise is about 0.01).
#[test]
fn sampled_azimuths_follow_the_density() {
    let (table, _) = table(-4.0, 0.04);
    use rand_core::SeedableRng;
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(7);
    let mut u = move || crate::testing::uniform4(&mut rng)[0];
    for theta_i in [theta_i_node(96), 0.93] {
        let bins = 128;
        let mut histogram = vec![0.0; bins];
        let draws = 400_000;
        let mut kept = 0;
        while kept < draws {
            let h = 2.0 * u() - 1.0;
            if u() > 1.0 - 0.5 * h * h {
                continue;
            }
            let mirror = tilted_mirror(theta_i, table.alpha, h).phi;
            let phi = crate::geometry::frame::wrap_pi(table.sample_phi(theta_i, h, mirror, u()));
            let b = (((phi + PI) / (2.0 * PI)) * bins as f64) as usize;
            histogram[b.min(bins - 1)] += 1.0 / draws as f64;
            kept += 1;
        }
        let width = 2.0 * PI / bins as f64;
        let density: Vec<f64> = (0..bins)
            .map(|b| {
                (0..16)
                    .map(|k| {
                        let phi = -PI + width * (b as f64 + (k as f64 + 0.5) / 16.0);
                        table.density(theta_i, phi, Weighting::Selection)
                    })
                    .sum::<f64>()
                    * width
                    / 16.0
            })
            .collect();
        let total: f64 = density.iter().sum();
        let tv = 0.5
            * histogram
                .iter()
                .zip(&density)
                .map(|(a, b)| (a - b / total).abs())
                .sum::<f64>();
        assert!(tv < 0.02, "θ_i {theta_i}: total variation {tv}");
    }
}
