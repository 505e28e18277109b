// srbf/cg_lobes.rs and srbf/taylor.rs in f32: N_R as Schlick's polynomial against 𝒞_k, and the
// TRT fit at one (η, θ_d), which eccentric fibers need at every sample (their η̄* varies).

// C_0 … C_6 of N_R's polynomial in |cos(φ/2)| (Xu et al. 2011 eq. 13).
fn r_coefficients(eta: f32, cos_theta_d: f32) -> array<f32, 7> {
    var binomial = array<f32, 6>(1.0, 5.0, 10.0, 10.0, 5.0, 1.0);
    let f0 = schlick_f0(eta);
    var out = array<f32, 7>(0.0, 0.25, 0.0, 0.0, 0.0, 0.0, 0.0);
    var power = 1.0;
    for (var n = 1u; n < 6u; n++) {
        power *= -cos_theta_d;
        out[n + 1u] = 0.25 * (1.0 - f0) * binomial[n] * power;
    }
    return out;
}

// 𝒩_R = Σ_k C_k 𝒞_k(λ′, δ) (eq. 14), from the table of 𝒞_k/Z and ln Z.
fn r_convolved(eta: f32, cos_theta_d: f32, lambda_light: f32, delta: f32) -> f32 {
    var c = r_coefficients(eta, cos_theta_d);
    let g = params.grids[GRID_COSINE];
    let cx = cell_x(g, log(clamp(lambda_light, 0.001, 10.0)));
    let cy = cell_y(g, abs(wrap_pi(delta)));
    var sum = 0.0;
    for (var k = 1u; k < 7u; k++) {
        sum += c[k] * static_at(GRID_COSINE, cx, cy, k);
    }
    return sum * exp(static_at(GRID_COSINE, cx, cy, 7u));
}

// [a₀, a₂, a₄] of T^n (Xu et al. 2011 eqs. 18, 22).
fn taylor_coefficients(n: f32, sigma_prime: f32, eta_prime: f32) -> vec3<f32> {
    let s = n * sigma_prime;
    let e = exp(-2.0 * s);
    let q = 1.0 / (eta_prime * eta_prime);
    return vec3<f32>(e, e * s * q, e * (0.25 * s + 0.5 * s * s) * q * q);
}

// What the TRT fit needs at one (η, θ_d) (cg_lobes.rs's Geometry, its TRT part).
struct Geometry {
    eta_prime: f32,
    cos_theta_t: f32,
    h_trt: vec3<f32>,
    // (weight, path) of the roots of Φ ≡ 0.
    root0: vec2<f32>,
    root1: vec2<f32>,
    // φ* of the caustics, or a negative number for none (η′ ≥ 2).
    phi_star: f32,
}

fn trt_root(eta: f32, theta_d: f32, ep: f32, h: f32, mult: f32) -> vec2<f32> {
    let f = oblique(eta, theta_d, h);
    let w = 0.5 * (1.0 - f) * (1.0 - f) * f / max(abs(deflection_slope(2.0, h, ep)), 1e-9);
    return vec2<f32>(mult * w, sqrt(max(1.0 - (h / ep) * (h / ep), 0.0)));
}

fn geometry(eta: f32, theta_d: f32) -> Geometry {
    let ep = eta_perp(eta, theta_d);
    var root1 = vec2<f32>(0.0, 1.0);
    var phi_star = -1.0;
    if (ep < 2.0) {
        let h0 = ep * sqrt(max(1.0 - 0.25 * ep * ep, 0.0));
        if (h0 < 1.0 - 1e-9) {
            root1 = trt_root(eta, theta_d, ep, h0, 2.0);
        }
        let h_star = sqrt((4.0 - ep * ep) / 3.0);
        phi_star = max(abs(wrap_pi(deflection(2.0, h_star, ep))), MIN_BANDWIDTH);
    }
    let g = params.grids[GRID_H_TRT];
    let cx = cell_x(g, log(clamp(eta, 1.0, 10.0)));
    let cy = cell_y(g, abs(theta_d));
    let h = vec3<f32>(static_at(GRID_H_TRT, cx, cy, 0u), static_at(GRID_H_TRT, cx, cy, 1u), static_at(GRID_H_TRT, cx, cy, 2u));
    return Geometry(ep, max(cos_theta_t(eta, theta_d), 1e-6), h, trt_root(eta, theta_d, ep, 0.0, 1.0), root1, phi_star);
}

const MIN_BANDWIDTH: f32 = 1e-3;
const MAX_BANDWIDTH: f32 = 20.0;

// One channel's TRT slots (glint at +φ*, glint at −φ*, centre): weights and bandwidths, and the
// slots' centres.
struct TrtFit {
    weight: vec3<f32>,
    bandwidth: vec3<f32>,
    centre: vec3<f32>,
}

// trt_fit (Xu et al. 2011 eqs. 20–23 and the blend of §4.2.4) as it was before main's
// CausticMoments (cg_lobes.rs now keeps Marschner's caustic glints in the TRT energy): not yet
// mirrored, so eccentric fibers, the one user of this on-the-spot fit, differ from the CPU by
// 4e-3 relative RMSE (tests/parity.rs) where circular fibers, which read the lobe table, agree
// to 1e-4. TODO: port CausticMoments.
fn trt_fit(g: Geometry, sigma_a: f32) -> TrtFit {
    let sp = sigma_a / g.cos_theta_t;
    let c = taylor_coefficients(2.0, sp, g.eta_prime);
    let energy = 0.5 * dot(c, g.h_trt);
    let at_zero = g.root0.x * exp(-4.0 * sp * g.root0.y) + g.root1.x * exp(-4.0 * sp * g.root1.y);
    let l1 = params.caustic_bandwidth;
    if (g.phi_star >= 0.0) {
        let phi_star = g.phi_star;
        let miss = 1.0 - cg_eval(0.0, phi_star, l1);
        let b2 = at_zero * miss * miss;
        let b1 = max((energy - b2 * cg_integral(phi_star)) / (2.0 * cg_integral(l1)), 0.0);
        return TrtFit(vec3<f32>(b1, b1, b2), vec3<f32>(l1, l1, phi_star), vec3<f32>(phi_star, -phi_star, 0.0));
    }
    let b3 = max(at_zero, 1e-30);
    let l3 = clamp(bandwidth_for_integral(energy / b3), MIN_BANDWIDTH, MAX_BANDWIDTH);
    let s = smoothstep_ab(2.0, 2.0 + params.caustic_fade, g.eta_prime);
    let blended = l1 + s * (l3 - l1);
    let merged = 0.5 * energy / cg_integral(blended);
    return TrtFit(vec3<f32>(merged, merged, 0.0), vec3<f32>(blended, blended, MIN_BANDWIDTH), vec3<f32>(0.0));
}
