//! Outputs as sets (DESIGN.md §9) and validation reading what it relies on: a folder holds the
//! previous complete set or the new one after a kill, a folder of another command is refused,
//! and `validate` refuses a configuration whose files disagree with its record.

mod common;

use common::{B, assert_refused, assert_runs, cuticle, names};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

/// The width recorded in a render folder, checked against both images: one set, not a mix.
fn render_set_width(dir: &Path) -> u64 {
    assert_eq!(
        names(dir),
        ["coverage.exr", "image.exr", "image.png", "render.json"],
        "{}",
        dir.display()
    );
    let record: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("render.json")).unwrap()).unwrap();
    let width = record["params"]["width"].as_u64().unwrap();
    let png = image::open(dir.join("image.png")).unwrap();
    assert_eq!(png.width() as u64, width, "image.png of another run");
    for name in ["image.exr", "coverage.exr"] {
        let exr = exr::meta::MetaData::read_from_file(dir.join(name), false).unwrap();
        assert_eq!(
            exr.headers[0].layer_size.0 as u64, width,
            "{name} of another run"
        );
    }
    width
}

fn render(out: &str, width: &str) -> Vec<String> {
    let mut args: Vec<String> = ["render"].iter().chain(&B).map(|s| s.to_string()).collect();
    let at = args.iter().position(|a| a == "--width").unwrap();
    args[at + 1] = width.into();
    args.extend(["--out".into(), out.into()]);
    args
}

#[test]
fn a_render_over_an_earlier_one_replaces_it_whole_even_when_killed() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("render");
    let out = dir.to_str().unwrap();
    let run = |width: &str| {
        let args = render(out, width);
        assert_runs(&args.iter().map(String::as_str).collect::<Vec<_>>());
    };
    let start = std::time::Instant::now();
    run("32");
    let seconds = start.elapsed().as_secs_f64();
    assert_eq!(render_set_width(&dir), 32);
    // Killed at moments spread over a run (tables, fit, drawing, shading, writing, the swap):
    // each time the folder holds one whole set, 32 or 48 wide.
    let bin = env!("CARGO_BIN_EXE_cuticle");
    let mut widths = Vec::new();
    for fraction in [0.3, 0.7, 0.9, 0.97, 1.0, 1.03] {
        let mut child = Command::new(bin)
            .args(render(out, "48"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_secs_f64(fraction * seconds));
        let _ = child.kill();
        child.wait().unwrap();
        let width = render_set_width(&dir);
        widths.push(width);
        if width == 48 {
            run("32");
        }
    }
    eprintln!("widths after each kill: {widths:?}");
    assert_eq!(
        names(tmp.path()),
        ["render"],
        "stages of killed runs are cleared"
    );
}

#[test]
fn folders_of_other_commands_or_with_other_files_are_never_merged() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let out = dir.to_str().unwrap();
    assert_runs(&[
        "lobes",
        "--model",
        "marschner",
        "--width",
        "16",
        "--out",
        out,
    ]);
    let before = names(&dir);
    let args = render(out, "32");
    assert_refused(
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
        "not an earlier output of `cuticle render`",
    );
    assert_eq!(names(&dir), before, "the lobes set is untouched");
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    assert_refused(
        &[
            "lobes",
            "--model",
            "marschner",
            "--width",
            "16",
            "--out",
            out,
        ],
        "holds notes.txt",
    );
    // A set replaced by one with fewer files leaves none of the old ones behind.
    std::fs::remove_file(dir.join("notes.txt")).unwrap();
    assert_runs(&[
        "lobes",
        "--model",
        "marschner",
        "--width",
        "16",
        "--samples",
        "2000",
        "--out",
        out,
    ]);
    assert!(dir.join("compare.png").is_file());
    assert_runs(&[
        "lobes",
        "--model",
        "marschner",
        "--width",
        "16",
        "--out",
        out,
    ]);
    assert!(
        !dir.join("compare.png").exists(),
        "a file of the earlier set stayed"
    );
}

/// Writes an RGB EXR with the given pixels.
fn write_exr(path: &Path, width: usize, height: usize, pixel: impl Fn(usize, usize) -> f32 + Sync) {
    exr::prelude::write_rgb_file(path, width, height, |x, y| {
        let v = pixel(x, y);
        (v, v, v)
    })
    .unwrap();
}

#[test]
fn validate_refuses_a_configuration_whose_files_disagree_with_its_record() {
    let tmp = tempfile::tempdir().unwrap();
    let good = tmp.path().join("good");
    assert_runs(&["sim", "--rays", "20000", "--out", good.to_str().unwrap()]);
    let validate = |sim: &Path| {
        let out = tmp.path().join("validation").display().to_string();
        vec![
            "validate".to_string(),
            "--sim".into(),
            sim.display().to_string(),
            "--models".into(),
            "marschner".into(),
            "--sheets".into(),
            "0".into(),
            "--out".into(),
            out,
        ]
    };
    let as_str = |v: &[String]| v.iter().map(String::clone).collect::<Vec<_>>();
    type Spoil = fn(&Path);
    let cases: [(&str, Spoil, &str); 8] = [
        // Issue 9 #2: a 5 × 3 TT.exr panicked on "images on different grids".
        (
            "small",
            |d| write_exr(&d.join("TT.exr"), 5, 3, |_, _| 0.0),
            "is 5x3",
        ),
        // Issue 9 #14: one NaN pixel went into validation.csv.
        (
            "nan",
            |d| {
                write_exr(&d.join("TT.exr"), 400, 100, |x, y| {
                    if (x, y) == (7, 3) { f32::NAN } else { 0.0 }
                })
            },
            "pixel (7, 3)",
        ),
        // Issue 9 #25: what validate did not read, it did not check.
        (
            "csv",
            |d| std::fs::write(d.join("azimuthal.csv"), "garbage").unwrap(),
            "azimuthal.csv",
        ),
        (
            "total",
            |d| std::fs::remove_file(d.join("total.exr")).unwrap(),
            "total.exr",
        ),
        (
            "energy",
            |d| edit_record(d, |v| v["energy"]["TT"] = "lots".into()),
            "\"energy\".\"TT\" is \"lots\"",
        ),
        (
            "rays",
            |d| edit_record(d, |v| v["rays"] = serde_json::Value::Null),
            "rays",
        ),
        (
            "swapped",
            |d| {
                std::fs::copy(d.join("R.exr"), d.join("TT.exr"))
                    .map(|_| ())
                    .unwrap()
            },
            "TT.exr",
        ),
        (
            "grid",
            |d| edit_record(d, |v| v["params"]["grid"] = serde_json::json!([40, 10])),
            "40x10",
        ),
    ];
    for (name, spoil, needle) in cases {
        let dir = tmp.path().join(name);
        copy_dir(&good, &dir);
        spoil(&dir);
        let args = validate(&dir);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_refused(&args, needle);
        assert!(
            !tmp.path().join("validation").exists(),
            "{name}: wrote a validation"
        );
    }
    let ok = as_str(&validate(&good));
    let run = cuticle(&ok.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}

fn edit_record(dir: &Path, edit: impl Fn(&mut serde_json::Value)) {
    let path = dir.join("sim.json");
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    edit(&mut v);
    std::fs::write(&path, serde_json::to_string(&v).unwrap()).unwrap();
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
}
