//! Tone mapping for previews: a global exposure from the map's log-average luminance (Reinhard et
//! al. 2002's "key"), per-channel x/(1+x), then the sRGB transfer curve.

use crate::color::luminance;
use crate::{EnvMap, SrbfLight, evaluate_lights};
use glam::Vec3;
use image::{Rgb, RgbImage};
use rayon::prelude::*;

/// A global tone-mapping operator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToneMap {
    /// Linear scale applied before the curve.
    pub exposure: f32,
}

/// Where the log-average luminance lands before the curve.
const KEY: f64 = 0.25;

impl ToneMap {
    /// Exposure that maps the solid-angle-weighted log-average luminance of `map` to 0.25.
    pub fn for_map(map: &EnvMap) -> Self {
        let (log_sum, weight) = map.iter().fold((0.0, 0.0), |(s, w), p| {
            let l = luminance(p.radiance) as f64;
            (s + p.solid_angle * (l + 1e-4).ln(), w + p.solid_angle)
        });
        let log_average = (log_sum / weight).exp();
        Self {
            exposure: (KEY / log_average) as f32,
        }
    }

    /// Linear radiance → 8-bit sRGB.
    pub fn apply(&self, radiance: Vec3) -> [u8; 3] {
        let v = radiance * self.exposure;
        let curve = |x: f32| {
            let y = x.max(0.0) / (1.0 + x.max(0.0));
            (srgb_encode(y) * 255.0 + 0.5) as u8
        };
        [curve(v.x), curve(v.y), curve(v.z)]
    }
}

/// The sRGB opto-electronic transfer function (IEC 61966-2-1).
fn srgb_encode(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// Gap between the two panels of [`comparison_image`], in pixels.
const GAP: u32 = 4;

/// The map (left) and its SRBF reconstruction (right) side by side, each `panel_width` wide,
/// tone-mapped with one exposure taken from the map.
pub fn comparison_image(map: &EnvMap, lights: &[SrbfLight], panel_width: usize) -> RgbImage {
    let panel = panel_of(map, panel_width);
    let tone = ToneMap::for_map(&panel);
    let (w, h) = (panel.width() as u32, panel.height() as u32);
    let reconstruction: Vec<Vec3> = (0..panel.width() * panel.height())
        .into_par_iter()
        .map(|i| {
            let d = panel.direction(i % panel.width(), i / panel.width());
            evaluate_lights(lights, d).as_vec3()
        })
        .collect();
    let mut image = RgbImage::from_pixel(2 * w + GAP, h, Rgb([20, 20, 20]));
    for (i, (orig, fit)) in panel.pixels().iter().zip(&reconstruction).enumerate() {
        let (x, y) = ((i % panel.width()) as u32, (i / panel.width()) as u32);
        image.put_pixel(x, y, Rgb(tone.apply(*orig)));
        image.put_pixel(w + GAP + x, y, Rgb(tone.apply(*fit)));
    }
    image
}

/// `map` at `width × width·H/W`: area-averaged when smaller, bilinear when larger.
fn panel_of(map: &EnvMap, width: usize) -> EnvMap {
    let height = (width * map.height() / map.width()).max(1);
    if width <= map.width() && height <= map.height() {
        return map.downsample(width, height);
    }
    let rotation = map.rotation();
    let unrotated = map.clone().with_rotation(0.0);
    EnvMap::from_fn(width, height, |d| unrotated.radiance(d.as_vec3())).with_rotation(rotation)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exposure_puts_the_log_average_at_the_key() {
        let map = EnvMap::new(16, 8, vec![Vec3::splat(4.0); 128]);
        let tone = ToneMap::for_map(&map);
        assert!((tone.exposure * 4.0 - KEY as f32).abs() < 1e-3);
        let dark = tone.apply(Vec3::ZERO);
        let bright = tone.apply(Vec3::splat(1e6));
        assert_eq!(dark, [0, 0, 0]);
        assert_eq!(bright, [255, 255, 255]);
    }

    #[test]
    fn comparison_has_two_panels_and_a_gap() {
        let map = EnvMap::new(32, 16, vec![Vec3::new(1.0, 0.5, 0.25); 512]);
        let light = SrbfLight::new(Vec3::Y, 0.5, Vec3::ONE);
        let image = comparison_image(&map, &[light], 16);
        assert_eq!(image.dimensions(), (2 * 16 + GAP, 8));
        assert_eq!(image.get_pixel(16, 3), &Rgb([20, 20, 20]));
        assert_ne!(image.get_pixel(3, 0), image.get_pixel(16 + GAP + 3, 0));
    }
}
