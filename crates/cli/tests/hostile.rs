//! Issue 9's attack, kept: every command's numeric flags and every scene key × {NaN, ±∞, 0,
//! negative, huge}, hostile scene and lights files, impossible sizes, a resumed sweep with other
//! settings, and outputs over earlier outputs. Each refusal is one clear line naming the flag or
//! key and its value, a non-zero exit, no panic, and nothing written.

mod common;

use common::{B, assert_refused, assert_runs, cuticle, names};
use std::path::Path;

/// Hostile values a real flag never accepts.
const NON_FINITE: [&str; 5] = ["NaN", "inf", "-inf", "1e300", "-1e300"];

/// Runs each `(args, needle)` refused, then checks nothing landed in `dir`'s `out`.
fn refuse_all(dir: &Path, rows: &[(Vec<String>, String)]) {
    for (args, needle) in rows {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_refused(&args, needle);
        assert!(
            !dir.join("out").exists(),
            "{args:?} wrote its output folder"
        );
    }
}

/// `command... FLAG VALUE --out DIR/out` for every value, each refused naming `name`.
fn flag_rows(
    dir: &Path,
    command: &[impl AsRef<str>],
    flag: &str,
    values: &[&str],
    name: &str,
) -> Vec<(Vec<String>, String)> {
    let out = dir.join("out").display().to_string();
    values
        .iter()
        .map(|v| {
            let mut args: Vec<String> = command.iter().map(|s| s.as_ref().to_string()).collect();
            // `--flag=VALUE`: the parser would read `-inf` after a space as short flags.
            args.extend([format!("{flag}={v}"), "--out".into(), out.clone()]);
            (args, name.to_string())
        })
        .collect()
}

/// `a` then `b`, owned.
fn with(a: &[impl AsRef<str>], b: &[&str]) -> Vec<String> {
    a.iter()
        .map(|s| s.as_ref().to_string())
        .chain(b.iter().map(|s| s.to_string()))
        .collect()
}

#[test]
fn fiber_flags_refuse_hostile_numbers_naming_the_flag() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let mut rows = Vec::new();
    for command in [["lobes"], ["furnace"]] {
        let c = &command[..];
        let f = |flag, extra: &[&str], name| {
            let values: Vec<&str> = NON_FINITE.iter().chain(extra).copied().collect();
            flag_rows(dir, c, flag, &values, name)
        };
        rows.extend(f("--beta", &["0", "-1", "1e-9", "100"], "beta"));
        rows.extend(f("--eta", &["0", "-1", "1", "1e160"], "eta"));
        rows.extend(f("--alpha-deg", &["45", "-90"], "alpha_deg"));
        rows.extend(f("--mu-a", &["-1", "0.1,nan,0.3", "2000"], "mu_a"));
        rows.extend(f("--eumelanin", &["-1"], "eumelanin"));
        rows.extend(f("--pheomelanin", &["-1"], "pheomelanin"));
        rows.extend(flag_rows(
            dir,
            c,
            "--iterations",
            &["0", "100000"],
            "iterations",
        ));
        rows.extend(flag_rows(
            dir,
            c,
            "--iterations",
            &["-1", "1e300"],
            "invalid value",
        ));
    }
    let lobes = &["lobes"][..];
    rows.extend(flag_rows(dir, lobes, "--theta-i", &NON_FINITE, "theta_i"));
    rows.extend(flag_rows(
        dir,
        lobes,
        "--theta-i",
        &["1.5708", "-2"],
        "theta_i",
    ));
    rows.extend(flag_rows(
        dir,
        lobes,
        "--width",
        &["0", "4", "10", "1000000"],
        "width",
    ));
    rows.extend(flag_rows(
        dir,
        lobes,
        "--samples",
        &["18446744073709551615", "1000000000000"],
        "samples",
    ));
    rows.extend(flag_rows(
        dir,
        lobes,
        "--samples",
        &["1e12", "-1"],
        "invalid value",
    ));
    let furnace = &["furnace"][..];
    rows.extend(flag_rows(
        dir,
        furnace,
        "--theta-i",
        &["0.5,nan", "inf", "2"],
        "theta_i",
    ));
    rows.extend(flag_rows(
        dir,
        furnace,
        "--betas",
        &["0.04,nan", "0", "1e-9", "inf"],
        "beta",
    ));
    refuse_all(dir, &rows);
}

#[test]
fn sim_sweep_env_validate_and_groom_flags_refuse_hostile_numbers() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let mut rows = Vec::new();
    let sim = &["sim"][..];
    for (flag, extra, name) in [
        ("--theta-i", &["2"][..], "theta_i"),
        ("--alpha-deg", &["45"], "alpha_deg"),
        ("--beta", &["0", "-1", "100"], "beta"),
        ("--eta", &["1", "0.5"], "eta"),
        ("--mu-a", &["-1", "nan,0,0"], "mu_a"),
    ] {
        let values: Vec<&str> = NON_FINITE.iter().chain(extra).copied().collect();
        rows.extend(flag_rows(dir, sim, flag, &values, name));
    }
    rows.extend(flag_rows(
        dir,
        sim,
        "--rays",
        &["0", "18446744073709551615"],
        "rays",
    ));
    let sweep = with(&["sweep", "--grid", "small"], &[]);
    rows.extend(flag_rows(
        dir,
        &sweep,
        "--rays",
        &["0", "10000000000"],
        "rays",
    ));
    rows.extend(flag_rows(
        dir,
        &sweep,
        "--shard",
        &["0/0", "3/2", "x"],
        "shard",
    ));
    let fit = &["env", "fit"][..];
    rows.extend(flag_rows(
        dir,
        fit,
        "--rotate-deg",
        &NON_FINITE,
        "rotate_deg",
    ));
    rows.extend(flag_rows(
        dir,
        fit,
        "--preview-width",
        &["0", "20000", "1000000"],
        "preview_width",
    ));
    rows.extend(flag_rows(
        dir,
        fit,
        "--lights",
        &["0", "513", "100000"],
        "lights",
    ));
    rows.extend(flag_rows(
        dir,
        fit,
        "--max-iterations",
        &["18446744073709551615"],
        "iterations",
    ));
    rows.extend(flag_rows(dir, fit, "--fit-width", &["0"], "fit grid"));
    let sim_dir = dir.join("missing").display().to_string();
    let validate = with(&["validate", "--sim", &sim_dir], &[]);
    rows.extend(flag_rows(
        dir,
        &validate,
        "--sheet-samples",
        &["0", "18446744073709551615"],
        "sheet_samples",
    ));
    let make = &["groom", "make"][..];
    rows.extend(flag_rows(
        dir,
        make,
        "--strands",
        &["0", "2000001", "18446744073709551615"],
        "strands",
    ));
    let bench = &["bench", "render"][..];
    rows.extend(flag_rows(
        dir,
        bench,
        "--frames",
        &["0", "1000000000"],
        "frames",
    ));
    rows.extend(flag_rows(
        dir,
        bench,
        "--strands",
        &["0", "2000001"],
        "strands",
    ));
    rows.extend(flag_rows(dir, bench, "--width", &["0", "16385"], "width"));
    refuse_all(dir, &rows);
}

#[test]
fn render_flags_refuse_hostile_numbers_naming_the_key() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let render = with(&["render"], &B);
    let mut rows = Vec::new();
    for (flag, extra, name) in [
        ("--eta", &["1", "0", "-1", "1e160"][..], "eta"),
        ("--alpha-r-deg", &["45"], "alpha_r_deg"),
        ("--beta-r-deg", &["0", "-1", "90"], "beta_r_deg"),
        ("--mu-a", &["-1", "nan,0.5,0.9", "0.3,inf,0.9"], "mu_a"),
        // Issue 9 #1: the scene took [0.5, 2], the exact model (1/√2, √2).
        (
            "--eccentricity",
            &["1.42", "0.5", "0.7", "2", "0"],
            "eccentricity",
        ),
        (
            "--caustic-width-deg",
            &["0", "-1", "180"],
            "caustic_width_deg",
        ),
    ] {
        let values: Vec<&str> = NON_FINITE.iter().chain(extra).copied().collect();
        rows.extend(flag_rows(dir, &render, flag, &values, name));
    }
    let brute = with(&render, &["--method", "brute"]);
    rows.extend(flag_rows(
        dir,
        &brute,
        "--eccentricity",
        &["1.42", "0.6"],
        "eccentricity",
    ));
    for (flag, bad, name) in [
        (
            "--width",
            &["0", "16385", "18446744073709551615"][..],
            "width",
        ),
        ("--height", &["0", "100000"], "height"),
        ("--supersampling", &["0", "9"], "supersampling"),
        ("--quadrature", &["0", "1", "100000"], "quadrature"),
        ("--brute-grid", &["0", "65"], "brute_grid"),
    ] {
        // Without B, which sets some of these flags already.
        rows.extend(flag_rows(dir, &["render"], flag, bad, name));
        rows.extend(flag_rows(
            dir,
            &["render"],
            flag,
            &["-1", "1e300"],
            "invalid value",
        ));
    }
    // `--lights` takes a count or a lights file.
    rows.extend(flag_rows(
        dir,
        &["render"],
        "--lights",
        &["0", "513", "100000"],
        "lights",
    ));
    rows.extend(flag_rows(
        dir,
        &["render"],
        "--lights",
        &["-1", "1e300"],
        "cannot read",
    ));
    // `--strands` appears in B: the parser refuses it twice, so these go without B.
    let plain = &["render", "--width", "32", "--height", "24"][..];
    rows.extend(flag_rows(
        dir,
        plain,
        "--strands",
        &["0", "2000001"],
        "strands",
    ));
    refuse_all(dir, &rows);
}

/// A TOML value for each hostile number.
const TOML_NON_FINITE: [&str; 5] = ["nan", "inf", "-inf", "1e300", "-1e300"];

#[test]
fn scene_keys_refuse_hostile_numbers_naming_the_key() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let camera = |fov: &str, eye: &str, target: &str, up: &str| {
        format!("[camera]\nfov_deg = {fov}\neye = {eye}\ntarget = {target}\nup = {up}\n")
    };
    let ok_eye = "[0.0, -60.0, 10.0]";
    let ok_target = "[0.0, 0.0, 10.0]";
    let ok_up = "[0.0, 0.0, 1.0]";
    let mut scenes: Vec<(String, &str)> = Vec::new();
    for v in TOML_NON_FINITE {
        for (key, needle) in [
            ("env_rotate_deg", "env_rotate_deg"),
            ("[hair]\neta", "eta"),
            ("[hair]\nalpha_r_deg", "alpha_r_deg"),
            ("[hair]\nbeta_r_deg", "beta_r_deg"),
            ("[hair]\neccentricity", "eccentricity"),
            ("[hair]\ncaustic_width_deg", "caustic_width_deg"),
            ("[hair]\ncaustic_fade", "caustic_fade"),
            ("[hair]\nd_b", "d_b"),
            ("[shadows]\ndensity", "shadows.density"),
            ("[shadows]\ncutoff", "shadows.cutoff"),
        ] {
            scenes.push((format!("{key} = {v}\n"), needle));
        }
        scenes.push((format!("[hair]\nmu_a = [{v}, 0.5, 0.9]\n"), "mu_a"));
        scenes.push((
            format!("[hair]\ndefault_mu_a = [0.3, 0.5, {v}]\n"),
            "default_mu_a",
        ));
        scenes.push((camera(v, ok_eye, ok_target, ok_up), "camera.fov_deg"));
        let eye = format!("[{v}, 60.0, 10.0]");
        scenes.push((camera("30.0", &eye, ok_target, ok_up), "camera.eye"));
        let up = format!("[0.0, {v}, 1.0]");
        scenes.push((camera("30.0", ok_eye, ok_target, &up), "camera.up"));
    }
    for fov in ["0.0", "180.0", "360.0", "-35.0"] {
        scenes.push((camera(fov, ok_eye, ok_target, ok_up), "camera.fov_deg"));
    }
    scenes.extend([
        (camera("30.0", ok_target, ok_target, ok_up), "must differ"),
        (
            camera("30.0", ok_eye, ok_target, "[0.0, 0.0, 0.0]"),
            "camera.up",
        ),
        (
            camera("30.0", ok_eye, ok_target, "[0.0, 1.0, 0.0]"),
            "camera.up",
        ),
        (
            "[hair]\nmu_a = [0.3, 0.5, 0.9, 1.0]\n".into(),
            "invalid length 4",
        ),
        ("[hair]\nmu_a = [0.3, 0.5]\n".into(), "invalid length 2"),
        ("[hair]\nmu_a = [nan, 0.5, 0.9]\n".into(), "got NaN"),
        ("width = 0\n".into(), "width"),
        ("height = 9223372036854775807\n".into(), "height"),
        ("width = -1\n".into(), "invalid value"),
        ("strands = 0\n".into(), "strands"),
        ("lights = 100000\n".into(), "lights"),
        ("quadrature = 1\n".into(), "quadrature"),
        ("supersampling = 0\n".into(), "supersampling"),
        ("brute_grid = 1000\n".into(), "brute_grid"),
        ("[shadows]\nresolution = 0\n".into(), "shadows.resolution"),
        ("[shadows]\ndensity = -1.0\n".into(), "shadows.density"),
        ("colour = 3\n".into(), "unknown field"),
        ("width = \"wide\"\n".into(), "line 1 column 9"),
        ("[[[\n".into(), "line 1"),
    ]);
    let out = dir.join("out").display().to_string();
    for (i, (text, needle)) in scenes.iter().enumerate() {
        let path = dir.join(format!("scene{i}.toml"));
        std::fs::write(&path, text).unwrap();
        let scene = path.display().to_string();
        let mut args = vec!["render", "--scene", &scene, "--out", &out];
        // B's small sizes, unless the scene sets what a flag would override.
        if !["width", "height", "strands", "lights", "supersampling"]
            .iter()
            .any(|k| text.starts_with(k))
        {
            args.extend(B);
        }
        let err = assert_refused(&args, needle);
        if text.starts_with("width = \"") || text.starts_with("[[[") {
            assert!(err.contains(&scene), "a parse error names the file: {err}");
        }
    }
    assert!(!dir.join("out").exists());
}

#[test]
fn hostile_lights_files_are_refused_naming_the_light() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let light = |direction: &str, bandwidth: &str, coefficient: &str| {
        format!(
            r#"{{"direction": {direction}, "bandwidth": {bandwidth}, "coefficient": {coefficient}}}"#
        )
    };
    let good = light("[0, 1, 0]", "0.5", "[1, 1, 1]");
    let files: Vec<(String, &str)> = vec![
        (
            format!(
                r#"{{"lights": [{good}, {}]}}"#,
                light("[0, 1, 0]", "0", "[1, 1, 1]")
            ),
            "light 1: bandwidth",
        ),
        (
            format!(
                r#"{{"lights": [{}]}}"#,
                light("[0, 1, 0]", "1e300", "[1, 1, 1]")
            ),
            "light 0: bandwidth",
        ),
        (
            format!(
                r#"{{"lights": [{}]}}"#,
                light("[0, 0, 0]", "0.5", "[1, 1, 1]")
            ),
            "light 0: direction",
        ),
        (
            format!(
                r#"{{"lights": [{}]}}"#,
                light("[0, 1, 0]", "0.5", "[1e308, 1, 1]")
            ),
            "light 0: coefficient",
        ),
        (
            format!(
                r#"{{"lights": [{}]}}"#,
                light("[0, 1, 0]", "0.5", "[1, -1, 1]")
            ),
            "light 0: coefficient",
        ),
        (r#"{"lights": []}"#.into(), "1 to 512 lights"),
        (
            format!(r#"{{"lights": [{}]}}"#, vec![good.as_str(); 600].join(",")),
            "1 to 512 lights, got 600",
        ),
        (r#"{"lights": "many"}"#.into(), "not a list of lights"),
        (r#"{"light": []}"#.into(), "no \"lights\" array"),
        ("not json".into(), "is not JSON"),
    ];
    let out = dir.join("out").display().to_string();
    for (i, (text, needle)) in files.iter().enumerate() {
        let path = dir.join(format!("lights{i}.json"));
        std::fs::write(&path, text).unwrap();
        let lights = path.display().to_string();
        let mut args = with(&["render"], &B[..8]);
        args.extend(["--lights".into(), lights, "--out".into(), out.clone()]);
        assert_refused(&args.iter().map(String::as_str).collect::<Vec<_>>(), needle);
    }
    assert!(!dir.join("out").exists());
}

#[test]
fn sizes_beyond_memory_are_refused_before_allocating() {
    // CUTICLE_MEMORY_LIMIT is 4 GB in these tests (common::cuticle).
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out").display().to_string();
    for args in [
        vec![
            "render", "--width", "16384", "--height", "16384", "--out", &out,
        ],
        vec![
            "render",
            "--width",
            "4096",
            "--height",
            "4096",
            "--supersampling",
            "8",
            "--out",
            &out,
        ],
        vec!["render", "--strands", "2000000", "--out", &out],
        vec![
            "render",
            "--method",
            "brute",
            "--brute-grid",
            "64",
            "--out",
            &out,
        ],
        vec!["bench", "render", "--strands", "2000000", "--out", &out],
        vec![
            "groom",
            "make",
            "--preset",
            "curly",
            "--strands",
            "2000000",
            "--out",
            &out,
        ],
    ] {
        let err = assert_refused(&args, "of memory");
        assert!(err.contains("4.0 GB is available"), "{err}");
    }
    assert!(!tmp.path().join("out").exists());
}

#[test]
fn messages_stay_short_and_say_each_cause_once() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out").display().to_string();
    let err = assert_refused(&["lobes", "--eta", "1e300", "--out", &out], "got 1e300");
    assert!(err.len() < 120, "{err}");
    let missing = tmp.path().join("none.toml").display().to_string();
    let err = assert_refused(
        &["render", "--scene", &missing, "--out", &out],
        "cannot read scene file",
    );
    assert_eq!(err.matches("No such file").count(), 1, "{err}");
    // A sweep grid with β = 1e300 is refused by its range, not by the file system.
    let grid = tmp.path().join("grid.json");
    std::fs::write(
        &grid,
        r#"[{"theta_i": 0.5, "alpha_deg": -2, "beta": 1e300, "eta": 1.55, "mu_a": 0.25}]"#,
    )
    .unwrap();
    let grid = grid.display().to_string();
    let err = assert_refused(&["sweep", "--grid", &grid, "--out", &out], "beta");
    assert!(
        err.contains("got 1e300") && !err.contains("too long"),
        "{err}"
    );
}

/// A reader that closes the pipe early (`cuticle … | head -1`) ends the command by SIGPIPE, as
/// any Unix filter, and not by a panic on the broken pipe.
#[test]
fn a_closed_stdout_ends_the_command_without_a_panic() {
    use std::os::unix::process::ExitStatusExt;
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g");
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cuticle"))
        .args(["groom", "make", "--strands", "5", "--out"])
        .arg(&out)
        .stdout(writer)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(
        run.status.signal(),
        Some(libc::SIGPIPE),
        "{:?}: {err}",
        run.status
    );
}

#[test]
fn groom_make_writes_its_groom_and_record_as_a_set() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g.json");
    let shown = assert_runs(&[
        "groom",
        "make",
        "--strands",
        "50",
        "--out",
        out.to_str().unwrap(),
    ]);
    // Issue 9 #16: `--out g.json` once meant the record overwrote the .hair data.
    assert_eq!(names(&out), ["groom.hair", "groom.json"]);
    assert!(shown.contains("groom.hair"), "{shown}");
    let info = assert_runs(&["groom", "info", out.join("groom.hair").to_str().unwrap()]);
    assert!(info.contains("50 strands"), "{info}");
}

#[test]
fn a_resumed_sweep_with_other_settings_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let grid = tmp.path().join("grid.json");
    std::fs::write(
        &grid,
        r#"[{"theta_i": 0.5, "alpha_deg": -2, "beta": 0.04, "eta": 1.55, "mu_a": 0.25},
            {"theta_i": 1.0, "alpha_deg": 2, "beta": 0.08, "eta": 1.55, "mu_a": 0}]"#,
    )
    .unwrap();
    let (grid, out) = (grid.display().to_string(), tmp.path().join("sweep"));
    let out = out.to_str().unwrap();
    let sweep = |more: &[&str]| {
        let mut args = vec!["sweep", "--grid", &grid, "--out", out, "--rays", "2000"];
        args.extend(more);
        args.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let run = |args: Vec<String>| cuticle(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(run(sweep(&["--limit", "1"])).status.success());
    for (more, needle) in [
        (&["--rays", "20000"][..], "made with rays 2000"),
        (&["--seed", "9"], "made with seed 1"),
        (&["--png"], "made without --png"),
    ] {
        let mut args = sweep(&[]);
        args.retain(|a| a != "--rays" && a != "2000");
        if !more.contains(&"--rays") {
            args.extend(["--rays".into(), "2000".into()]);
        }
        args.extend(more.iter().map(|s| s.to_string()));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_refused(&args, needle);
    }
    let done = run(sweep(&[]));
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let record: serde_json::Value =
        serde_json::from_slice(&std::fs::read(tmp.path().join("sweep/sweep.json")).unwrap())
            .unwrap();
    assert_eq!(
        (record["skipped"].as_u64(), record["ran"].as_u64()),
        (Some(1), Some(1))
    );
}

#[test]
fn path_tracer_and_bench_trace_flags_refuse_hostile_numbers() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let path = with(&["render"], &B);
    let path = with(&path, &["--method", "path", "--spp", "1"]);
    let mut rows = Vec::new();
    let no_spp: Vec<String> = path[..path.len() - 2].to_vec();
    rows.extend(flag_rows(dir, &no_spp, "--spp", &["0", "1048577"], "spp"));
    rows.extend(flag_rows(
        dir,
        &path,
        "--max-depth",
        &["0", "100001"],
        "max_depth",
    ));
    for model in ["deon2011", "nonseparable", "chiang2016"] {
        let m = with(&path, &["--model", model]);
        let values: Vec<&str> = NON_FINITE.iter().chain(&["0", "2"]).copied().collect();
        let beta = if model == "chiang2016" {
            "--beta-m"
        } else {
            "--beta"
        };
        rows.extend(flag_rows(
            dir,
            &m,
            beta,
            &values,
            &beta[2..].replace('-', "_"),
        ));
        let values: Vec<&str> = NON_FINITE.iter().chain(&["45"]).copied().collect();
        rows.extend(flag_rows(dir, &m, "--alpha-deg", &values, "alpha_deg"));
        let values: Vec<&str> = NON_FINITE.iter().chain(&["-1", "51"]).copied().collect();
        rows.extend(flag_rows(dir, &m, "--eumelanin", &values, "eumelanin"));
        rows.extend(flag_rows(dir, &m, "--pheomelanin", &values, "pheomelanin"));
    }
    let chiang = with(&path, &["--model", "chiang2016"]);
    let values: Vec<&str> = NON_FINITE.iter().chain(&["0", "2"]).copied().collect();
    rows.extend(flag_rows(dir, &chiang, "--beta-n", &values, "beta_n"));
    let values: Vec<&str> = NON_FINITE.iter().chain(&["0", "1"]).copied().collect();
    rows.extend(flag_rows(dir, &path, "--eta", &values, "eta"));
    rows.extend(flag_rows(dir, &path, "--device", &["gpu"], "cpu only"));
    rows.push((
        with(
            &path,
            &[
                "--no-multiple",
                "--out",
                &dir.join("out").display().to_string(),
            ],
        ),
        "--max-depth 1".into(),
    ));
    // Issue 9 #18's kind: `bench trace --spp 0` ran one sample per pixel and said nothing.
    let bench = [
        "bench", "trace", "--groom", "straight", "--width", "32", "--height", "24",
    ];
    rows.extend(flag_rows(dir, &bench, "--spp", &["0", "1048577"], "spp"));
    rows.extend(flag_rows(dir, &bench, "--max-depth", &["0"], "max_depth"));
    rows.extend(flag_rows(
        dir,
        &bench[..6],
        "--height",
        &["0", "16385"],
        "height",
    ));
    refuse_all(dir, &rows);
    // The path tracer's image needs memory as the SRBF renderer's does: refused before
    // allocating, not killed.
    let out = dir.join("out").display().to_string();
    let big = [
        "render", "--method", "path", "--width", "16384", "--height", "16384", "--out", &out,
    ];
    assert!(assert_refused(&big, "of memory").contains("4.0 GB is available"));
}

#[test]
fn the_path_tracer_writes_a_finite_set() {
    // After the lights of a scene were checked (1 to 512), `--method path`, which loads its
    // scene without SRBF lights, was refused with "got 0" whatever its flags.
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("path");
    let mut args = with(&["render"], &B);
    args.extend(
        [
            "--method",
            "path",
            "--spp",
            "2",
            "--max-depth",
            "8",
            "--out",
        ]
        .map(String::from),
    );
    args.push(out.display().to_string());
    assert_runs(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(
        names(&out),
        [
            "coverage.exr",
            "image.exr",
            "image.png",
            "render.json",
            "standard_error.exr"
        ]
    );
    let image = cuticle_light::image_file::read_rgb_exr(&out.join("image.exr")).unwrap();
    assert_eq!((image.width, image.height), (32, 24));
    assert!(image.pixels.iter().any(|p| p.max_element() > 0.0));
}

/// A render folder of `cuticle render` at 32 × 24, then copies of it with one file spoiled.
#[test]
fn compare_refuses_hostile_render_folders_naming_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let good = dir.join("good");
    let mut args = with(&["render", "--device", "cpu"], &B);
    args.extend(["--out".into(), good.display().to_string()]);
    assert_runs(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let spoiled = |name: &str, spoil: &dyn Fn(&Path)| {
        let copy = dir.join(name);
        std::fs::create_dir_all(&copy).unwrap();
        for file in names(&good) {
            std::fs::copy(good.join(&file), copy.join(&file)).unwrap();
        }
        spoil(&copy);
        copy.display().to_string()
    };
    let exr = |w: usize, h: usize, f: &dyn Fn(usize) -> f64| {
        let pixels: Vec<glam::DVec3> = (0..w * h).map(|k| glam::DVec3::splat(f(k))).collect();
        cuticle_light::image_file::exr_bytes(w, h, &pixels).unwrap()
    };
    // An EXR header that claims 100000 × 100000 pixels in a few hundred bytes: compare once
    // tried to allocate 240 GB and aborted.
    let mut claim = exr(4, 4, &|_| 1.0);
    let at = claim.windows(10).position(|w| w == b"dataWindow").unwrap();
    // name\0 "box2i"\0 size(4): then x_min, y_min, x_max, y_max.
    let max = at + b"dataWindow\0box2i\0".len() + 4 + 8;
    claim[max..max + 8]
        .copy_from_slice(&[&99_999i32.to_le_bytes()[..], &99_999i32.to_le_bytes()].concat());
    let cases: Vec<(String, &str)> = vec![
        (
            spoiled("no-record", &|d| {
                std::fs::remove_file(d.join("render.json")).unwrap()
            }),
            "not a complete output of `cuticle render`",
        ),
        (
            spoiled("nan", &|d| {
                let bytes = exr(32, 24, &|k| if k == 33 { f64::NAN } else { 1.0 });
                std::fs::write(d.join("image.exr"), bytes).unwrap()
            }),
            "nan/image.exr: pixel (column 1, row 1) has a non-finite value NaN",
        ),
        (
            spoiled("claim", &|d| {
                std::fs::write(d.join("image.exr"), &claim).unwrap()
            }),
            "claim/image.exr",
        ),
        (
            spoiled("small", &|d| {
                std::fs::write(d.join("image.exr"), exr(16, 12, &|_| 1.0)).unwrap()
            }),
            "B is 16x12, A is 32x24",
        ),
        (
            spoiled("black", &|d| {
                std::fs::write(d.join("image.exr"), exr(32, 24, &|_| 0.0)).unwrap()
            }),
            "ratio A/B and the relative RMSE are undefined",
        ),
        (
            spoiled("png", &|d| {
                std::fs::write(d.join("image.png"), b"not a png").unwrap()
            }),
            "png/image.png",
        ),
        (
            spoiled("garbage", &|d| {
                std::fs::write(d.join("image.exr"), b"v/1\x01garbage").unwrap()
            }),
            "garbage/image.exr",
        ),
        (dir.join("missing").display().to_string(), "missing"),
    ];
    let out = dir.join("out").display().to_string();
    let good = good.display().to_string();
    for (b, needle) in &cases {
        assert_refused(&["compare", &good, b, "--out", &out], needle);
    }
    assert_refused(
        &[
            "compare", &good, &good, "--minus", &good, &good, "--out", &out,
        ],
        "undefined",
    );
    let err = assert_refused(
        &[
            "compare",
            &good,
            &good,
            "--min-coverage=1e300",
            "--out",
            &out,
        ],
        "got 1e300",
    );
    assert!(err.len() < 80, "{err}");
    assert!(!dir.join("out").exists());
    assert_runs(&["compare", &good, &good, "--out", &out]);
}

#[test]
fn view_refuses_what_would_hang_or_exhaust_it_before_opening_a_window() {
    // No display is needed: each is refused before the window opens.
    let tmp = tempfile::tempdir().unwrap();
    let shot = tmp.path().join("shot.png").display().to_string();
    let view = |more: &[&str]| {
        let mut args = vec!["view", "--screenshot", &shot];
        args.extend(more);
        args.into_iter().map(String::from).collect::<Vec<_>>()
    };
    for (more, needle) in [
        // Waited a billion frames after the first full one: never wrote, never exited.
        (&["--after-frames", "1001"][..], "after_frames"),
        (&["--width", "16384", "--height", "16384"], "of memory"),
        (&["--strands", "2000000"], "of memory"),
        (&["--method", "path"], "--method path"),
        (&["--eta", "nan"], "eta"),
    ] {
        let args = view(more);
        assert_refused(&args.iter().map(String::as_str).collect::<Vec<_>>(), needle);
    }
    assert!(!tmp.path().join("shot.png").exists());
}

// Issue 57: the second attack, on the newer surfaces. Each test reproduced its defect first.

/// A crafted file of ../shared/data/hostile, or `None` (said plainly) where the data folder is
/// not beside the checkout.
fn hostile(name: &str) -> Option<String> {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/hostile"
    ))
    .join(name);
    if path.is_file() {
        Some(path.display().to_string())
    } else {
        eprintln!("skipped: {} is not here", path.display());
        None
    }
}

/// A render of B into `dir/name` with `more` flags; its folder.
fn small_render(dir: &Path, name: &str, more: &[&str]) -> String {
    let out = dir.join(name).display().to_string();
    let mut args = with(&["render", "--device", "cpu"], &B);
    args.extend(more.iter().map(|s| s.to_string()));
    args.extend(["--out".into(), out.clone()]);
    assert_runs(&args.iter().map(String::as_str).collect::<Vec<_>>());
    out
}

/// #1: "memory allocation of 70368744177664 bytes failed", exit 134, from every reader of EXR.
#[test]
fn issue57_a_crafted_dwaa_exr_is_refused_by_every_reader() {
    let Some(dwaa) = hostile("dwaa_dc_count_2e45.exr") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let out = dir.join("out").display().to_string();
    let good = small_render(dir, "good", &[]);
    let spoiled = dir.join("spoiled");
    std::fs::create_dir(&spoiled).unwrap();
    for file in names(Path::new(&good)) {
        std::fs::copy(Path::new(&good).join(&file), spoiled.join(&file)).unwrap();
    }
    std::fs::copy(&dwaa, spoiled.join("image.exr")).unwrap();
    let spoiled = spoiled.display().to_string();
    let render = with(&["render", "--env", &dwaa], &B);
    let path = with(&render, &["--method", "path", "--spp", "1"]);
    let rows: Vec<Vec<String>> = vec![
        with(&["env", "fit", "--env", &dwaa, "--lights", "2"], &[]),
        render,
        path,
        with(&["compare", &good, &spoiled], &[]),
        with(&["compare", &good, &good, "--coverage", &dwaa], &[]),
        with(
            &[
                "bench", "trace", "--groom", "straight", "--width", "32", "--height", "24",
                "--spp", "1", "--env", &dwaa,
            ],
            &[],
        ),
    ];
    for mut args in rows {
        args.extend(["--out".into(), out.clone()]);
        assert_refused(
            &args.iter().map(String::as_str).collect::<Vec<_>>(),
            "DWAA compression is not read",
        );
    }
    assert!(!dir.join("out").exists());
}

/// #2 and #11: a groom at 1e20 panicked in the BVH builder; one at 3e38 gave `groom info`
/// lengths of inf and bounds of null. One range (GroomParts::MAX_COORDINATE), checked on read.
#[test]
fn issue57_grooms_beyond_the_coordinate_range_are_refused_on_read() {
    let (Some(x_1e20), Some(points_3e38)) = (
        hostile("bangs_x_1e20.hair"),
        hostile("bangs_points_3e38.hair"),
    ) else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out").display().to_string();
    let small = ["--width", "32", "--height", "24", "--supersampling", "1"];
    for groom in [&x_1e20, &points_3e38] {
        let path = with(
            &["render", "--method", "path", "--spp", "2", "--groom", groom],
            &small,
        );
        let srbf = with(&["render", "--lights", "4", "--groom", groom], &small);
        let bench = with(
            &[
                "bench", "trace", "--width", "32", "--height", "24", "--spp", "1",
            ],
            &["--groom", groom],
        );
        for mut args in [path, srbf, bench] {
            args.extend(["--out".into(), out.clone()]);
            assert_refused(
                &args.iter().map(String::as_str).collect::<Vec<_>>(),
                "the largest a groom may hold",
            );
        }
        for info in [
            vec!["groom", "info", groom],
            vec!["groom", "info", "--json", groom],
        ] {
            assert_refused(&info, "the largest a groom may hold");
        }
    }
    assert!(!tmp.path().join("out").exists());
}

/// A one-configuration sweep of `rays` paths with `seed` into `dir`; its configuration folder.
fn one_config_sweep(dir: &Path, seed: &str) -> std::path::PathBuf {
    let grid = dir.with_extension("grid.json");
    std::fs::write(
        &grid,
        r#"[{"theta_i": 0.5, "alpha_deg": -2, "beta": 0.08, "eta": 1.55, "mu_a": 0.2}]"#,
    )
    .unwrap();
    assert_runs(&[
        "sweep",
        "--grid",
        grid.to_str().unwrap(),
        "--rays",
        "20000",
        "--seed",
        seed,
        "--out",
        dir.to_str().unwrap(),
    ]);
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.is_dir() && !p.file_name().unwrap().to_string_lossy().starts_with('.'))
        .unwrap()
}

/// Rewrites `"params"."key"` of `config`/sim.json.
fn edit_sim_json(config: &Path, key: &str, value: serde_json::Value) {
    let path = config.join("sim.json");
    let mut record: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    record["params"][key] = value;
    std::fs::write(&path, serde_json::to_vec_pretty(&record).unwrap()).unwrap();
}

/// #3: `validate --noise` with runs on two grids panicked ("two runs on different grids");
/// #10: θ_i = 10 in sim.json validated to energies of 0, θ_i = 1e308 to a report of NaN.
#[test]
fn issue57_validate_refuses_other_grids_and_parameters_outside_their_ranges() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    one_config_sweep(&a, "1");
    let twin = one_config_sweep(&b, "2");
    edit_sim_json(&twin, "grid", serde_json::json!([20, 5]));
    let out = tmp.path().join("out").display().to_string();
    let (a_s, b_s) = (a.display().to_string(), b.display().to_string());
    assert_refused(
        &["validate", "--sim", &a_s, "--noise", &b_s, "--out", &out],
        "the second run needs the same grid",
    );
    for (key, value, needle) in [
        ("theta_i", serde_json::json!(10.0), "theta_i must be"),
        ("theta_i", serde_json::json!(1e308), "theta_i must be"),
        ("beta", serde_json::json!(0.0), "beta must be"),
        ("eta", serde_json::json!(0.5), "eta must be"),
        ("alpha_deg", serde_json::json!(90.0), "alpha_deg must be"),
        ("mu_a", serde_json::json!([0.2, -1.0, 0.2]), "mu_a must be"),
    ] {
        let config = one_config_sweep(&tmp.path().join(format!("{key}{value}")), "1");
        edit_sim_json(&config, key, value);
        let sim = config.parent().unwrap().display().to_string();
        assert_refused(&["validate", "--sim", &sim, "--out", &out], needle);
    }
    assert!(!tmp.path().join("out").exists());
}

/// #5 and #12: a map or constant beyond what a light may be (3e38) rendered +inf pixels with
/// exit 0, and `env fit` wrote coefficients `render --lights` refused. One bound
/// (cuticle_light::MAX_RADIANCE = MAX_COEFFICIENT) at both ends.
#[test]
fn issue57_radiance_beyond_a_lights_bound_is_refused_where_it_is_read() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out").display().to_string();
    let path = with(
        &[
            "render", "--method", "path", "--spp", "4", "--mu-a", "0", "--eta", "1.01",
        ],
        &[
            "--max-depth",
            "50",
            "--strands",
            "30",
            "--width",
            "48",
            "--height",
            "32",
        ],
    );
    let mut rows: Vec<(Vec<String>, &str)> = Vec::new();
    for env in [
        "constant:3e38",
        "constant:3.4028235e38",
        "constant:1,1,2e20",
    ] {
        rows.push((with(&path, &["--env", env]), "constant takes"));
    }
    if let Some(map) = hostile("radiance_3e38.exr") {
        rows.push((
            with(&path, &["--env", &map]),
            "above the 1e20 a map may hold",
        ));
        rows.push((
            with(&["env", "fit", "--lights", "4", "--env", &map], &[]),
            "above the 1e20 a map may hold",
        ));
    }
    for (mut args, needle) in rows {
        args.extend(["--out".into(), out.clone()]);
        assert_refused(&args.iter().map(String::as_str).collect::<Vec<_>>(), needle);
    }
    assert!(!tmp.path().join("out").exists());
    // The brightest map a fit reads gives lights a render reads.
    let bright: Vec<glam::DVec3> = (0..32 * 16)
        .map(|k| glam::DVec3::splat(if k == 100 { 1e20 } else { 1.0 }))
        .collect();
    std::fs::write(
        tmp.path().join("bright.exr"),
        cuticle_light::image_file::exr_bytes(32, 16, &bright).unwrap(),
    )
    .unwrap();
    let fit = tmp.path().join("fit").display().to_string();
    let exr = tmp.path().join("bright.exr").display().to_string();
    let run = cuticle(&["env", "fit", "--env", &exr, "--lights", "4", "--out", &fit]);
    if run.status.success() {
        let lights = tmp.path().join("fit/lights.json").display().to_string();
        let mut args = with(&["render", "--device", "cpu"], &B[..8]);
        args.extend(["--lights".into(), lights, "--out".into(), out.clone()]);
        assert_runs(&args.iter().map(String::as_str).collect::<Vec<_>>());
    } else {
        // Refused by the fit itself, naming the light: never written for render to refuse.
        assert_refused(
            &["env", "fit", "--env", &exr, "--lights", "4", "--out", &fit],
            "light",
        );
    }
}

/// #6: `compare A0 B --minus A B0` (swapped) wrote ratios of −2; negative pixels in A's
/// image.exr were taken while a negative B was refused.
#[test]
fn issue57_compare_refuses_negative_radiance_on_either_side() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let full = small_render(dir, "full", &[]);
    let direct = small_render(dir, "direct", &["--no-multiple"]);
    let out = dir.join("out").display().to_string();
    assert_refused(
        &[
            "compare", &direct, &full, "--minus", &full, &direct, "--out", &out,
        ],
        "are A0 and B0 swapped",
    );
    let negative = dir.join("negative");
    std::fs::create_dir(&negative).unwrap();
    for file in names(Path::new(&full)) {
        std::fs::copy(Path::new(&full).join(&file), negative.join(&file)).unwrap();
    }
    let mut image = cuticle_light::image_file::read_rgb_exr(&negative.join("image.exr")).unwrap();
    image.pixels[40] = glam::DVec3::new(0.5, -3.0, 0.5);
    std::fs::write(
        negative.join("image.exr"),
        cuticle_light::image_file::exr_bytes(image.width, image.height, &image.pixels).unwrap(),
    )
    .unwrap();
    let negative = negative.display().to_string();
    for (a, b) in [(&negative, &full), (&full, &negative)] {
        assert_refused(
            &["compare", a, b, "--out", &out],
            "pixel (column 8, row 1) is negative",
        );
    }
    assert!(!dir.join("out").exists());
    assert_runs(&["compare", &full, &direct, "--out", &out]);
}

/// #7: `sweep` added its set to a render's output and to a folder of notes.
#[test]
fn issue57_sweep_writes_only_into_a_sweeps_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let render = small_render(tmp.path(), "render", &[]);
    let notes = tmp.path().join("notes");
    std::fs::create_dir(&notes).unwrap();
    std::fs::write(notes.join("notes.txt"), "mine").unwrap();
    let sweep = |out: &str| {
        vec![
            "sweep", "--grid", "small", "--rays", "100", "--limit", "1", "--out", out,
        ]
        .into_iter()
        .map(String::from)
        .collect::<Vec<_>>()
    };
    let before = names(Path::new(&render));
    for (folder, holds) in [
        (render.as_str(), ".exr"),
        (notes.to_str().unwrap(), "notes.txt"),
    ] {
        let args = sweep(folder);
        let err = assert_refused(
            &args.iter().map(String::as_str).collect::<Vec<_>>(),
            "is not a sweep's folder",
        );
        assert!(err.contains(holds), "{err}");
    }
    assert_eq!(names(Path::new(&render)), before);
    assert_eq!(names(&notes), ["notes.txt"]);
    // A sweep's own folder resumes.
    let own = tmp.path().join("own").display().to_string();
    for _ in 0..2 {
        let args = sweep(&own);
        assert_runs(&args.iter().map(String::as_str).collect::<Vec<_>>());
    }
}

/// #8: two sweeps into one folder at once both ran, and mixed ten configurations of each.
/// One run per configuration: the second is refused; a shard that owns others runs beside.
#[test]
fn issue57_a_second_sweep_into_a_running_ones_folder_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("sweep");
    let out_s = out.display().to_string();
    let mut first = std::process::Command::new(env!("CARGO_BIN_EXE_cuticle"))
        .args([
            "sweep", "--grid", "small", "--rays", "50000000", "--limit", "2", "--shard", "1/2",
            "--out", &out_s,
        ])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while !out.join(".sweep.lock").exists() && start.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // The locks are taken a moment after the file is made.
    std::thread::sleep(std::time::Duration::from_millis(300));
    for shard in ["1/1", "1/2"] {
        assert_refused(
            &[
                "sweep", "--grid", "small", "--rays", "1000", "--seed", "2", "--limit", "20",
                "--shard", shard, "--out", &out_s,
            ],
            "another sweep is running",
        );
    }
    // Shard 2 of 2 owns none of shard 1's configurations.
    assert_runs(&[
        "sweep", "--grid", "small", "--rays", "50000000", "--limit", "0", "--shard", "2/2",
        "--out", &out_s,
    ]);
    assert!(
        first.try_wait().unwrap().is_none(),
        "the first sweep ended before the second was tried: the test proves nothing"
    );
    first.kill().unwrap();
    first.wait().unwrap();
    // Its locks went with it.
    assert_runs(&[
        "sweep", "--grid", "small", "--rays", "50000000", "--limit", "0", "--out", &out_s,
    ]);
}

/// #9: the path tracer took a strand absorption sidecar, melanin, a lights file, and --mu-a
/// with melanin, and rendered as without them.
#[test]
fn issue57_the_path_tracer_refuses_what_it_would_ignore() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let out = dir.join("out").display().to_string();
    let path = with(&with(&["render"], &B), &["--method", "path", "--spp", "1"]);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, "strand_absorption = \"absorption.json\"\n").unwrap();
    let lights = dir.join("lights.json");
    std::fs::write(
        &lights,
        r#"{"lights": [{"direction": [0, 1, 0], "bandwidth": 0.5, "coefficient": [1, 1, 1]}]}"#,
    )
    .unwrap();
    let (scene, lights) = (scene.display().to_string(), lights.display().to_string());
    let rows: Vec<(Vec<String>, &str)> = vec![
        (
            with(&path, &["--model", "deon2011", "--scene", &scene]),
            "strand_absorption",
        ),
        (
            with(&path, &["--eumelanin", "8"]),
            "--eumelanin does not apply to --model marschner",
        ),
        (
            with(&path, &["--beta", "0.1"]),
            "--beta does not apply to --model marschner",
        ),
        (
            with(&path, &["--model", "chiang2016", "--beta", "0.1"]),
            "--beta does not apply to --model chiang2016",
        ),
        (
            with(&path, &["--model", "deon2011", "--beta-n", "0.1"]),
            "--beta-n does not apply",
        ),
        (
            with(
                &path,
                &["--model", "deon2011", "--mu-a", "0.5", "--eumelanin", "8"],
            ),
            "both set the absorption",
        ),
        (
            with(
                &with(&["render"], &B[..8]),
                &["--method", "path", "--lights", &lights],
            ),
            "--lights FILE is for --method srbf and brute",
        ),
        (
            with(&with(&["render"], &B), &["--model", "deon2011"]),
            "--model is for --method path",
        ),
        (
            with(&with(&["render"], &B), &["--eumelanin", "8"]),
            "--eumelanin is for --method path",
        ),
    ];
    refuse_all(
        dir,
        &rows
            .into_iter()
            .map(|(mut a, n)| {
                a.extend(["--out".into(), out.clone()]);
                (a, n.to_string())
            })
            .collect::<Vec<_>>(),
    );
}

/// #14: under `prlimit --as=4294967296` a 2,000,000-strand groom aborted in the allocator, and
/// the refusal under CUTICLE_MEMORY_LIMIT advised `groom make` to lower a --width it lacks.
#[test]
fn issue57_memory_checks_read_the_address_space_limit_and_advise_per_command() {
    use std::os::unix::process::CommandExt;
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out").display().to_string();
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_cuticle"));
    command.args([
        "groom",
        "make",
        "--preset",
        "curly",
        "--strands",
        "2000000",
        "--out",
        &out,
    ]);
    // SAFETY: setrlimit is async-signal-safe; nothing else runs between fork and exec.
    unsafe {
        command.pre_exec(|| {
            let limit = libc::rlimit {
                rlim_cur: 4 << 30,
                rlim_max: 4 << 30,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let run = command.output().unwrap();
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{err}");
    assert!(err.starts_with("error: this groom needs about"), "{err}");
    assert!(
        err.contains("lower --strands") && !err.contains("--width"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    let err = assert_refused(
        &[
            "render", "--method", "path", "--width", "16384", "--height", "16384", "--out", &out,
        ],
        "of memory",
    );
    assert!(
        err.contains("--width/--height or --strands") && !err.contains("lights"),
        "{err}"
    );
    assert!(!tmp.path().join("out").exists());
}

/// The arguable item of issue 57: a FIFO given as `--scene` blocked forever, and reads had no
/// size cap. Every input file must be a regular file of a sane size.
#[test]
fn issue57_special_and_oversized_input_files_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let fifo = dir.join("fifo");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let fifo = fifo.display().to_string();
    let sparse = dir.join("sparse.toml");
    std::fs::File::create(&sparse)
        .unwrap()
        .set_len(20 << 30)
        .unwrap();
    let sparse = sparse.display().to_string();
    let out = dir.join("out").display().to_string();
    let render = with(&["render"], &B);
    let rows: Vec<(Vec<String>, &str)> = vec![
        (with(&render, &["--scene", &fifo]), "not a regular file"),
        (
            with(&render, &["--scene", "/dev/zero"]),
            "not a regular file",
        ),
        (with(&render, &["--scene", &sparse]), "more than the"),
        (with(&render, &["--env", &fifo]), "not a regular file"),
        (with(&render, &["--env", &sparse]), "more than the"),
        (with(&render, &["--groom", &fifo]), "not a regular file"),
        (
            with(&with(&["render"], &B[..8]), &["--lights", &fifo]),
            "not a regular file",
        ),
        (
            with(&["env", "fit", "--env", "/dev/zero"], &[]),
            "not a regular file",
        ),
        (with(&["sweep", "--grid", &fifo], &[]), "not a regular file"),
    ];
    for (mut args, needle) in rows {
        args.extend(["--out".into(), out.clone()]);
        assert_refused(&args.iter().map(String::as_str).collect::<Vec<_>>(), needle);
    }
    assert_refused(&["groom", "info", &fifo], "not a regular file");
    assert!(!dir.join("out").exists());
}
