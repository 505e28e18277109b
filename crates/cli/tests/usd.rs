//! USD grooms through the command line (issue 54): read everywhere a groom is taken, written by
//! `groom make --out FILE.usda|.usdc`, and hostile stages refused in one line.

mod common;

use common::{B, assert_refused, assert_runs};
use std::path::{Path, PathBuf};

fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../groom/tests/data/usd")
        .join(name)
        .display()
        .to_string()
}

fn make(out: &Path, strands: &str) -> String {
    assert_runs(&[
        "groom",
        "make",
        "--preset",
        "wavy",
        "--strands",
        strands,
        "--out",
        out.to_str().unwrap(),
    ])
}

#[test]
fn groom_make_writes_usd_that_groom_info_and_render_read() {
    let tmp = tempfile::tempdir().unwrap();
    let hair_dir = tmp.path().join("hair");
    make(&hair_dir, "30");
    let hair_info = assert_runs(&[
        "groom",
        "info",
        hair_dir.join("groom.hair").to_str().unwrap(),
    ]);
    {
        let ext = "usda";
        let out: PathBuf = tmp.path().join(format!("groom.{ext}"));
        let shown = make(&out, "30");
        assert!(shown.contains("USD BasisCurves"), "{shown}");
        let info = assert_runs(&["groom", "info", out.to_str().unwrap()]);
        // the same strands, points, bounds and lengths as the .hair of the same groom.
        let tail = |s: &str| {
            s.lines()
                .skip(1)
                .filter(|l| !l.starts_with("info:"))
                .map(str::to_string)
                .collect::<Vec<_>>()
        };
        assert!(info.contains("30 strands"), "{info}");
        assert_eq!(
            tail(&info)[2..],
            tail(&hair_info)[2..],
            "{info}\n{hair_info}"
        );
        let render_out = tmp.path().join(format!("render-{ext}"));
        let mut args = vec![
            "render",
            "--device",
            "cpu",
            "--groom",
            out.to_str().unwrap(),
        ];
        args.extend(B);
        args.extend(["--out", render_out.to_str().unwrap()]);
        assert_runs(&args);
        assert!(render_out.join("image.png").exists());
    }
    assert_refused(
        &[
            "groom",
            "make",
            "--out",
            tmp.path().join("g.usdz").to_str().unwrap(),
        ],
        ".usdz is not written",
    );
}

#[test]
fn fixtures_from_pixars_library_render_with_either_method() {
    let tmp = tempfile::tempdir().unwrap();
    for name in ["upright_y_cm.usda", "transforms.usdc", "primvars.usda"] {
        let groom = fixture(name);
        let out = tmp.path().join(name).display().to_string();
        let mut srbf = vec!["render", "--device", "cpu", "--groom", &groom];
        srbf.extend(B);
        srbf.extend(["--out", &out]);
        assert_runs(&srbf);
        let path_out = format!("{out}-path");
        assert_runs(&[
            "render", "--method", "path", "--spp", "2", "--width", "32", "--height", "24",
            "--groom", &groom, "--out", &path_out,
        ]);
    }
}

/// A stage of 12 thick vertical strands whose eumelanin primvar is `eumelanin` (uniform).
fn pigmented(dir: &Path, name: &str, eumelanin: [f32; 2]) -> String {
    let points: Vec<String> = (0..12)
        .flat_map(|i| {
            let x = i as f32 * 0.4 - 2.2;
            [format!("({x}, 0, -3)"), format!("({x}, 0, 3)")]
        })
        .collect();
    let values: Vec<String> = (0..12).map(|i| eumelanin[i % 2].to_string()).collect();
    let text = format!(
        "#usda 1.0\n(\n    metersPerUnit = 0.01\n    upAxis = \"Z\"\n)\ndef BasisCurves \"Hair\"\n{{\n    uniform token type = \"linear\"\n    int[] curveVertexCounts = [{}]\n    point3f[] points = [{}]\n    float[] widths = [0.3] (interpolation = \"constant\")\n    float[] primvars:eumelanin = [{}] (interpolation = \"uniform\")\n}}\n",
        ["2"; 12].join(", "),
        points.join(", "),
        values.join(", ")
    );
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// Mean of the image's channels.
fn mean_of(png: &Path) -> f64 {
    let image = image::open(png).unwrap().to_rgb8();
    image.pixels().flat_map(|p| p.0).map(f64::from).sum::<f64>() / (image.len() as f64)
}

/// Per-curve melanin from the stage is what the strands are shaded with: all-blonde renders
/// brighter than half-black, and half-black brighter than all-black.
#[test]
fn per_curve_melanin_shades_each_strand() {
    let tmp = tempfile::tempdir().unwrap();
    let mut means = Vec::new();
    for (name, eu) in [
        ("blonde", [0.1, 0.1]),
        ("mixed", [0.1, 8.0]),
        ("black", [8.0, 8.0]),
    ] {
        let groom = pigmented(tmp.path(), &format!("{name}.usda"), eu);
        let out = tmp.path().join(name);
        let mut args = vec!["render", "--device", "cpu", "--groom", &groom];
        args.extend(B);
        args.extend(["--out", out.to_str().unwrap()]);
        assert_runs(&args);
        means.push(mean_of(&out.join("image.png")));
    }
    assert!(means[0] > means[1] && means[1] > means[2], "{means:?}");
}

/// The scene file's `groom` key takes a USD groom too.
#[test]
fn a_scene_file_names_a_usd_groom() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("scene.toml");
    let groom = fixture("primvars.usda");
    std::fs::write(&scene, format!("groom = {groom:?}\n")).unwrap();
    let out = tmp.path().join("out");
    let mut args = vec![
        "render",
        "--device",
        "cpu",
        "--scene",
        scene.to_str().unwrap(),
    ];
    args.extend(B);
    args.extend(["--out", out.to_str().unwrap()]);
    assert_runs(&args);
    let record = std::fs::read_to_string(out.join("render.json")).unwrap();
    assert!(record.contains("primvars.usda"), "{record}");
}

#[test]
fn hostile_usd_is_refused_in_one_line_by_every_reader() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let mut huge = std::fs::read(fixture("upright_z_m.usdc")).unwrap();
    let mut pattern = 4u64.to_le_bytes().to_vec();
    for v in [0.0f32, 0.0, 0.1] {
        pattern.extend(v.to_le_bytes());
    }
    let at = huge
        .windows(pattern.len())
        .position(|w| w == pattern)
        .unwrap();
    huge[at..at + 8].copy_from_slice(&(1u64 << 31).to_le_bytes());
    let huge_path = dir.join("huge.usdc");
    std::fs::write(&huge_path, &huge).unwrap();
    let whole = std::fs::read(fixture("transforms.usdc")).unwrap();
    let cut = dir.join("cut.usdc");
    std::fs::write(&cut, &whole[..whole.len() / 2]).unwrap();
    let nan = dir.join("nan.usda");
    std::fs::write(
        &nan,
        "#usda 1.0\ndef BasisCurves \"H\"\n{\n    uniform token type = \"linear\"\n    int[] curveVertexCounts = [2]\n    point3f[] points = [(0, 0, 0), (nan, 0, 1)]\n}\n",
    )
    .unwrap();
    let out = dir.join("out").display().to_string();
    for (path, needle) in [
        (huge_path, "declares 2147483648"),
        (cut, "not a readable USD file"),
        (nan, "not a finite number"),
    ] {
        let groom = path.to_str().unwrap();
        assert_refused(&["groom", "info", groom], needle);
        let mut render = vec!["render", "--groom", groom];
        render.extend(B);
        render.extend(["--out", &out]);
        assert_refused(&render, needle);
        assert_refused(
            &[
                "render", "--method", "path", "--spp", "1", "--groom", groom, "--out", &out,
            ],
            needle,
        );
    }
    assert!(!dir.join("out").exists());
}
