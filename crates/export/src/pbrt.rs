//! The scene for pbrt-v4: `scene.pbrt` and the environment's equal-area image `env.exr`
//! (`cd DIR && pbrt scene.pbrt` writes `image.exr`: pbrt resolves the light's image beside the
//! scene file but writes the film's into the working folder).
//!
//! # The mapping (pbrt-v4's source: `src/pbrt/{cameras,shapes,materials,lights,samplers}.cpp`,
//! `src/pbrt/bxdfs.h`; its file-format documentation, pbrt.org/fileformat-v4)
//! - Camera: `Scale -1 1 1` then `LookAt eye target up`: pbrt's `LookAt` builds a left-handed
//!   camera frame (x = up × view), so without the mirror the picture would be flipped left to
//!   right against cuticle's (x = view × up). `Camera "perspective"` takes `"fov"` for the
//!   shorter image axis (the screen window is ±1 along it, `PerspectiveCamera::Create`):
//!   cuticle's vertical field of view when width ≥ height, else 2 atan(tan(fov/2) · W/H).
//! - Film `"rgb"` of the scene's size, a box filter of radius ½ pixel (cuticle averages
//!   uniform samples over each pixel), `Sampler "independent"` with the spp and seed, and
//!   `Integrator "path"` with `maxdepth` = cuticle's `--max-depth` (pbrt's `maxdepth` 1 is one
//!   scattering event: direct light at the first hit).
//! - Environment: `LightSource "infinite"` with `env.exr`, no transform (light space = world,
//!   z up) and scale 1; the image and its orientation are [`crate::env`]'s.
//! - Strands: one `Shape "curve"` per strand, `"string type" "cylinder"` (a ribbon facing the
//!   ray, shaded as a round fiber: pbrt's `HairMaterial` reads the offset h = −1 + 2v across
//!   it), cubic Bézier (the default basis, degree 3), each polyline segment p → q written as
//!   the control points p, p + (q − p)/3, p + 2(q − p)/3, q, so the curve is exactly the
//!   polyline. pbrt's `"width"` is a diameter, as the groom's thickness is, but one shape
//!   interpolates its width linearly in segment index from `width0` to `width1`
//!   (`CreateCurves`): a strand is split into as few shapes as make every point's diameter exact
//!   (one for a strand of constant or linearly tapering width).
//! - Hair: `Material "hair"` (Chiang et al. 2016 as `HairBxDF`) with `beta_m`, `beta_n`,
//!   `alpha` (degrees, the same sign as cuticle's: pbrt shifts the R lobe's cone by −2α of the
//!   given direction's inclination, `HairBxDF::f`, as cuticle's M_R sits at −θ_i + 2α), `eta`
//!   (the medium outside is 1) and `"rgb sigma_a"`: pbrt's σ_a is per unit radius (its
//!   transmittance is exp(−σ_a · 2 cos γ_t / cos θ_t), the chord of a unit-radius fiber), as
//!   cuticle's μ_a is, so the numbers are written as they are; melanin is written as the σ_a
//!   cuticle derives from it. pbrt renders spectrally and turns the RGB σ_a into a smooth
//!   spectrum (`RGBUnboundedSpectrum`), so exp(−σ_a ℓ) per channel is matched only
//!   approximately. Per-strand absorption is supported: each distinct σ_a is its own
//!   `Material` inside its own `AttributeBegin`/`AttributeEnd` block.

use crate::strands::{Grouped, Polyline, grouped};
use crate::{
    ChiangHair, Export, ExportError, ExportFile, Format, HairLook, RenderSettings, Summary, env,
    num, triple,
};
use cuticle_render::{Camera, Scene};
use glam::{DVec3, Vec3};
use std::fmt::Write;

/// The scene file's name.
pub const SCENE_FILE: &str = "scene.pbrt";
/// The environment image's name.
pub const ENV_FILE: &str = "env.exr";
/// The image pbrt writes.
pub const IMAGE_FILE: &str = "image.exr";

/// A diameter this close (relative to the strand's largest) to the linear interpolation is
/// exact for one shape.
const WIDTH_TOLERANCE: f32 = 1e-5;

/// `scene.pbrt` and `env.exr` for `scene` (module documentation).
pub fn export(
    scene: &Scene,
    look: &HairLook,
    settings: &RenderSettings,
) -> Result<Export, ExportError> {
    let strands = grouped(&scene.groom, &look.sigma_a)?;
    let image = env::pbrt_image(&scene.env);
    let mut text = String::new();
    header(&mut text, scene, settings, &strands);
    world(&mut text, &look.fiber, &strands);
    Ok(Export {
        summary: Summary::of(
            Format::Pbrt,
            [SCENE_FILE, IMAGE_FILE, ENV_FILE],
            &strands,
            (image.width, image.height),
        ),
        files: vec![
            ExportFile {
                name: SCENE_FILE.into(),
                bytes: text.into_bytes(),
            },
            ExportFile {
                name: ENV_FILE.into(),
                bytes: image.exr_bytes()?,
            },
        ],
    })
}

/// pbrt's `"fov"`: the field of view of the shorter image axis, degrees.
pub fn pbrt_fov_deg(camera: &Camera, width: usize, height: usize) -> f64 {
    if width >= height {
        camera.fov_deg
    } else {
        let half = (0.5 * camera.fov_deg.to_radians()).tan() * width as f64 / height as f64;
        2.0 * half.atan().to_degrees()
    }
}

/// Camera, film, sampler and integrator: everything before `WorldBegin`.
fn header(out: &mut String, scene: &Scene, settings: &RenderSettings, strands: &Grouped) {
    let (w, h) = (scene.spec.width, scene.spec.height);
    let c = &scene.camera;
    let v = |a: [f64; 3]| triple(DVec3::from_array(a), " ");
    let _ = writeln!(
        out,
        "# cuticle export for pbrt-v4: {} strands, Chiang et al. 2016 hair, environment {} \
         (mapping: crate cuticle-export, module pbrt)",
        strands.strand_count(),
        scene.spec.env
    );
    let _ = writeln!(out, "Scale -1 1 1");
    let _ = writeln!(out, "LookAt {}  {}  {}", v(c.eye), v(c.target), v(c.up));
    let _ = writeln!(
        out,
        "Camera \"perspective\" \"float fov\" [ {} ]",
        num(pbrt_fov_deg(c, w, h))
    );
    let _ = writeln!(
        out,
        "Film \"rgb\" \"string filename\" [ \"{IMAGE_FILE}\" ] \"integer xresolution\" [ {w} ] \
         \"integer yresolution\" [ {h} ]"
    );
    let _ = writeln!(
        out,
        "PixelFilter \"box\" \"float xradius\" [ 0.5 ] \"float yradius\" [ 0.5 ]"
    );
    let _ = writeln!(
        out,
        "Sampler \"independent\" \"integer pixelsamples\" [ {} ] \"integer seed\" [ {} ]",
        settings.spp,
        // pbrt's seed is an int.
        settings.seed % (i32::MAX as u64 + 1)
    );
    let _ = writeln!(
        out,
        "Integrator \"path\" \"integer maxdepth\" [ {} ]",
        settings.max_depth
    );
}

/// The light, and each absorption group's material and strands.
fn world(out: &mut String, fiber: &ChiangHair, strands: &Grouped) {
    let _ = writeln!(out, "WorldBegin");
    let _ = writeln!(out, "AttributeBegin");
    let _ = writeln!(
        out,
        "LightSource \"infinite\" \"string filename\" [ \"{ENV_FILE}\" ] \"float scale\" [ 1 ]"
    );
    let _ = writeln!(out, "AttributeEnd");
    for group in &strands.groups {
        let _ = writeln!(out, "AttributeBegin");
        let _ = writeln!(
            out,
            "Material \"hair\" \"rgb sigma_a\" [ {} ] \"float beta_m\" [ {} ] \
             \"float beta_n\" [ {} ] \"float alpha\" [ {} ] \"float eta\" [ {} ]",
            triple(group.sigma_a, " "),
            num(fiber.beta_m),
            num(fiber.beta_n),
            num(fiber.alpha_deg),
            num(fiber.eta)
        );
        for strand in &group.strands {
            for run in width_runs(&strand.diameters) {
                curve(out, strand, run);
            }
        }
        let _ = writeln!(out, "AttributeEnd");
    }
}

/// Points `first..=last` of a strand: one curve shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Run {
    pub first: usize,
    pub last: usize,
}

/// The fewest runs of consecutive segments over which each point's diameter is the linear
/// interpolation (in segment index) of the run's end diameters, as pbrt widens one shape.
pub fn width_runs(diameters: &[f32]) -> Vec<Run> {
    let largest = diameters.iter().copied().fold(0.0, f32::max);
    let tolerance = WIDTH_TOLERANCE * largest.max(f32::MIN_POSITIVE);
    let linear = |first: usize, last: usize| {
        let (a, b) = (diameters[first], diameters[last]);
        (first..=last).all(|k| {
            let t = (k - first) as f32 / (last - first) as f32;
            (diameters[k] - (a + (b - a) * t)).abs() <= tolerance
        })
    };
    let mut runs = Vec::new();
    let mut first = 0;
    while first + 1 < diameters.len() {
        let mut last = first + 1;
        while last + 1 < diameters.len() && linear(first, last + 1) {
            last += 1;
        }
        runs.push(Run { first, last });
        first = last;
    }
    runs
}

/// One `Shape "curve"`: the run's segments as cubic Béziers on the polyline.
fn curve(out: &mut String, strand: &Polyline, run: Run) {
    let p = &strand.points;
    let mut control = vec![p[run.first]];
    for k in run.first..run.last {
        let (a, b) = (p[k], p[k + 1]);
        control.extend([a + (b - a) / 3.0, a + (b - a) * (2.0 / 3.0), b]);
    }
    let points: Vec<String> = control.iter().map(|q| point(*q)).collect();
    let _ = writeln!(
        out,
        "Shape \"curve\" \"string type\" [ \"cylinder\" ] \"string basis\" [ \"bezier\" ] \
         \"integer degree\" [ 3 ] \"point3 P\" [ {} ] \"float width0\" [ {} ] \"float width1\" [ {} ]",
        points.join("  "),
        strand.diameters[run.first],
        strand.diameters[run.last]
    );
}

/// A point as three f32 numbers (the groom's precision, written to round-trip).
fn point(p: Vec3) -> String {
    format!("{} {} {}", p.x, p.y, p.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant or linear taper is one run; a taper over the last fifth (the procedural
    /// grooms') is two; every point's diameter is exact.
    #[test]
    fn width_runs_are_few_and_exact() {
        assert_eq!(width_runs(&[0.1; 6]), vec![Run { first: 0, last: 5 }]);
        assert_eq!(
            width_runs(&[0.1, 0.08, 0.06, 0.04]),
            vec![Run { first: 0, last: 3 }]
        );
        let taper = [0.1, 0.1, 0.1, 0.1, 0.05, 0.0];
        assert_eq!(
            width_runs(&taper),
            vec![Run { first: 0, last: 3 }, Run { first: 3, last: 5 }]
        );
        let bumpy = [0.1, 0.3, 0.1, 0.3];
        assert_eq!(width_runs(&bumpy).len(), 3);
    }

    /// pbrt's fov is the shorter axis's: vertical for a wide image, widened for a tall one.
    #[test]
    fn fov_follows_the_shorter_axis() {
        let c = Camera {
            eye: [0.0, -10.0, 0.0],
            target: [0.0; 3],
            up: [0.0, 0.0, 1.0],
            fov_deg: 40.0,
        };
        assert_eq!(pbrt_fov_deg(&c, 300, 200), 40.0);
        let tall = pbrt_fov_deg(&c, 100, 200);
        let want = 2.0 * ((20f64.to_radians().tan()) * 0.5).atan().to_degrees();
        assert!((tall - want).abs() < 1e-12 && tall < 40.0);
    }
}
