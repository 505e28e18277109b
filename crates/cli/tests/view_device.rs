//! `cuticle view --device`: what the window cannot do is refused before it opens, with one
//! clear line and a non-zero exit (no display is needed for these).

mod common;

#[test]
fn view_refuses_a_bad_device_and_the_brute_force_on_the_gpu() {
    common::assert_refused(
        &["view", "--device", "tpu"],
        "--device takes auto, gpu or cpu",
    );
    common::assert_refused(
        &[
            "view",
            "--device",
            "gpu",
            "--method",
            "brute",
            "--strands",
            "20",
            "--width",
            "32",
            "--height",
            "24",
        ],
        "runs on the CPU only",
    );
}
