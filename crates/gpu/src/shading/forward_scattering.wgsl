// srbf/forward_scattering.rs and the averages of tables/back_scattering.rs in f32: what reaches
// a point through forward scattering along a light's shadow path (Zinke et al. 2008 §4.1).

const DENSITY_FACTOR: f32 = 0.7;
const MAX_FORWARD: f32 = 0.995;

// back_scattering.rs's Averages.
struct Averages {
    forward: f32,
    forward_variance: f32,
    back: f32,
    back_shift: f32,
    back_width: f32,
}

// back_scattering.rs's BackPaths: A_k and n̄_k of the paths back-scattered k times.
struct BackPaths {
    events: f32,
    weight: f32,
    forward_crossings: f32,
}

// back_paths: A₁ and A₃ of a Poisson medium of fibers, with their mean forward crossings.
fn back_paths(af: f32, ab: f32) -> array<BackPaths, 2> {
    let open = 1.0 - af;
    return array<BackPaths, 2>(
        BackPaths(1.0, af * ab / (2.0 * open), 1.0 / open),
        BackPaths(3.0, af * ab * ab * ab / (8.0 * open * open * open), 1.0 + 3.0 * af / open),
    );
}

// averages_from_moments: [ā_f, β̄_f², Ā_b, Δ̄_b, σ̄_b] from [ā_f, ā_b, α_f, α_b, β_f², β_b²].
fn averages_from_moments(m: array<f32, 6>) -> Averages {
    let af = clamp(m[0], 0.0, MAX_FORWARD);
    let ab = max(m[1], 0.0);
    let alpha_f = m[2];
    let alpha_b = m[3];
    let beta_f2 = max(m[4], 0.0);
    let beta_b2 = max(m[5], 0.0);
    // Written out over the two paths rather than looped: llvmpipe caps the loop iterations of
    // one invocation (shading::loop_cost counts the loops that remain).
    let paths = back_paths(af, ab);
    let one = paths[0];
    let three = paths[1];
    let shift_one = one.events * alpha_b + one.forward_crossings * alpha_f;
    let variance_one = one.events * beta_b2 + one.forward_crossings * beta_f2;
    let big_ab = one.weight + three.weight;
    var shift = shift_one;
    var variance = variance_one;
    if (big_ab > 1e-30) {
        shift = (one.weight * shift_one
            + three.weight * (three.events * alpha_b + three.forward_crossings * alpha_f)) / big_ab;
        variance = (one.weight * variance_one
            + three.weight * (three.events * beta_b2 + three.forward_crossings * beta_f2)) / big_ab;
    }
    return Averages(af, beta_f2, big_ab, shift, max(sqrt(variance), 1e-4));
}

// BackScatteringTables::at_coordinate: the averages at |θ_d| for absorption coordinate x.
fn back_at_coordinate(theta_d: f32, x: f32) -> Averages {
    let g = params.grids[GRID_BACK];
    let cx = cell_x(g, abs(theta_d));
    let cy = cell_y(g, x);
    var m: array<f32, 6>;
    for (var k = 0u; k < 6u; k++) {
        m[k] = back_at(GRID_BACK, cx, cy, k);
    }
    return averages_from_moments(m);
}

// forward_scattering.rs's Forward: the scattered share d_f (T_f − T̃)⁺ and the variance σ̄_f².
struct Forward {
    scattered: f32,
    variance: f32,
}

fn forward(direct_in: f32, a: Averages) -> Forward {
    let direct = clamp(direct_in, 1e-30, 1.0);
    let n = -log(direct);
    let a_f = clamp(a.forward, 0.0, 1.0);
    let m = n * a_f;
    // e^{−n} (e^{n ā_f} − 1), and E[k | k ≥ 1] = m / (1 − e^{−m}) → 1 as m → 0 (expm1 formed
    // by its series below 1e-3, where f32's exp(m) − 1 would cancel).
    var expm1_m = exp(m) - 1.0;
    var crossings = 1.0;
    if (m < 1e-3) {
        expm1_m = m * (1.0 + 0.5 * m);
    } else {
        crossings = m / (1.0 - exp(-m));
    }
    let scattered = direct * expm1_m;
    return Forward(DENSITY_FACTOR * scattered, select(0.0, crossings * a.forward_variance, n > 0.0));
}
