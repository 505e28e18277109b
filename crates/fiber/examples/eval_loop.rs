//! A tight loop of d'Eon 2011 evaluations with the table, for profilers (`perf record`).
use cuticle_fiber::{DEon2011, FiberAngles, FiberModel, FiberParams};

fn main() {
    let m = DEon2011::new(FiberParams::default()).unwrap().tabulated();
    let mut acc = 0.0;
    for i in 0..2_000_000u64 {
        let t = (i % 997) as f64 / 997.0;
        let wi = FiberAngles::new(2.8 * (t - 0.5), 0.0);
        let wo = FiberAngles::new(
            2.8 * ((i % 131) as f64 / 131.0 - 0.5),
            6.2 * ((i % 71) as f64 / 71.0 - 0.5),
        );
        acc += m.eval(wi, wo).total().x;
    }
    println!("{acc}");
}
