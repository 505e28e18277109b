//! What an edit redoes on the GPU: a hair-parameter edit re-shades and resolves without
//! redrawing or rebuilding shadows (counted passes and their dispatches), a camera move
//! redraws (the drawing's dispatches again) and rebuilds the shadows and re-shades without
//! re-uploading tables or strands, an environment rotation turns the lights (no fit) and rebuilds
//! the shadows without redrawing, and re-uploading one strand's parameters changes that
//! strand's pixels and no other, as the CPU renderer paints it.

mod common;

use common::{agreeing_pixels, cpu, device, gpu, load, relative_rmse, spec};
use cuticle_gpu::{GpuRenderer, Passes, StrandError, StrandParams, Visibility};
use cuticle_groom::Absorption;
use cuticle_render::{Renderer, Scene};

#[test]
fn a_hair_edit_reshades_without_redrawing() {
    // Its own renderers: the tables' one-entry caches must not see other tests' parameters.
    let cpu = Renderer::new();
    let gpu = GpuRenderer::new(device(), &cpu);
    let scene = load(spec(80, "default", 8));
    let mut frame = gpu.prepare(&scene).unwrap();
    let before = gpu.shade(&mut frame, &scene);
    let first = frame.passes();
    // The drawing's steps (draw.wgsl's six entry points, `cover` twice) and at least one
    // level of each of its two prefix sums (a scan and no add-back).
    assert!(first.drawing_steps >= 9, "{first:?}");
    // One shading dispatch per chunk of lights (within llvmpipe's loop budget), at least one.
    assert!(first.shading_steps >= 1, "{first:?}");
    assert_eq!(
        first,
        Passes {
            drawing: 1,
            drawing_steps: first.drawing_steps,
            shadows: 1,
            shadow_steps: 5,
            shading: 1,
            shading_steps: first.shading_steps,
            resolve: 1,
            table_uploads: 2,
            strand_uploads: 1,
            groom_uploads: 1,
        }
    );
    let mut edited = scene.clone();
    edited.spec.hair.beta_r_deg = 4.0;
    let after = gpu.shade(&mut frame, &edited);
    let second = frame.passes();
    assert_eq!(
        (
            second.drawing,
            second.drawing_steps,
            second.shadows,
            second.shadow_steps
        ),
        (1, first.drawing_steps, 1, 5),
        "an edit redrew"
    );
    assert_eq!((second.shading, second.resolve), (2, 2));
    // β_R rebuilds the back-scattering tables (not the lobe table, which has no β axis).
    assert_eq!(second.table_uploads, 3);
    assert_eq!(second.strand_uploads, 1, "no strand changed");
    assert_ne!(after.pixels, before.pixels, "the edit changed nothing");
    // The re-shaded frame is the frame rendered afresh with the edit.
    let (fresh, _) = gpu.render(&edited).unwrap();
    assert_eq!(after.pixels, fresh.pixels);
}

#[test]
fn a_camera_move_redraws_and_reshades_without_uploads() {
    let cpu = Renderer::new();
    let gpu = GpuRenderer::new(device(), &cpu);
    let scene = load(spec(80, "default", 8));
    let mut frame = gpu.prepare(&scene).unwrap();
    let before = gpu.shade(&mut frame, &scene);
    let (steps, shading_steps) = (frame.passes().drawing_steps, frame.passes().shading_steps);
    let mut moved = scene.clone();
    let c = &mut moved.camera;
    let distance = glam::DVec3::from(c.eye).distance(glam::DVec3::from(c.target));
    c.eye[0] += 0.2 * distance;
    gpu.redraw(&mut frame, &moved).unwrap();
    let after = gpu.shade(&mut frame, &moved);
    assert_eq!(
        frame.passes(),
        Passes {
            drawing: 2,
            drawing_steps: 2 * steps,
            shadows: 2,
            shadow_steps: 10,
            shading: 2,
            shading_steps: 2 * shading_steps,
            resolve: 2,
            table_uploads: 2,
            strand_uploads: 1,
            groom_uploads: 1,
        },
        "a camera move must redo drawing, shadows and shading, and upload nothing else (the \
         groom included)"
    );
    assert_ne!(after.pixels, before.pixels, "the move changed nothing");
    let (fresh, _) = gpu.render(&moved).unwrap();
    assert_eq!(
        after.pixels, fresh.pixels,
        "the redrawn frame is not the moved one"
    );
    // A painted strand stays painted across the move.
    let vis = gpu.visibility(&frame);
    let s = most_visible(&vis, moved.groom.strand_count());
    gpu.update_strands(&mut frame, s, &[StrandParams::new([2.0, 3.0, 5.0])])
        .unwrap();
    let painted = gpu.shade(&mut frame, &moved);
    gpu.redraw(&mut frame, &moved).unwrap();
    assert_eq!(
        frame.passes().strand_uploads,
        2,
        "the move re-uploaded strands"
    );
    assert_eq!(gpu.shade(&mut frame, &moved).pixels, painted.pixels);
}

/// The strand covering the most subsamples.
/// A redraw with another groom uploads it and derives its strand records (the camera-move
/// test above keeps both because the groom is the same), and draws that groom: the image is
/// the new scene's fresh render.
#[test]
fn a_redraw_with_another_groom_uploads_it() {
    let cpu = Renderer::new();
    let gpu = GpuRenderer::new(device(), &cpu);
    let scene = load(spec(80, "default", 8));
    let mut frame = gpu.prepare(&scene).unwrap();
    gpu.shade(&mut frame, &scene);
    let other = load(spec(60, "default", 8));
    gpu.redraw(&mut frame, &other).unwrap();
    let after = gpu.shade(&mut frame, &other);
    let p = frame.passes();
    assert_eq!((p.groom_uploads, p.strand_uploads), (2, 2), "{p:?}");
    let (fresh, _) = gpu.render(&other).unwrap();
    assert_eq!(after.pixels, fresh.pixels);
}

/// An environment rotation re-fits nothing: the map and its fitted lights turn together, and
/// `relight` rebuilds the opacity maps and shadows for the turned lights without redrawing or
/// uploading tables or strands. The image is the turned scene's: bit for bit the GPU's fresh
/// render of it, and the CPU's within the parity bound (tests/parity.rs).
#[test]
fn an_environment_rotation_reshadows_without_a_fit_or_a_redraw() {
    let cpu = Renderer::new();
    let gpu = GpuRenderer::new(device(), &cpu);
    let scene = load(spec(80, "default", 8));
    let mut frame = gpu.prepare(&scene).unwrap();
    let before = gpu.shade(&mut frame, &scene);
    let first = frame.passes();
    let turned = rotated(&scene, 60.0);
    gpu.relight(&mut frame, &turned).unwrap();
    let after = gpu.shade(&mut frame, &turned);
    let p = frame.passes();
    assert_eq!(
        (p.drawing, p.drawing_steps),
        (1, first.drawing_steps),
        "a rotation redrew"
    );
    assert_eq!((p.shadows, p.shadow_steps), (2, 2 * first.shadow_steps));
    assert_eq!((p.shading, p.resolve), (2, 2));
    assert_eq!(
        (p.table_uploads, p.strand_uploads, p.groom_uploads),
        (first.table_uploads, first.strand_uploads, 1),
        "a rotation uploaded tables, strand records or the groom"
    );
    assert_ne!(after.pixels, before.pixels, "the rotation changed nothing");
    let (fresh, _) = gpu.render(&turned).unwrap();
    assert_eq!(
        after.pixels, fresh.pixels,
        "the relit frame is not the turned one"
    );
    let (want, prepared, _) = cpu.render(&turned);
    let mask = agreeing_pixels(&gpu.coverage(&frame), &prepared.coverage);
    let e = relative_rmse(&after, &want, &mask.hair);
    eprintln!("turned 60°: relative RMSE against the CPU {e:.2e}");
    assert!(e < 5e-3, "{e}");
    // And the turn is not a no-op on the CPU either: the turned image is far from the first.
    let moved = relative_rmse(&before, &want, &mask.hair);
    assert!(moved > 10.0 * 5e-3, "{moved}");
}

/// `scene` with its map and its fitted lights turned by `deg` about the up axis (+y), as the
/// viewer turns them before its re-fit: no fit.
fn rotated(scene: &Scene, deg: f64) -> Scene {
    let (s, c) = (deg.to_radians() as f32).sin_cos();
    let lights = scene
        .lights
        .iter()
        .map(|l| {
            let (d, mut l) = (l.direction, *l);
            l.direction = glam::Vec3::new(d.x * c - d.z * s, d.y, d.x * s + d.z * c);
            l
        })
        .collect();
    let mut spec = scene.spec.clone();
    spec.env_rotate_deg += deg;
    let env = scene
        .env
        .clone()
        .with_rotation(spec.env_rotate_deg.to_radians());
    Scene::from_parts(spec, scene.groom.clone(), env, lights)
}

fn most_visible(vis: &Visibility, strands: usize) -> usize {
    let mut count = vec![0usize; strands];
    vis.strand
        .iter()
        .filter(|&&s| s != Visibility::EMPTY)
        .for_each(|&s| count[s as usize] += 1);
    (0..strands).max_by_key(|&s| count[s]).unwrap()
}

#[test]
fn updating_one_strand_changes_only_its_pixels() {
    let scene = load(spec(80, "default", 8));
    let mut frame = gpu().prepare(&scene).unwrap();
    let before = gpu().shade(&mut frame, &scene);
    let vis = gpu().visibility(&frame);
    let s = most_visible(&vis, scene.groom.strand_count());
    let paint = [2.0f32, 3.0, 5.0];
    gpu()
        .update_strands(&mut frame, s, &[StrandParams::new(paint)])
        .unwrap();
    let after = gpu().shade(&mut frame, &scene);
    assert_eq!(frame.passes().drawing, 1);
    let (mut touched, mut changed) = (0, 0);
    for k in 0..before.pixels.len() {
        let shows = vis
            .pixel(k % vis.width, k / vis.width)
            .any(|t| t == s as u32);
        let differs = before.pixels[k] != after.pixels[k];
        if shows {
            touched += 1;
            changed += differs as usize;
        } else {
            assert!(!differs, "pixel {k} shows no strand {s} but changed");
        }
    }
    assert!(touched > 20, "strand {s} covers only {touched} pixels");
    assert!(
        changed * 10 >= touched * 9,
        "{changed} of {touched} pixels changed"
    );
    // The CPU renderer with the strand's appearance painted the same way agrees.
    let mut painted = scene.clone();
    painted.groom.appearance_mut()[s].absorption = Some(Absorption::MuA(paint));
    let (want, prepared, _) = cpu().render(&painted);
    let mask = agreeing_pixels(&gpu().coverage(&frame), &prepared.coverage);
    let e = relative_rmse(&after, &want, &mask.hair);
    assert!(e < 5e-3, "painted strand against the CPU: {e}");
}

#[test]
fn bad_strand_updates_are_refused() {
    let scene = load(spec(20, "default", 4));
    let mut frame = gpu().prepare(&scene).unwrap();
    let n = scene.groom.strand_count();
    let before = frame.strands()[0];
    let ok = StrandParams::new([0.1, 0.2, 0.3]);
    assert_eq!(
        gpu().update_strands(&mut frame, n - 1, &[ok, ok]),
        Err(StrandError::OutOfRange {
            first: n - 1,
            end: n + 1,
            count: n
        })
    );
    assert!(matches!(
        gpu().update_strands(&mut frame, 0, &[StrandParams::new([0.1, f32::NAN, 0.3])]),
        Err(StrandError::BadAbsorption { strand: 0, .. })
    ));
    assert_eq!(frame.strands()[0], before, "a refused update wrote");
    assert_eq!(frame.passes().strand_uploads, 1, "a refused update wrote");
}
