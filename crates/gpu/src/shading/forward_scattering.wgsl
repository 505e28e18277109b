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

// averages_from_moments: [ā_f, β̄_f², Ā_b, Δ̄_b, σ̄_b] from [ā_f, ā_b, α_f, α_b, β_f², β_b²]
// (Zinke et al. 2008).
fn averages_from_moments(m: array<f32, 6>, d_b: f32) -> Averages {
    let af = clamp(m[0], 0.0, MAX_FORWARD);
    let ab = max(m[1], 0.0);
    let alpha_f = m[2];
    let alpha_b = m[3];
    let beta_f2 = m[4];
    let beta_b2 = m[5];
    let af2 = af * af;
    let ab2 = ab * ab;
    let one = 1.0 - af2;
    let one3 = one * one * one;
    let big_ab = ab * af2 / one + ab * ab2 * af2 / one3;
    let shift = alpha_b * (1.0 - 2.0 * ab2 / (one * one)) + alpha_f * (2.0 * one * one + 4.0 * af2 * ab2) / one3;
    let bf = sqrt(max(beta_f2, 0.0));
    let bb = sqrt(max(beta_b2, 0.0));
    let width_num = ab * sqrt(2.0 * beta_f2 + beta_b2) + ab * ab2 * sqrt(2.0 * beta_f2 + 3.0 * beta_b2);
    let width_den = ab + ab * ab2 * (2.0 * bf + 3.0 * bb);
    var width: f32;
    if (width_den > 1e-30) {
        width = (1.0 + d_b * af2) * width_num / width_den;
    } else {
        width = sqrt(2.0 * beta_f2 + beta_b2);
    }
    return Averages(af, beta_f2, big_ab, shift, max(width, 1e-4));
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
    return averages_from_moments(m, params.d_b);
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
