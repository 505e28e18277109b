//! A frame's lights merged into a few, for the preview: shading costs per light, and the full
//! frame's lights are the fitted narrow ones plus the sub-lights the wide ones are split into
//! ([`crate::frame::sub_lights`]), several dozen in all.
//!
//! Merging is agglomerative, as Ward 1963's grouping (each step merges the pair that costs the
//! objective least), the objective the L2 distance of radiance: starting from one group per
//! light, the two groups whose merge changes the radiance Σ L_j G_j over the sphere least,
//! ‖M_a + M_b − M_ab‖² (M the groups' merged lights), are merged until `count` remain (the
//! squared norms are closed forms, ∫ (L_a G_a)(L_b G_b) dω, [`SrbfLight::inner_product`]). A
//! bright narrow light (the sun) thus stays itself, and the dim sub-lights of a sky merge into
//! a few broad lobes.
//!
//! A group becomes one SRBF light by moment matching, the reduction of von Mises–Fisher
//! mixtures (Banerjee et al. 2005 §2, §4): G(ω; ω_j, λ_j) normalised is a vMF density of
//! concentration κ_j = 2/λ_j² (Xu et al. 2011 eq. 1), whose mean vector is A(κ_j) ω_j with
//! A(κ) = coth κ − 1/κ; the group's mean vector m = Σ_j E_j A(κ_j) ω_j / Σ_j E_j (E_j the
//! light's energy ∫ L_j G_j dω, summed over channels) gives its centre m/‖m‖ and concentration
//! A⁻¹(‖m‖), and its coefficient is the group's energy per channel over its basis integral, so
//! that every channel's energy is exactly that of the lights it replaces.

use cuticle_fiber::math::vmf::{concentration, mean_cosine};
use cuticle_light::{MAX_BANDWIDTH, MIN_BANDWIDTH, SrbfLight};
use glam::{DVec3, Vec3};

/// What a group of lights adds up to: the moments its merged light matches.
#[derive(Clone, Copy, Debug)]
struct Group {
    /// ∫ L G dω per channel.
    channels: DVec3,
    /// Σ_j E_j A(κ_j) ω_j.
    moment: DVec3,
    /// The one light of these moments.
    light: SrbfLight,
}

impl Group {
    fn of(light: &SrbfLight) -> Self {
        let channels = light.integral();
        Self {
            channels,
            moment: channels.element_sum() * mean_cosine(light.sharpness()) * light.centre(),
            light: *light,
        }
    }

    fn with(&self, other: &Group) -> Self {
        let channels = self.channels + other.channels;
        let moment = self.moment + other.moment;
        Self {
            channels,
            moment,
            light: matched(channels, moment, self.light.centre()),
        }
    }
}

/// The light of energy `channels` and mean vector `moment` / energy (`fallback` its centre if
/// that vanishes).
fn matched(channels: DVec3, moment: DVec3, fallback: DVec3) -> SrbfLight {
    let energy = channels.element_sum();
    let r = moment.length() / energy;
    let direction = if moment.length_squared() > 0.0 {
        moment.normalize()
    } else {
        fallback
    };
    let bandwidth = (2.0 / concentration(r))
        .sqrt()
        .clamp(MIN_BANDWIDTH, MAX_BANDWIDTH);
    let basis = SrbfLight::new(direction.as_vec3(), bandwidth as f32, Vec3::ONE);
    SrbfLight {
        coefficient: (channels / basis.basis_integral()).as_vec3(),
        ..basis
    }
}

/// ‖a + b − merged‖² over the sphere, channels summed.
fn merge_cost(a: &Group, b: &Group) -> f64 {
    let m = a.with(b).light;
    let (a, b) = (a.light, b.light);
    (a.inner_product(&a) + b.inner_product(&b) + m.inner_product(&m) + 2.0 * a.inner_product(&b)
        - 2.0 * a.inner_product(&m)
        - 2.0 * b.inner_product(&m))
    .element_sum()
    .max(0.0)
}

/// `lights` merged into at most `count` lights carrying, channel by channel, the same energy;
/// returned unchanged when there are no more than `count`. Lights that carry no light are
/// dropped.
pub fn merge_lights(lights: &[SrbfLight], count: usize) -> Vec<SrbfLight> {
    let lit: Vec<SrbfLight> = lights
        .iter()
        .filter(|l| l.integral().element_sum() > 0.0)
        .copied()
        .collect();
    if count == 0 {
        return Vec::new();
    }
    if lit.len() <= count {
        return lit;
    }
    let mut groups: Vec<Option<Group>> = lit.iter().map(|l| Some(Group::of(l))).collect();
    let n = groups.len();
    let mut cost = vec![f64::INFINITY; n * n];
    for i in 0..n {
        for j in i + 1..n {
            if let (Some(a), Some(b)) = (&groups[i], &groups[j]) {
                cost[i * n + j] = merge_cost(a, b);
            }
        }
    }
    for _ in count..n {
        let (mut best, mut at) = (f64::INFINITY, (0, 1));
        for i in 0..n {
            for j in i + 1..n {
                if cost[i * n + j] < best {
                    (best, at) = (cost[i * n + j], (i, j));
                }
            }
        }
        let (i, j) = at;
        let (Some(a), Some(b)) = (groups[i], groups[j].take()) else {
            break;
        };
        groups[i] = Some(a.with(&b));
        for k in 0..n {
            cost[k.min(j) * n + k.max(j)] = f64::INFINITY;
        }
        for k in (0..n).filter(|&k| k != i) {
            cost[k.min(i) * n + k.max(i)] = match (&groups[i], &groups[k]) {
                (Some(a), Some(b)) => merge_cost(a, b),
                _ => f64::INFINITY,
            };
        }
    }
    groups.into_iter().flatten().map(|g| g.light).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::sub_lights::{fibonacci_sphere, split_wide};
    use crate::preview::PREVIEW_SPLIT_BANDWIDTH;
    use cuticle_light::evaluate_lights;
    use glam::Vec3;

    /// A fitted sky's kind of lights: a narrow bright sun, a wide ground, a wide sky dome and
    /// medium lights.
    fn fitted() -> Vec<SrbfLight> {
        vec![
            SrbfLight::new(
                Vec3::new(0.4, 0.8, 0.3),
                0.05,
                Vec3::new(900.0, 800.0, 600.0),
            ),
            SrbfLight::new(Vec3::new(0.05, -1.0, 0.1), 2.6, Vec3::new(0.3, 0.25, 0.2)),
            SrbfLight::new(Vec3::new(-0.1, 1.0, 0.0), 1.3, Vec3::new(0.6, 0.8, 1.2)),
            SrbfLight::new(Vec3::new(1.0, 0.2, -0.3), 0.4, Vec3::new(0.5, 0.5, 0.4)),
            SrbfLight::new(Vec3::new(-0.8, 0.3, 0.5), 0.6, Vec3::new(0.4, 0.5, 0.7)),
            SrbfLight::new(Vec3::new(0.2, 0.1, -1.0), 0.9, Vec3::new(0.3, 0.3, 0.35)),
            SrbfLight::new(Vec3::new(-0.5, -0.4, -0.6), 0.5, Vec3::new(0.2, 0.15, 0.1)),
            SrbfLight::new(Vec3::new(0.7, -0.2, 0.6), 0.3, Vec3::new(0.3, 0.3, 0.2)),
            SrbfLight::new(Vec3::new(-0.2, 0.6, -0.7), 0.2, Vec3::new(0.8, 0.9, 1.0)),
            SrbfLight::new(Vec3::new(0.9, 0.6, 0.1), 0.8, Vec3::new(0.2, 0.3, 0.4)),
        ]
    }

    /// The lights a preview merges: [`fitted`] with the wide ones split.
    fn frame_lights() -> Vec<SrbfLight> {
        split_wide(&fitted(), PREVIEW_SPLIT_BANDWIDTH)
    }

    /// Relative L2 error over the sphere of `model`'s radiance against `truth`'s, channels
    /// pooled (equal-area directions).
    fn radiance_error(truth: &[SrbfLight], model: &[SrbfLight]) -> f64 {
        let (mut err, mut norm) = (0.0, 0.0);
        for d in fibonacci_sphere(20_000) {
            let t = evaluate_lights(truth, d);
            err += (t - evaluate_lights(model, d)).length_squared();
            norm += t.length_squared();
        }
        (err / norm).sqrt()
    }

    /// The preview's lights before merging: the `count` fitted lights of most energy, scaled to
    /// keep each channel's energy (then split as the frame splits them).
    fn strongest(lights: &[SrbfLight], count: usize) -> Vec<SrbfLight> {
        let energy = |l: &SrbfLight| l.integral().element_sum();
        let mut order = lights.to_vec();
        order.sort_by(|a, b| energy(b).total_cmp(&energy(a)));
        order.truncate(count);
        let total: DVec3 = lights.iter().map(SrbfLight::integral).sum();
        let kept: DVec3 = order.iter().map(SrbfLight::integral).sum();
        let gain = total / kept;
        order
            .iter()
            .map(|l| SrbfLight {
                coefficient: (l.coefficient.as_dvec3() * gain).as_vec3(),
                ..*l
            })
            .collect()
    }

    #[test]
    fn merged_lights_keep_each_channels_energy() {
        let lights = frame_lights();
        assert!(lights.len() > 20, "{} lights", lights.len());
        for count in [1, 4, 8] {
            let merged = merge_lights(&lights, count);
            assert_eq!(merged.len(), count);
            let want: DVec3 = lights.iter().map(SrbfLight::integral).sum();
            let got: DVec3 = merged.iter().map(SrbfLight::integral).sum();
            assert!(
                ((got - want) / want).abs().max_element() < 1e-5,
                "{count}: {got} vs {want}"
            );
            assert!(merged.iter().all(|l| l.fault().is_none()), "{merged:?}");
        }
    }

    /// Eight merged lights describe the frame's light better than the eight strongest fitted
    /// lights (energy kept, split), and within a stated bound of the full set.
    #[test]
    fn merged_lights_are_closer_to_the_frame_than_the_strongest() {
        let lights = frame_lights();
        assert!(fitted().len() > 8);
        let merged = radiance_error(&lights, &merge_lights(&lights, 8));
        let old = split_wide(&strongest(&fitted(), 8), PREVIEW_SPLIT_BANDWIDTH);
        let strongest = radiance_error(&lights, &old);
        eprintln!("radiance error: merged {merged:.3}, strongest {strongest:.3}");
        assert!(merged < strongest, "merged {merged} strongest {strongest}");
        assert!(merged < 0.2, "merged {merged}");
    }

    /// A narrow light far from the others stays itself: its own cluster, its centre and width.
    #[test]
    fn a_lone_narrow_light_is_kept() {
        let lights = frame_lights();
        let sun = lights[0];
        let merged = merge_lights(&lights, 8);
        let closest = merged
            .iter()
            .max_by(|a, b| {
                a.centre()
                    .dot(sun.centre())
                    .total_cmp(&b.centre().dot(sun.centre()))
            })
            .unwrap();
        assert!(closest.centre().dot(sun.centre()) > 0.999, "{closest:?}");
        assert!(
            (closest.bandwidth - sun.bandwidth).abs() < 0.02,
            "{closest:?}"
        );
    }

    /// Merging one light into one gives it back; fewer lights than asked pass unchanged.
    #[test]
    fn one_light_merges_into_itself() {
        let l = SrbfLight::new(Vec3::new(0.3, 0.5, -0.2), 0.7, Vec3::new(1.0, 2.0, 3.0));
        let twice = merge_lights(
            &[
                l,
                SrbfLight {
                    coefficient: Vec3::ZERO,
                    ..l
                },
                l,
            ],
            1,
        );
        assert_eq!(twice.len(), 1);
        assert!(twice[0].centre().dot(l.centre()) > 1.0 - 1e-6);
        assert!((twice[0].bandwidth - l.bandwidth).abs() < 1e-4);
        assert!(
            (twice[0].coefficient - 2.0 * l.coefficient)
                .abs()
                .max_element()
                < 1e-4
        );
        assert_eq!(merge_lights(&[l], 8), vec![l]);
    }
}
