//! `docs/scene.toml`, the documented example scene, stays in step with `SceneSpec`: it reads
//! back as the defaults, and it names every key the defaults serialise.

use cuticle_render::SceneSpec;
use std::collections::BTreeSet;
use std::path::PathBuf;

fn example() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene.toml")
}

/// Every dotted key of a TOML table.
fn keys(value: &toml::Value, prefix: &str, out: &mut BTreeSet<String>) {
    if let toml::Value::Table(table) = value {
        for (k, v) in table {
            let key = format!("{prefix}{k}");
            keys(v, &format!("{key}."), out);
            out.insert(key);
        }
    }
}

#[test]
fn example_scene_is_the_defaults_and_names_every_key() {
    let spec = SceneSpec::from_toml_file(&example()).expect("docs/scene.toml reads");
    assert_eq!(spec, SceneSpec::default());
    spec.validate().expect("the defaults validate");

    let text = std::fs::read_to_string(example()).unwrap();
    let (mut written, mut wanted) = (BTreeSet::new(), BTreeSet::new());
    let table = |t: &str| toml::Value::Table(toml::from_str::<toml::Table>(t).unwrap());
    keys(&table(&text), "", &mut written);
    keys(
        &table(&toml::to_string(&SceneSpec::default()).unwrap()),
        "",
        &mut wanted,
    );
    let missing: Vec<_> = wanted.difference(&written).collect();
    assert!(missing.is_empty(), "docs/scene.toml lacks {missing:?}");
}
