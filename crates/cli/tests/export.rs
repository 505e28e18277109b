//! `cuticle export`: both formats write their set with `export.json`, and every impossible
//! request (a model the renderers lack, flags that do not apply, bad numbers, an output folder
//! that cannot be written) is one clear line, a non-zero exit and nothing written.

mod common;

use common::{assert_refused, assert_runs, names};
use serde_json::Value;

/// A small scene: 6 strands of the straight preset, 24 × 16 pixels, a constant environment.
const SMALL: [&str; 10] = [
    "--strands",
    "6",
    "--width",
    "24",
    "--height",
    "16",
    "--env",
    "constant:0.5,0.6,0.7",
    "--model",
    "chiang2016",
];

#[test]
fn both_formats_write_their_set_and_record() {
    let tmp = tempfile::tempdir().unwrap();
    for (format, files) in [
        ("pbrt", vec!["env.exr", "export.json", "scene.pbrt"]),
        (
            "mitsuba",
            vec!["env.exr", "export.json", "hair.txt", "scene.xml"],
        ),
    ] {
        let out = tmp.path().join(format);
        let out_s = out.display().to_string();
        let mut args = vec![
            "export", "--format", format, "--beta-m", "0.2", "--eta", "1.5",
        ];
        args.extend(SMALL);
        args.extend(["--spp", "8", "--out", &out_s]);
        let printed = assert_runs(&args);
        assert!(printed.contains("6 strands"), "{printed}");
        assert_eq!(names(&out), files);
        let record: Value =
            serde_json::from_slice(&std::fs::read(out.join("export.json")).unwrap()).unwrap();
        assert_eq!(record["format"], format);
        assert_eq!(record["export"]["strands"], 6);
        assert_eq!(record["path"]["fiber"]["beta_m"], 0.2);
        assert_eq!(record["path"]["fiber"]["eta"], 1.5);
        assert_eq!(record["path"]["spp"], 8);
        // A second export replaces the first as a set.
        assert_runs(&args);
        assert_eq!(names(&out), files);
    }
    let scene = std::fs::read_to_string(tmp.path().join("mitsuba/scene.xml")).unwrap();
    assert!(scene.contains("<float name=\"longitudinal_roughness\" value=\"0.2\"/>"));
    assert!(scene.contains("<float name=\"int_ior\" value=\"1.5\"/>"));
    let pbrt = std::fs::read_to_string(tmp.path().join("pbrt/scene.pbrt")).unwrap();
    assert!(pbrt.contains("\"float beta_m\" [ 0.2 ]"));
}

#[test]
fn impossible_exports_are_refused_with_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let out_s = out.display().to_string();
    let file = tmp.path().join("a-file");
    std::fs::write(&file, "not a folder").unwrap();
    let under_file = file.join("out").display().to_string();
    let small = |extra: &[&'static str], out: &str| {
        let mut args = vec!["export"];
        args.extend(SMALL);
        args.extend(extra);
        args.extend(["--out", out]);
        args.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let rows: Vec<(Vec<String>, &str)> = vec![
        (small(&["--format", "obj"], &out_s), "obj"),
        (small(&[], &out_s), "--format"),
        (
            vec![
                "export",
                "--format",
                "pbrt",
                "--strands",
                "6",
                "--out",
                &out_s,
            ]
            .into_iter()
            .map(String::from)
            .collect(),
            "--model chiang2016",
        ),
        (
            small(&["--format", "pbrt", "--method", "srbf"], &out_s),
            "--method srbf",
        ),
        (
            small(&["--format", "pbrt", "--lights", "8"], &out_s),
            "--lights",
        ),
        (
            small(&["--format", "pbrt", "--beta-m", "2"], &out_s),
            "beta_m",
        ),
        (
            small(&["--format", "pbrt", "--beta", "0.1"], &out_s),
            "--beta",
        ),
        (
            small(&["--format", "mitsuba", "--eta", "nan"], &out_s),
            "eta",
        ),
        (small(&["--format", "mitsuba", "--spp", "0"], &out_s), "spp"),
        (
            small(&["--format", "mitsuba", "--no-multiple"], &out_s),
            "--no-multiple",
        ),
        (
            small(
                &["--format", "mitsuba", "--groom", "/nonexistent.hair"],
                &out_s,
            ),
            "nonexistent",
        ),
        (small(&["--format", "pbrt"], &under_file), "cannot"),
    ];
    for (args, needle) in &rows {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_refused(&args, needle);
        assert!(!out.exists(), "{args:?} wrote its output folder");
    }
}
