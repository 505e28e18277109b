//! Colour helpers shared by the fit and the previews.

use glam::{DVec3, Vec3};

/// Relative luminance of linear Rec. 709 RGB.
pub fn luminance(rgb: Vec3) -> f32 {
    0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z
}

/// [`luminance`] in double precision.
pub fn luminance_f64(rgb: DVec3) -> f64 {
    0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z
}
