//! What `render` writes beside its images: render.json's parts shared by every method, the
//! coverage mask, and the finite-image check before anything is written.

use anyhow::Result;
use cuticle_render::{Image, Method, Scene, Timings};
use glam::DVec3;
use serde_json::{Value, json};

/// Refuses to write an image holding a pixel that is not a finite 32-bit float
/// ([`Image::check_finite`]); `what` names the image in the message.
pub(crate) fn check_finite(image: &Image, what: &str) -> Result<()> {
    Ok(image.check_finite(what)?)
}

/// Whether and how multiple scattering was rendered.
pub fn multiple_json(scene: &Scene) -> Value {
    let terms = match scene.spec.method {
        Method::Srbf => "circular-Gaussian fits against SRBF windows (Xu et al. 2011 eqs. 27-31)",
        Method::Brute => {
            "exact azimuthal functions and Marschner lobes per directional light, integrated numerically"
        }
        Method::Path => "every path, by path tracing",
    };
    json!({
        "enabled": scene.spec.multiple,
        "model": "dual scattering (Zinke et al. 2008; Xu et al. 2011 section 4.3)",
        "terms": terms,
        "d_b": scene.spec.hair.d_b,
        "d_f": cuticle_render::srbf::forward_scattering::DENSITY_FACTOR,
    })
}

/// Seconds per stage as render.json records them.
pub fn seconds_json(t: &Timings) -> Value {
    json!({
        "tables": t.tables,
        "srbf_fit": t.srbf_fit,
        "drawing": t.drawing,
        "shadows": t.shadows,
        "shading": t.shading,
        "resolve": t.resolve,
        "frame": t.drawing + t.shadows + t.shading + t.resolve,
    })
}

/// Each pixel's hair coverage (the fraction of its subsamples a strand covers) in all three
/// channels: the mask `cuticle compare` averages over.
pub fn coverage_image(coverage: &cuticle_render::frame::draw::Coverage) -> Image {
    let (width, height) = (coverage.width, coverage.height);
    Image {
        width,
        height,
        pixels: (0..width * height)
            .map(|k| DVec3::splat(coverage.pixel_fraction(k % width, k / width)))
            .collect(),
    }
}
