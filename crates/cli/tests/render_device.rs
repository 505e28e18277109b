//! `--device auto|gpu|cpu` end to end: without any adapter `--device gpu` fails with one clear
//! line and a non-zero exit while `auto` falls back to the CPU renderer; on the software device
//! (lavapipe, which CI installs) `gpu` renders and render.json names the adapter, and `auto`
//! does not take a software adapter.

use std::process::Command;

/// A tiny render with `device`, Vulkan hidden when `no_adapter` (the loader then finds no
/// driver, as on a machine without one).
fn render(device: &str, no_adapter: bool, out: &std::path::Path) -> std::process::Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_cuticle"));
    cmd.args([
        "render",
        "--device",
        device,
        "--strands",
        "30",
        "--lights",
        "4",
        "--width",
        "48",
        "--height",
        "32",
        "--out",
    ])
    .arg(out);
    if no_adapter {
        cmd.env("VK_ICD_FILENAMES", "/nonexistent.json")
            .env("VK_DRIVER_FILES", "/nonexistent.json");
    }
    cmd.output().expect("the binary runs")
}

fn device_of(out: &std::path::Path) -> serde_json::Value {
    let text = std::fs::read_to_string(out.join("render.json")).unwrap();
    serde_json::from_str::<serde_json::Value>(&text).unwrap()["device"].clone()
}

#[test]
fn no_adapter_fails_gpu_and_auto_falls_back_to_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let out = render("gpu", true, &dir.path().join("gpu"));
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(lines[0].contains("no GPU adapter found"), "{stderr}");
    assert!(
        lines[0].contains("apt-get install -y mesa-vulkan-drivers"),
        "{stderr}"
    );
    assert!(
        !dir.path().join("gpu").exists(),
        "a failed render left a folder"
    );
    let auto = dir.path().join("auto");
    let out = render("auto", true, &auto);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(device_of(&auto)["name"], "cpu");
}

#[test]
fn gpu_renders_on_the_software_device_and_auto_does_not_take_it() {
    let dir = tempfile::tempdir().unwrap();
    let gpu = dir.path().join("gpu");
    let out = render("gpu", false, &gpu);
    assert!(
        out.status.success(),
        "--device gpu needs a Vulkan driver (apt-get install -y mesa-vulkan-drivers libvulkan1): {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let device = device_of(&gpu);
    assert_eq!(device["name"], "gpu");
    let kind = device["adapter"]["kind"].as_str().unwrap().to_string();
    assert!(gpu.join("image.png").exists() && gpu.join("image.exr").exists());
    let auto = dir.path().join("auto");
    assert!(render("auto", false, &auto).status.success());
    let expected = if kind == "software" { "cpu" } else { "gpu" };
    assert_eq!(device_of(&auto)["name"], expected, "adapter kind {kind}");
}
