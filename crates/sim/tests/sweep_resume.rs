//! A sweep resumes: complete configurations (those with `sim.json`) are skipped, an interrupted
//! run leaves no damaged one, shards cover the sweep exactly once, and a folder made with other
//! settings is refused rather than mixed.

use cuticle_fiber::LatLongGrid;
use cuticle_sim::sweep::RECORD;
use cuticle_sim::{Shard, SimResult, Sweep, SweepConfig, grid, list_complete};
use std::cell::Cell;
use std::fs;
use std::path::Path;
use std::time::SystemTime;

/// Stands in for the CLI's staged EXR writer: one small file per lobe and `sim.json`, written
/// beside the folder and renamed into place.
fn write_images(dir: &Path, r: &SimResult) -> Result<(), String> {
    let name = dir.file_name().unwrap().to_string_lossy();
    let stage = dir.with_file_name(format!(".{name}.staging"));
    fs::create_dir_all(&stage).map_err(|e| e.to_string())?;
    for (name, e) in cuticle_sim::LOBE_NAMES.iter().zip(&r.energy) {
        fs::write(stage.join(format!("{name}.txt")), format!("{}\n", e.x))
            .map_err(|e| e.to_string())?;
    }
    let record = serde_json::to_string(&cuticle_sim::sim_json(r)).unwrap();
    fs::write(stage.join(RECORD), record).map_err(|e| e.to_string())?;
    fs::rename(&stage, dir).map_err(|e| e.to_string())
}

fn configs() -> Vec<SweepConfig> {
    grid::small().into_iter().step_by(20).collect()
}

fn sweep(root: &Path, shard: Shard) -> Sweep {
    Sweep::new(&configs(), shard, root, 20_000, 1, LatLongGrid::new(40, 10)).unwrap()
}

fn modified(p: &Path) -> SystemTime {
    fs::metadata(p).unwrap().modified().unwrap()
}

fn assert_complete_and_whole(s: &Sweep, c: &SweepConfig) {
    let dir = s.dir(c);
    assert!(s.is_complete(c), "{} incomplete", c.dir_name());
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.join(RECORD)).unwrap()).unwrap();
    assert_eq!(json["rays"], 20_000);
    for name in cuticle_sim::LOBE_NAMES {
        assert!(
            dir.join(format!("{name}.txt")).is_file(),
            "{name} missing in {}",
            c.dir_name()
        );
    }
    let stray: Vec<_> = fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let n = e.unwrap().file_name().to_string_lossy().into_owned();
            n.starts_with('.').then_some(n)
        })
        .collect();
    assert!(
        stray.is_empty(),
        "temporary files left in {}: {stray:?}",
        c.dir_name()
    );
}

#[test]
fn interrupted_sweep_resumes_without_redoing_or_damaging() {
    let tmp = tempfile::tempdir().unwrap();
    let s = sweep(tmp.path(), Shard::ALL);
    assert_eq!(s.configs.len(), 6);

    // First run: stopped (as by Ctrl-C) before the fourth configuration.
    let done = Cell::new(0);
    let first = s
        .run(&write_images, &|| done.get() == 3, &mut |_, _| {
            done.set(done.get() + 1)
        })
        .unwrap();
    assert_eq!((first.ran, first.skipped, first.remaining), (3, 0, 3));
    let finished: Vec<&SweepConfig> = s
        .configs
        .iter()
        .map(|(_, c)| c)
        .filter(|c| s.is_complete(c))
        .collect();
    assert_eq!(finished.len(), 3);
    let stamps: Vec<SystemTime> = finished
        .iter()
        .map(|c| modified(&s.dir(c).join(RECORD)))
        .collect();

    // A run killed mid-configuration: images half written, a temporary file, no sim.json.
    let killed = &s.configs[4].1;
    let dir = s.dir(killed);
    fs::create_dir_all(&dir).unwrap();
    fs::write(dir.join("R.txt"), "0.0").unwrap();
    fs::write(dir.join(".TT.exr.tmp999"), "partial").unwrap();
    assert!(!s.is_complete(killed));

    let second = s.run(&write_images, &|| false, &mut |_, _| {}).unwrap();
    assert_eq!((second.ran, second.skipped, second.remaining), (3, 3, 0));
    for (_, c) in &s.configs {
        assert_complete_and_whole(&s, c);
    }
    for (c, t) in finished.iter().zip(stamps) {
        assert_eq!(
            modified(&s.dir(c).join(RECORD)),
            t,
            "{} was redone",
            c.dir_name()
        );
    }
    let third = s
        .run(&write_images, &|| false, &mut |_, _| {
            panic!("nothing left to run")
        })
        .unwrap();
    assert_eq!((third.ran, third.skipped), (0, 6));

    let listed = list_complete(tmp.path()).unwrap();
    assert_eq!(listed.len(), 6);
    for (c, dir) in listed {
        assert!(
            configs().contains(&c),
            "{c:?} read back from {}",
            dir.display()
        );
    }
}

#[test]
fn shards_share_the_sweep_without_overlap() {
    let tmp = tempfile::tempdir().unwrap();
    let mut seen = Vec::new();
    for k in 1..=4 {
        let s = sweep(tmp.path(), Shard { k, n: 4 });
        seen.extend(s.configs.iter().map(|(i, _)| *i));
        let summary = s.run(&write_images, &|| false, &mut |_, _| {}).unwrap();
        assert_eq!(summary.skipped, 0, "shard {k} found another shard's work");
    }
    seen.sort();
    assert_eq!(seen, (0..6).collect::<Vec<_>>());
    assert_eq!(list_complete(tmp.path()).unwrap().len(), 6);
}

#[test]
fn a_resume_with_other_settings_is_refused_before_anything_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let s = sweep(tmp.path(), Shard::ALL);
    let first = Cell::new(0);
    s.run(&write_images, &|| first.get() == 2, &mut |_, _| {
        first.set(first.get() + 1)
    })
    .unwrap();
    let grid = LatLongGrid::new(40, 10);
    for (rays, seed, grid, what) in [
        (200_000, 1, grid, "rays"),
        (20_000, 9, grid, "seed"),
        (20_000, 1, LatLongGrid::new(80, 20), "grid"),
    ] {
        let other = Sweep::new(&configs(), Shard::ALL, tmp.path(), rays, seed, grid).unwrap();
        let err = other
            .run(&write_images, &|| false, &mut |_, _| {
                panic!("ran a configuration")
            })
            .unwrap_err()
            .to_string();
        assert!(err.contains(&format!("made with {what}")), "{err}");
    }
    // The same settings resume.
    let resumed = s.run(&write_images, &|| false, &mut |_, _| {}).unwrap();
    assert_eq!((resumed.ran, resumed.skipped), (4, 2));
}

#[test]
fn duplicate_folders_and_bad_parameters_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let mut twice = configs();
    twice.push(twice[0].clone());
    assert!(
        Sweep::new(
            &twice,
            Shard::ALL,
            tmp.path(),
            1000,
            1,
            LatLongGrid::default()
        )
        .is_err()
    );
    let bad = vec![SweepConfig {
        beta: 0.0,
        ..configs()[0].clone()
    }];
    assert!(
        Sweep::new(
            &bad,
            Shard::ALL,
            tmp.path(),
            1000,
            1,
            LatLongGrid::default()
        )
        .is_err()
    );
}
