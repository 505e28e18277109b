//! The inputs every per-call figure of the fiber models is taken on (issue 15's, as pbrt-v4's
//! hair BSDF was timed): shared by `benches/models.rs` (criterion) and `examples/model_calls.rs`
//! (instruction counts), so both measure the same calls.
use cuticle_fiber::FiberAngles;
use cuticle_fiber::FiberParams;
use cuticle_fiber::optics::absorption::mu_a_from_melanin;

/// One call's inputs: ω_i, ω_o and four uniform numbers for sampling.
pub type Case = (FiberAngles, FiberAngles, [f64; 4]);

/// η 1.55, β = 0.3, α = 2°, μ_a of eumelanin 1.3.
pub fn params() -> FiberParams {
    FiberParams {
        eta: 1.55,
        beta: 0.3,
        alpha: 2f64.to_radians(),
        mu_a: mu_a_from_melanin(1.3, 0.0),
    }
}

/// `n` cases, both directions uniform on the sphere (θ = asin(2ξ − 1), φ uniform), from a
/// fixed xorshift stream.
pub fn cases(n: usize) -> Vec<Case> {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let direction = |next: &mut dyn FnMut() -> f64| {
        let theta = (2.0 * next() - 1.0).asin();
        FiberAngles::new(theta, (next() - 0.5) * std::f64::consts::TAU)
    };
    (0..n)
        .map(|_| {
            let (wi, wo) = (direction(&mut next), direction(&mut next));
            (wi, wo, [next(), next(), next(), next()])
        })
        .collect()
}
