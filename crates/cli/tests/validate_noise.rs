//! `cuticle validate --noise` end to end (issue 14): two small sweeps of one configuration with
//! different seeds give every figure a seed-to-seed L1, a floor and a residual, in the CSV and
//! on stdout; a second sweep with the same seed, or of another configuration, is refused with
//! one clear error. `--moments` adds each lobe's moments in θ per column.

use std::path::Path;
use std::process::Command;

fn cuticle(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_cuticle"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn sweep(dir: &Path, grid: &Path, seed: &str) {
    let run = cuticle(&[
        "sweep",
        "--grid",
        grid.to_str().unwrap(),
        "--rays",
        "200000",
        "--seed",
        seed,
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}

fn write_grid(path: &Path, theta_i: f64) {
    let text = format!(
        r#"[{{"theta_i": {theta_i}, "alpha_deg": 2, "beta": 0.08, "eta": 1.55, "mu_a": 0}}]"#
    );
    std::fs::write(path, text).unwrap();
}

/// `moments.csv` of `--moments`: rows for the simulation and both models in R, TT and TRT, and
/// the simulated TT where transmission puts it, near the specular cone θ_o = −θ_i = −0.75.
fn check_moments(csv: &str) {
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("config,source,lobe,phi,energy,mean_theta,std_dev_theta,skewness_theta")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    for source in ["sim", "deon2011", "nonseparable"] {
        for lobe in ["R", "TT", "TRT"] {
            assert!(
                rows.iter().any(|r| r[1] == source && r[2] == lobe),
                "no {source} {lobe} row"
            );
        }
    }
    let (mut energy, mut weighted_mean) = (0.0, 0.0);
    for r in rows.iter().filter(|r| r[1] == "sim" && r[2] == "TT") {
        let num = |k: usize| r[k].parse::<f64>().unwrap();
        assert!(num(6) > 0.0 && num(6) < 0.3 && num(7).is_finite(), "{r:?}");
        energy += num(4);
        weighted_mean += num(4) * num(5);
    }
    let mean = weighted_mean / energy;
    assert!((mean + 0.75).abs() < 0.1, "simulated TT's mean θ_o {mean}");
}

#[test]
fn a_second_seed_gives_every_figure_its_noise_floor() {
    let tmp = tempfile::tempdir().unwrap();
    let grid = tmp.path().join("grid.json");
    write_grid(&grid, 0.75);
    let (a, b, same) = (
        tmp.path().join("a"),
        tmp.path().join("b"),
        tmp.path().join("same"),
    );
    sweep(&a, &grid, "1");
    sweep(&b, &grid, "2");
    sweep(&same, &grid, "1");
    let out = tmp.path().join("validation");
    let run = cuticle(&[
        "validate",
        "--sim",
        a.to_str().unwrap(),
        "--noise",
        b.to_str().unwrap(),
        "--models",
        "deon2011,nonseparable",
        "--sheets",
        "0",
        "--moments",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(stdout.contains("seed-to-seed"), "{stdout}");
    let csv = std::fs::read_to_string(out.join("validation.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (lobe, l1, s2s, floor, residual) = (
        column("lobe"),
        column("relative_l1"),
        column("seed_to_seed_l1"),
        column("noise_floor"),
        column("residual_l1"),
    );
    let mut checked = 0;
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        if f[lobe] != "R" && f[lobe] != "TT" {
            continue;
        }
        let num = |k: usize| f[k].parse::<f64>().unwrap();
        // 200 k paths: the two runs differ visibly, and a model's residual sits below its L1.
        assert!(
            num(s2s) > 0.01 && (num(floor) - 0.5 * num(s2s)).abs() < 1e-6,
            "{line}"
        );
        assert!(num(residual) < num(l1) && num(residual) > 0.0, "{line}");
        checked += 1;
    }
    assert_eq!(checked, 4);
    let md = std::fs::read_to_string(out.join("validation.md")).unwrap();
    assert!(md.contains("noise floor") && md.contains("Residuals against the noise floor"));
    check_moments(&std::fs::read_to_string(out.join("moments.csv")).unwrap());
    let record = std::fs::read_to_string(out.join("validate.json")).unwrap();
    assert!(record.contains("\"moments\": true"), "{record}");

    // The same seed twice would make the floor zero: refused, and so is another configuration.
    for (noise, needle) in [
        (&same, "seed"),
        (&tmp.path().join("other"), "no configuration"),
    ] {
        if noise.ends_with("other") {
            let other_grid = tmp.path().join("other.json");
            write_grid(&other_grid, 1.1);
            sweep(noise, &other_grid, "2");
        }
        let run = cuticle(&[
            "validate",
            "--sim",
            a.to_str().unwrap(),
            "--noise",
            noise.to_str().unwrap(),
            "--models",
            "deon2011",
            "--sheets",
            "0",
            "--out",
            tmp.path().join("refused").to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{noise:?} accepted");
        assert!(
            stderr.contains(needle) && !stderr.contains("panicked"),
            "{stderr}"
        );
        assert!(
            !tmp.path().join("refused").exists(),
            "a refused run made its folder"
        );
    }
}
