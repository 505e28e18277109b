//! Every model's S, pdf and one importance sample at fixed inputs, pinned in `figures.json`
//! beside this file: the Python bindings' test (crates/py/tests/test_fiber.py) holds
//! `cuticle.Fiber` to the same file, so the bindings are checked against these Rust figures.
//! A deliberate change to a model rewrites the file with `CUTICLE_BLESS=1 cargo test --release
//! -p cuticle-fiber --test figures`.

use cuticle_fiber::{BuildOptions, FiberAngles, FiberParams, ModelId};
use serde_json::{Value, json};
use std::path::Path;

/// The fixed inputs: ω_i, ω_o as (θ, φ) radians, and the sample's four uniform numbers.
const WI: (f64, f64) = (0.5, 0.0);
const WO: (f64, f64) = (-0.3, 1.0);
const U: [f64; 4] = [0.3, 0.6, 0.2, 0.9];

fn figures() -> Value {
    let params = FiberParams::default();
    let wi = FiberAngles::new(WI.0, WI.1);
    let wo = FiberAngles::new(WO.0, WO.1);
    let models: serde_json::Map<String, Value> = ModelId::ALL
        .into_iter()
        .map(|id| {
            let model = id.build(&params, &BuildOptions::default()).unwrap();
            let sample = model.sample(wi, U).unwrap();
            let figures = json!({
                "eval": model.eval(wi, wo).total().to_array(),
                "pdf": model.pdf(wi, wo),
                "sample_wo": sample.wo.to_dir().to_array(),
                "sample_weight": sample.weight.to_array(),
                "sample_pdf": sample.pdf,
            });
            (id.name().to_string(), figures)
        })
        .collect();
    json!({
        "wi": FiberAngles::new(WI.0, WI.1).to_dir().to_array(),
        "wo": FiberAngles::new(WO.0, WO.1).to_dir().to_array(),
        "u": U,
        "models": models,
    })
}

/// Whether two JSON trees hold the same numbers within a relative 1e-12 (the last bits of a
/// libm call may differ between machines).
fn close(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1e-300)
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(x, y)| close(x, y))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| close(v, w)))
        }
        _ => a == b,
    }
}

#[test]
fn figures_match_the_pinned_file() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/figures.json");
    let now = figures();
    if std::env::var_os("CUTICLE_BLESS").is_some() {
        let text = serde_json::to_string_pretty(&now).unwrap() + "\n";
        std::fs::write(&path, text).unwrap();
    }
    let pinned: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert!(
        close(&now, &pinned),
        "the models' figures changed: {now:#}\n(rewrite {} with CUTICLE_BLESS=1 if that is meant)",
        path.display()
    );
}
