//! `sim.json`: the record of one simulation, with the keys docs/conventions.md §5 shares across
//! commands.

use crate::simulate::{LOBE_NAMES, SimResult};
use glam::DVec3;
use serde_json::{Map, Value, json};

fn mean(v: DVec3) -> f64 {
    (v.x + v.y + v.z) / 3.0
}

/// The `"params"` object, by flag name: theta_i, alpha_deg, beta, eta, mu_a [r,g,b], rays,
/// seed, grid [width, height].
pub fn params_json(r: &SimResult) -> Value {
    let p = &r.params;
    json!({
        "theta_i": p.theta_i,
        "alpha_deg": p.alpha.to_degrees(),
        "beta": p.beta,
        "eta": p.eta,
        "mu_a": p.mu_a,
        "rays": p.rays,
        "seed": p.seed,
        "grid": [p.grid.width, p.grid.height],
    })
}

/// The whole record: "params"; "energy" {R, TT, TRT, TRRT, rest, total} (channel means) and
/// "energy_rgb" (the same, RGB); "lost" {shadowing, backfacing, cutoff}; "absorbed";
/// "seconds"; "rays"; "paths_per_second".
pub fn sim_json(r: &SimResult) -> Value {
    let mut energy = Map::new();
    let mut energy_rgb = Map::new();
    for (name, e) in LOBE_NAMES.iter().zip(&r.energy) {
        energy.insert(name.to_string(), json!(mean(*e)));
        energy_rgb.insert(name.to_string(), json!(e.to_array()));
    }
    energy.insert("total".into(), json!(mean(r.albedo())));
    energy_rgb.insert("total".into(), json!(r.albedo().to_array()));
    json!({
        "params": params_json(r),
        "energy": energy,
        "energy_rgb": energy_rgb,
        "lost": {
            "shadowing": mean(r.lost_shadowing),
            "backfacing": mean(r.lost_backfacing),
            "cutoff": mean(r.lost_cutoff),
        },
        "absorbed": mean(r.absorbed()),
        "seconds": r.seconds,
        "rays": r.rays,
        "paths_per_second": r.paths_per_second(),
    })
}
