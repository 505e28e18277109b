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
