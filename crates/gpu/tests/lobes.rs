//! The per-lobe debug views on the GPU (the `lobes` flag word of shade.wgsl's uniform) against
//! the CPU renderer's, within the bounds of tests/parity.rs (relative RMSE over hair pixels
//! below 5e-3, no pixel off by more than 1e-2 of the brightest, where the two drawings agree).

mod common;

use common::{agreeing_pixels, cpu, gpu, load, relative_rmse, spec, worst_relative};
use cuticle_render::Lobes;

#[test]
fn lobe_masks_match_the_cpu() {
    let mut small = spec(150, "default", 16);
    (small.width, small.height) = (160, 106);
    let mut scene = load(small);
    let (all, frame) = gpu().render(&scene).expect("GPU render");
    let (_, prepared, _) = cpu().render(&scene);
    let agree = agreeing_pixels(&gpu().coverage(&frame), &prepared.coverage);
    let mask = agree.hair;
    for (name, lobes) in [
        (
            "R only",
            Lobes {
                r: true,
                tt: false,
                trt: false,
            },
        ),
        (
            "TT off",
            Lobes {
                tt: false,
                ..Lobes::ALL
            },
        ),
    ] {
        scene.spec.lobes = lobes;
        let (want, _, _) = cpu().render(&scene);
        let (got, _) = gpu().render(&scene).expect("GPU render");
        let e = relative_rmse(&got, &want, &mask);
        let worst = worst_relative(&got, &want, &agree.all);
        eprintln!("{name}: relative RMSE {e:.2e}, worst pixel {worst:.2e}");
        assert!(e < 5e-3 && worst < 1e-2, "{name}: RMSE {e}, worst {worst}");
        // The mask reached the shader: the view is far from the all-lobes image.
        let moved = relative_rmse(&got, &all, &mask);
        assert!(
            moved > 10.0 * 5e-3,
            "{name}: moved only {moved} from all lobes"
        );
    }
}
