//! The fiber commands end to end: bad parameters get one clear error line and a non-zero exit;
//! good ones write every file docs/conventions.md §5 promises.

mod common;

use common::cuticle;

fn assert_one_clear_error(args: &[&str], needle: &str) {
    common::assert_refused(args, needle);
}

#[test]
fn bad_fiber_parameters_are_refused_with_one_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    assert_one_clear_error(&["lobes", "--beta", "-0.1", "--out", out], "beta");
    assert_one_clear_error(
        &["lobes", "--eta", "1", "--out", out],
        "eta must be a finite number in (1, 10], got 1",
    );
    assert_one_clear_error(
        &["lobes", "--beta", "NaN", "--out", out],
        "beta must be a finite number in [0.0001, 1], got NaN",
    );
    assert_one_clear_error(&["lobes", "--mu-a", "0.1,-2,0.3", "--out", out], "mu_a");
    assert_one_clear_error(&["lobes", "--theta-i", "2", "--out", out], "theta_i");
    assert_one_clear_error(&["furnace", "--model", "fancy", "--out", out], "fancy");
    assert_one_clear_error(&["furnace", "--alpha-deg", "45", "--out", out], "alpha");
    assert!(
        common::names(dir.path()).is_empty(),
        "a refused command wrote files"
    );
}

#[test]
fn lobes_writes_images_csv_json_and_the_sampling_comparison() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lobes");
    let run = cuticle(&[
        "lobes",
        "--model",
        "deon2011",
        "--width",
        "40",
        "--samples",
        "20000",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for name in ["R", "TT", "TRT", "TRRT", "rest", "total"] {
        assert!(
            out.join(format!("{name}.exr")).is_file() && out.join(format!("{name}.png")).is_file(),
            "{name}"
        );
    }
    for name in [
        "azimuthal.csv",
        "compare.png",
        "sampled_total.exr",
        "azimuthal.svg",
    ] {
        assert!(out.join(name).is_file(), "{name}");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("lobes.json")).unwrap()).unwrap();
    let energy = &json["energy"];
    let lobes: f64 = ["R", "TT", "TRT", "TRRT", "rest"]
        .iter()
        .map(|l| energy[l].as_f64().unwrap())
        .sum();
    assert!((lobes - energy["total"].as_f64().unwrap()).abs() < 1e-9);
    assert!(energy["total"].as_f64().unwrap() > 0.3 && energy["total"].as_f64().unwrap() < 1.0);
    assert_eq!(json["params"]["model"], "deon2011");
}

#[test]
fn furnace_reports_a_lossless_fiber_as_white() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let run = cuticle(&[
        "furnace",
        "--model",
        "deon2011",
        "--mu-a",
        "0",
        "--alpha-deg",
        "0",
        "--theta-i",
        "0.3,1.2",
        "--out",
        out,
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("furnace.json")).unwrap()).unwrap();
    let results = json["results"].as_array().unwrap();
    assert_eq!(results.len(), 2);
    for r in results {
        assert!((r["albedo"].as_f64().unwrap() - 1.0).abs() < 0.005, "{r}");
    }
}

/// `--model` offers every model of the fiber crate's registry under its name (Chiang 2016 and
/// the paper's non-separable form included), and the record names the model it ran.
#[test]
fn every_registry_model_runs_the_furnace() {
    for name in cuticle_fiber::ModelId::names() {
        let dir = tempfile::tempdir().unwrap();
        let run = cuticle(&[
            "furnace",
            "--model",
            name,
            "--mu-a",
            "0",
            "--alpha-deg",
            "0",
            "--theta-i",
            "0.5",
            "--out",
            dir.path().to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{name}: {}", common::stderr(&run));
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.path().join("furnace.json")).unwrap())
                .unwrap();
        assert_eq!(json["params"]["model"], name);
        let albedo = json["results"][0]["albedo"].as_f64().unwrap();
        assert!(albedo > 0.5 && albedo < 1.05, "{name}: albedo {albedo}");
    }
}
