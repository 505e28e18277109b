//! The scene for Mitsuba 3 (`mitsuba scene.xml`, or `mi.load_file`): `scene.xml`, the
//! strands' curve files `hair*.txt` and the environment's lat-long image `env.exr`.
//!
//! # The mapping (Mitsuba 3.9.1's source: `src/bsdfs/hair.cpp`, `src/shapes/bsplinecurve.cpp`,
//! `src/shapes/linearcurve.cpp`, `src/emitters/envmap.cpp`, `src/sensors/perspective.cpp`)
//! - Camera: `perspective` with `fov_axis` y and cuticle's vertical `fov`, `to_world` a
//!   `lookat` from the camera's eye, target and up (Mitsuba's look-at camera is not mirrored);
//!   `hdrfilm` of the scene's size with a `box` filter (radius ½ pixel, cuticle's uniform
//!   samples over each pixel) and RGB pixels (Mitsuba's alpha is 1 wherever the environment
//!   shows, so it is no coverage); `independent` sampler with the spp and seed.
//! - Integrator: `path` with `max_depth` = cuticle's `--max-depth` + 1 (Mitsuba counts the
//!   camera segment: 2 is direct light only, one scattering event).
//! - Environment: `envmap` with `env.exr` and `to_world` [`crate::env::MITSUBA_TO_WORLD`]
//!   (cuticle's own light-to-world turn), scale 1; the image is [`crate::env`]'s.
//! - Strands: `bsplinecurve`, whose file holds one control point per line, `x y z r` with r a
//!   RADIUS (half the groom's thickness, a diameter), and a blank line between curves. Each
//!   polyline point is written three times: a uniform cubic B-spline over p, p, p, q, q, q is
//!   exactly the segment p → q (the blending functions of the repeated points sum to one), so
//!   the curve is the polyline the path tracer draws, its radius linear along each segment.
//!   Not `linearcurve`: in Mitsuba 3.9.1 it leaves ∂p/∂u unset, so the shading frame's tangent
//!   (the hair BSDF's local y) is an arbitrary direction about the normal; `bsplinecurve` sets
//!   ∂p/∂u around the fiber, which makes the frame's t the curve's direction, root to tip, as
//!   cuticle's u.
//! - Hair: `hair` (Chiang et al. 2016) with `longitudinal_roughness` = β_m,
//!   `azimuthal_roughness` = β_n (Mitsuba's v = (0.726β + 0.812β² + 3.7β²⁰)² and
//!   s = √(π/8)(0.265β + 1.194β² + 5.372β²²) are Chiang's eqs. 7–8, as cuticle's),
//!   `scale_tilt` = α in degrees with cuticle's sign (Mitsuba turns the given inclination by
//!   −2α for R, so the R cone sits at −θ_i + 2α, as cuticle's), `int_ior` = η and `ext_ior` = 1
//!   (Mitsuba's default outside is air, 1.000277), and `sigma_a` as RGB: Mitsuba's σ_a is per
//!   unit radius (its transmittance is exp(−σ_a · 2 cos γ_t / cos θ_t) whatever the fiber's size,
//!   though its documentation says "inverse scene units"), as cuticle's μ_a is; melanin is
//!   written as the σ_a cuticle derives from it. In the `*_rgb` variants the three channels are
//!   exactly cuticle's. Mitsuba's BSDF value has no cos θ_i factor (its M_p is a density per
//!   solid angle over 2π), so its path tracer integrates Σ M_p A_p N_p L dω as cuticle's does.
//!   Per-strand absorption: a curve shape carries one BSDF, so each distinct σ_a gets its own
//!   shape and file (`hair_K.txt`).

use crate::strands::{Group, Grouped, grouped};
use crate::{
    ChiangHair, Export, ExportError, ExportFile, Format, HairLook, RenderSettings, Summary, env,
    num, triple,
};
use cuticle_render::Scene;
use glam::DVec3;
use std::fmt::Write;

/// The scene file's name.
pub const SCENE_FILE: &str = "scene.xml";
/// The environment image's name.
pub const ENV_FILE: &str = "env.exr";
/// The image `mitsuba scene.xml` writes (named after the scene).
pub const IMAGE_FILE: &str = "scene.exr";

/// `scene.xml`, the curve files and `env.exr` for `scene` (module documentation).
pub fn export(
    scene: &Scene,
    look: &HairLook,
    settings: &RenderSettings,
) -> Result<Export, ExportError> {
    let strands = grouped(&scene.groom, &look.sigma_a)?;
    let image = env::mitsuba_image(&scene.env);
    let names = curve_file_names(strands.groups.len());
    let mut files = vec![ExportFile {
        name: SCENE_FILE.into(),
        bytes: scene_xml(scene, &look.fiber, settings, &strands, &names).into_bytes(),
    }];
    for (group, name) in strands.groups.iter().zip(&names) {
        files.push(ExportFile {
            name: name.clone(),
            bytes: curve_file(group).into_bytes(),
        });
    }
    files.push(ExportFile {
        name: ENV_FILE.into(),
        bytes: image.exr_bytes()?,
    });
    Ok(Export {
        files,
        summary: Summary::of(
            Format::Mitsuba,
            [SCENE_FILE, IMAGE_FILE, ENV_FILE],
            &strands,
            (image.width, image.height),
        ),
    })
}

/// `hair.txt` for one group, `hair_0.txt`, `hair_1.txt`, … for several.
fn curve_file_names(groups: usize) -> Vec<String> {
    if groups == 1 {
        return vec!["hair.txt".into()];
    }
    (0..groups).map(|k| format!("hair_{k}.txt")).collect()
}

/// The B-spline control points of a group's strands: each point three times, `x y z r`.
pub fn curve_file(group: &Group) -> String {
    let mut out = String::new();
    for (k, strand) in group.strands.iter().enumerate() {
        if k > 0 {
            out.push('\n');
        }
        for (p, d) in strand.points.iter().zip(&strand.diameters) {
            let line = format!("{} {} {} {}\n", p.x, p.y, p.z, 0.5 * d);
            for _ in 0..3 {
                out.push_str(&line);
            }
        }
    }
    out
}

fn scene_xml(
    scene: &Scene,
    fiber: &ChiangHair,
    settings: &RenderSettings,
    strands: &Grouped,
    names: &[String],
) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "<?xml version=\"1.0\" encoding=\"utf-8\"?>");
    let _ = writeln!(
        out,
        "<!-- cuticle export for Mitsuba 3: {} strands, Chiang et al. 2016 hair, environment {} \
         (mapping: crate cuticle-export, module mitsuba) -->",
        strands.strand_count(),
        xml_escape(&scene.spec.env).replace("--", "- -")
    );
    let _ = writeln!(out, "<scene version=\"3.0.0\">");
    let _ = writeln!(
        out,
        "  <integrator type=\"path\">\n    <integer name=\"max_depth\" value=\"{}\"/>\n  </integrator>",
        settings.max_depth as u64 + 1
    );
    sensor(&mut out, scene, settings);
    emitter(&mut out);
    for (k, (group, name)) in strands.groups.iter().zip(names).enumerate() {
        bsdf(&mut out, k, fiber, group.sigma_a);
        let _ = writeln!(
            out,
            "  <shape type=\"bsplinecurve\">\n    <string name=\"filename\" value=\"{name}\"/>\n    \
             <ref id=\"hair{k}\"/>\n  </shape>"
        );
    }
    let _ = writeln!(out, "</scene>");
    out
}

fn sensor(out: &mut String, scene: &Scene, settings: &RenderSettings) {
    let c = &scene.camera;
    let v = |a: [f64; 3]| triple(DVec3::from_array(a), ", ");
    let (eye, target) = (DVec3::from_array(c.eye), DVec3::from_array(c.target));
    let b = scene.groom.bounds();
    let reach = (eye - target).length() + (b.max - b.min).as_dvec3().length();
    let near = 1e-3 * (eye - target).length();
    let _ = writeln!(out, "  <sensor type=\"perspective\">");
    let _ = writeln!(out, "    <string name=\"fov_axis\" value=\"y\"/>");
    let _ = writeln!(
        out,
        "    <float name=\"fov\" value=\"{}\"/>",
        num(c.fov_deg)
    );
    let _ = writeln!(
        out,
        "    <float name=\"near_clip\" value=\"{}\"/>",
        num(near)
    );
    let _ = writeln!(
        out,
        "    <float name=\"far_clip\" value=\"{}\"/>",
        num(4.0 * reach)
    );
    let _ = writeln!(
        out,
        "    <transform name=\"to_world\">\n      <lookat origin=\"{}\" target=\"{}\" up=\"{}\"/>\n    </transform>",
        v(c.eye),
        v(c.target),
        v(c.up)
    );
    let _ = writeln!(
        out,
        "    <sampler type=\"independent\">\n      <integer name=\"sample_count\" value=\"{}\"/>\n      \
         <integer name=\"seed\" value=\"{}\"/>\n    </sampler>",
        settings.spp,
        settings.seed % (i32::MAX as u64 + 1)
    );
    let _ = writeln!(
        out,
        "    <film type=\"hdrfilm\">\n      <integer name=\"width\" value=\"{}\"/>\n      \
         <integer name=\"height\" value=\"{}\"/>\n      <string name=\"pixel_format\" value=\"rgb\"/>\n      \
         <rfilter type=\"box\"/>\n    </film>",
        scene.spec.width, scene.spec.height
    );
    let _ = writeln!(out, "  </sensor>");
}

fn emitter(out: &mut String) {
    let matrix: Vec<String> = env::MITSUBA_TO_WORLD
        .iter()
        .flatten()
        .map(|&x| num(x))
        .collect();
    let _ = writeln!(
        out,
        "  <emitter type=\"envmap\">\n    <string name=\"filename\" value=\"{ENV_FILE}\"/>\n    \
         <float name=\"scale\" value=\"1\"/>\n    <transform name=\"to_world\">\n      \
         <matrix value=\"{}\"/>\n    </transform>\n  </emitter>",
        matrix.join(" ")
    );
}

fn bsdf(out: &mut String, k: usize, fiber: &ChiangHair, sigma_a: DVec3) {
    let _ = writeln!(out, "  <bsdf type=\"hair\" id=\"hair{k}\">");
    for (name, value) in [
        ("longitudinal_roughness", fiber.beta_m),
        ("azimuthal_roughness", fiber.beta_n),
        ("scale_tilt", fiber.alpha_deg),
        ("int_ior", fiber.eta),
        ("ext_ior", 1.0),
    ] {
        let _ = writeln!(out, "    <float name=\"{name}\" value=\"{}\"/>", num(value));
    }
    let _ = writeln!(
        out,
        "    <rgb name=\"sigma_a\" value=\"{}\"/>",
        triple(sigma_a, ", ")
    );
    let _ = writeln!(out, "  </bsdf>");
}

/// `s` safe inside an XML comment or attribute.
fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strands::Polyline;
    use glam::Vec3;

    /// Each point three times with half its diameter, a blank line between strands, nothing
    /// after the last.
    #[test]
    fn curve_files_triple_points_and_hold_radii() {
        let line = |z: f32| Polyline {
            strand: 0,
            points: vec![Vec3::new(0.0, 0.0, z), Vec3::new(1.0, 0.0, z)],
            diameters: vec![0.5, 0.25],
        };
        let group = Group {
            sigma_a: DVec3::ONE,
            strands: vec![line(0.0), line(2.0)],
        };
        let text = curve_file(&group);
        let blocks: Vec<&str> = text.split("\n\n").collect();
        assert_eq!(blocks.len(), 2);
        let lines: Vec<&str> = blocks[1].lines().collect();
        assert_eq!(lines.len(), 6);
        assert_eq!(lines[0], "0 0 2 0.25");
        assert_eq!(lines[2], "0 0 2 0.25");
        assert_eq!(lines[3], "1 0 2 0.125");
        assert!(text.ends_with("0.125\n"));
    }

    /// A uniform cubic B-spline over p, p, p, q, q, q runs along the segment p → q: the basis
    /// (Mitsuba's `bsplinecurve`, de Boor's uniform cubic) evaluated over each window of four.
    #[test]
    fn tripled_points_make_the_polyline() {
        let basis = |t: f64| {
            [
                (1.0 - t).powi(3) / 6.0,
                (3.0 * t.powi(3) - 6.0 * t * t + 4.0) / 6.0,
                (-3.0 * t.powi(3) + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
                t.powi(3) / 6.0,
            ]
        };
        let (p, q, r) = (
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(1.0, 2.0, 3.0),
        );
        let control = [p, p, p, q, q, q, r, r, r];
        for window in control.windows(4) {
            for t in [0.0, 0.3, 0.7, 1.0] {
                let b = basis(t);
                let x: DVec3 = (0..4).map(|k| window[k] * b[k]).sum();
                // On p→q or q→r: the distance to the nearer segment is 0.
                let on = |a: DVec3, b: DVec3| {
                    let s = ((x - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    (a + (b - a) * s - x).length()
                };
                assert!(on(p, q).min(on(q, r)) < 1e-12, "{window:?} {t}: {x}");
            }
        }
        let b = basis(0.0);
        let start: DVec3 = (0..4).map(|k| control[k] * b[k]).sum();
        assert!(start.abs_diff_eq(p, 1e-12));
    }
}
