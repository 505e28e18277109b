//! The quick frame shown first after each edit ([`crate::worker::Quality::Preview`]). Shading
//! costs per visible point × light × quadrature segment, so a preview cuts all three:
//! - fewer pixels and one subsample each (fewer visible points), the reduction along each axis
//!   chosen from the last preview's shading time ([`next_scale`]);
//! - the [`PREVIEW_LIGHTS`] SRBF lights of most energy, scaled so that the lights' total energy
//!   ∫ Σ_j L_j G_j dω of each channel is kept ([`strongest_lights`]);
//! - at most [`PREVIEW_QUADRATURE`] segments of the linear quadrature (Xu et al. 2011 §4.2.2).
//!
//! The full-quality frame that follows uses the scene as it is.

use cuticle_light::SrbfLight;
use cuticle_render::Scene;
use glam::DVec3;

/// Shading seconds a preview aims at (the first updated frame after an edit).
pub const PREVIEW_BUDGET_S: f64 = 0.05;
/// Largest reduction of the preview along each axis.
pub const MAX_PREVIEW_SCALE: usize = 8;
/// SRBF lights a preview shades with.
pub const PREVIEW_LIGHTS: usize = 8;
/// Largest number of quadrature segments a preview integrates with.
pub const PREVIEW_QUADRATURE: usize = 2;

/// The scene at preview quality: `scale` times fewer pixels along each axis, one subsample,
/// the strongest lights and a coarser quadrature.
pub fn preview_scene(scene: &Scene, scale: usize) -> Scene {
    let mut s = scene.clone();
    s.spec.width = scene.spec.width.div_ceil(scale).max(1);
    s.spec.height = scene.spec.height.div_ceil(scale).max(1);
    s.spec.supersampling = 1;
    s.spec.quadrature = scene.spec.quadrature.min(PREVIEW_QUADRATURE);
    s.lights = strongest_lights(&scene.lights, PREVIEW_LIGHTS);
    s
}

/// The `count` lights of most energy (∫ L_j G_j dω, summed over channels), in their original
/// order, each channel scaled by the energy of all lights over that of those kept (a channel no
/// kept light carries stays as it is).
pub fn strongest_lights(lights: &[SrbfLight], count: usize) -> Vec<SrbfLight> {
    if lights.len() <= count {
        return lights.to_vec();
    }
    let energy = |l: &SrbfLight| l.integral().element_sum();
    let mut order: Vec<usize> = (0..lights.len()).collect();
    order.sort_by(|&a, &b| energy(&lights[b]).total_cmp(&energy(&lights[a])));
    let mut kept = order[..count].to_vec();
    kept.sort_unstable();
    let total: DVec3 = lights.iter().map(SrbfLight::integral).sum();
    let carried: DVec3 = kept.iter().map(|&j| lights[j].integral()).sum();
    let gain = DVec3::select(carried.cmpgt(DVec3::ZERO), total / carried, DVec3::ONE);
    kept.iter()
        .map(|&j| SrbfLight {
            coefficient: (lights[j].coefficient.as_dvec3() * gain).as_vec3(),
            ..lights[j]
        })
        .collect()
}

/// The preview reduction after a preview at `scale` that shaded in `shade_s`: unchanged while
/// the time is within a factor 2 of [`PREVIEW_BUDGET_S`], else the one whose pixel count (to
/// which shading is about proportional) meets the budget, within 1..=[`MAX_PREVIEW_SCALE`].
pub fn next_scale(scale: usize, shade_s: f64) -> usize {
    let ratio = shade_s / PREVIEW_BUDGET_S;
    if !(0.5..=2.0).contains(&ratio) {
        let ideal = scale as f64 * ratio.sqrt();
        return (ideal.round() as usize).clamp(1, MAX_PREVIEW_SCALE);
    }
    scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn light(x: f32, coefficient: [f32; 3]) -> SrbfLight {
        SrbfLight::new(
            Vec3::new(x, 1.0, 0.0).normalize(),
            0.5,
            Vec3::from_array(coefficient),
        )
    }

    /// The strongest lights are kept in order, and each channel's total energy is the same.
    #[test]
    fn strongest_lights_keep_the_energy_of_each_channel() {
        let lights = [
            light(0.0, [1.0, 1.0, 1.0]),
            light(0.5, [0.1, 0.0, 0.2]),
            light(-0.5, [5.0, 4.0, 3.0]),
            light(0.9, [0.2, 0.3, 0.0]),
        ];
        let kept = strongest_lights(&lights, 2);
        assert_eq!(kept.len(), 2);
        assert_eq!(kept[0].direction, lights[0].direction);
        assert_eq!(kept[1].direction, lights[2].direction);
        let total: DVec3 = lights.iter().map(SrbfLight::integral).sum();
        let after: DVec3 = kept.iter().map(SrbfLight::integral).sum();
        assert!((after - total).abs().max_element() < 1e-5 * total.max_element());
        assert_eq!(strongest_lights(&lights, 4), lights.to_vec());
    }

    /// A slow preview shrinks in one step to the budget's size; one near budget stays.
    #[test]
    fn next_scale_meets_the_budget_in_one_step() {
        assert_eq!(next_scale(2, 16.0 * PREVIEW_BUDGET_S), 8);
        assert_eq!(next_scale(2, 4.0 * PREVIEW_BUDGET_S), 4);
        assert_eq!(next_scale(4, 1.5 * PREVIEW_BUDGET_S), 4);
        assert_eq!(next_scale(4, 0.25 * PREVIEW_BUDGET_S), 2);
        assert_eq!(next_scale(8, 100.0), MAX_PREVIEW_SCALE);
        assert_eq!(next_scale(1, 0.0), 1);
    }
}
