// srbf/cg_lobes.rs and srbf/taylor.rs in f32: N_R as the Fresnel quintic's polynomial against 𝒞_k, and the
// TRT fit at one (η, θ_d) with its caustic moments, which eccentric fibers need at every sample
// (their η̄* varies). KEPT_PANELS, KEPT_POINTS and the Gauss–Legendre KEPT_NODES/KEPT_WEIGHTS
// are cg_lobes.rs's, written by shading/mod.rs.

// C_0 … C_6 of N_R's polynomial in |cos(φ/2)| (Xu et al. 2011 eq. 13): C_0 = 0 and
// C_{n+1} = ¼ a_n, the a_n of the Fresnel quintic's table (tables/r_fresnel.rs).
fn r_coefficients(eta: f32, theta_d: f32) -> array<f32, 7> {
    let g = params.grids[GRID_R_FRESNEL];
    let cx = cell_x(g, log(clamp(eta, 1.0, 10.0)));
    let cy = cell_y(g, abs(theta_d));
    var out = array<f32, 7>(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (var n = 0u; n < 6u; n++) {
        out[n + 1u] = 0.25 * static_at(GRID_R_FRESNEL, cx, cy, n);
    }
    return out;
}

// 𝒩_R = Σ_k C_k 𝒞_k(λ′, δ) (eq. 14), from the table of 𝒞_k/Z and ln Z.
fn r_convolved(eta: f32, theta_d: f32, lambda_light: f32, delta: f32) -> f32 {
    var c = r_coefficients(eta, theta_d);
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
    let ep = eta_prime(eta, theta_d);
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
    return Geometry(ep, max(cos_theta_t(eta, theta_d), 1e-6), trt_root(eta, theta_d, ep, 0.0, 1.0), root1, phi_star);
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

// exp(−z²/2) of the image k turns of the circle away from y, z = (y − 2πk)/σ.
fn gaussian_image(y: f32, sigma: f32, k: i32) -> f32 {
    let z = (y - 2.0 * PI * f32(k)) / sigma;
    return exp(-0.5 * z * z);
}

// The unit wrapped Gaussian of variance v at x (the fiber crate's wrapped_gaussian: the images
// within 3σ of the circle, plus one). The images |k| ≤ 2, all there are for σ ≤ 2π/3, are
// written out, not looped over: this runs twice at each of the caustic moments' 32 nodes, at
// every TRT sample of an eccentric fiber, and llvmpipe counts every loop of an invocation
// against one budget (shading/mod.rs's LOOP_BUDGET).
fn wrapped_gaussian(x: f32, v: f32) -> f32 {
    let sigma = sqrt(v);
    let y = wrap_pi(x);
    let images = i32(ceil(3.0 * sigma / (2.0 * PI))) + 1;
    // images ≥ 2 for every σ > 0.
    var sum = gaussian_image(y, sigma, 0) + gaussian_image(y, sigma, 1) + gaussian_image(y, sigma, -1)
        + gaussian_image(y, sigma, 2) + gaussian_image(y, sigma, -2);
    if (images > 2) {
        for (var k = 3; k <= images; k++) {
            sum += gaussian_image(y, sigma, k) + gaussian_image(y, sigma, -k);
        }
    }
    return sum / (sigma * sqrt(2.0 * PI));
}

// Marschner 2003's caustic at η′ (the fiber crate's Caustic::new, on the cubic Φ̂(2, γ) =
// (a − bγ²)γ + 2π): φ_c, γ_c, Δh and the glint strength t.
struct Caustic {
    phi_c: f32,
    gamma_c: f32,
    delta_h: f32,
    t: f32,
}

// The cubic Φ̂(2, γ)'s coefficients [a, b] (Marschner 2003 eq. 10's fit of Φ).
fn cubic_deflection(ep: f32) -> vec2<f32> {
    let pc = 2.0 * asin(clamp(1.0 / ep, -1.0, 1.0));
    return vec2<f32>(6.0 * pc / PI - 2.0, 8.0 * pc / (PI * PI * PI));
}

fn cubic_phi(ab: vec2<f32>, gamma: f32) -> f32 {
    return (ab.x - ab.y * gamma * gamma) * gamma + 2.0 * PI;
}

fn caustic(ep: f32, caustic_width: f32) -> Caustic {
    let ab = cubic_deflection(ep);
    // max(…, 0): no NaN where a ≤ 0 (η′ ≥ 2), which the test below rejects anyway.
    let g = sqrt(max(ab.x, 0.0) / (3.0 * ab.y));
    if (ab.x > 0.0 && ab.y > 0.0 && g < HALF_PI && ep < 2.0) {
        let c = cos(g);
        let d2phi_dh2 = -6.0 * ab.y * g / (c * c);
        let spread = 2.0 * sqrt(2.0 * caustic_width / abs(d2phi_dh2));
        return Caustic(wrap_pi(cubic_phi(ab, g)), g, min(params.caustic_limit, spread), 1.0);
    }
    return Caustic(0.0, 0.0, params.caustic_limit, 1.0 - smoothstep_ab(2.0, 2.0 + params.caustic_fade, ep));
}

// cg_lobes.rs's CausticMoments: what Marschner 2003's caustic treatment does to ∫ N_TRT dφ at
// one (η, θ_d) — the kept moments ℋ̃_0, ℋ̃_2, ℋ̃_4 (Xu et al. 2011 eq. 23's ℋ_k^TRT weighted
// by keep(Φ̂)), a glint's energy without T², and the glint's path √(1 − h_c²/η′²).
struct CausticMoments {
    kept: vec3<f32>,
    glint: f32,
    glint_path: f32,
}

// (1 − F)² F_int: A(2, h) without T², with F_int from Bravais' inverse indices at γ_t.
fn trt_attenuation(eta: f32, theta_d: f32, ep: f32, epar: f32, h: f32) -> f32 {
    let f = oblique(eta, theta_d, h);
    let gamma_t = asin(clamp(h / ep, -1.0, 1.0));
    let internal = 0.5 * (polarised_reflectance(1.0 / ep, gamma_t, true)
        + polarised_reflectance(1.0 / epar, gamma_t, false));
    return (1.0 - f) * (1.0 - f) * internal;
}

fn caustic_moments(eta: f32, theta_d: f32, ep: f32) -> CausticMoments {
    let width = params.caustic_bandwidth / SQRT_2;
    let c = caustic(ep, width);
    let ab = cubic_deflection(ep);
    let v = width * width;
    let g0 = wrapped_gaussian(0.0, v);
    let epar = eta_double_prime(eta, theta_d);
    // Twice the half range in γ, cut where F's parallel part reaches total reflection.
    var kink = 0.5 * HALF_PI;
    if (epar < 1.0) {
        kink = asin(epar);
    }
    var cuts = array<f32, 3>(0.0, kink, HALF_PI);
    var nodes = KEPT_NODES;
    var weights = KEPT_WEIGHTS;
    var kept = vec3<f32>(0.0);
    for (var span = 0u; span < 2u; span++) {
        let step = (cuts[span + 1u] - cuts[span]) / f32(KEPT_PANELS);
        for (var panel = 0u; panel < KEPT_PANELS; panel++) {
            let a = cuts[span] + f32(panel) * step;
            for (var i = 0u; i < KEPT_POINTS; i++) {
                let gamma = a + 0.5 * step * (nodes[i] + 1.0);
                let h = sin(gamma);
                let phi = cubic_phi(ab, gamma);
                let minus = 1.0 - c.t * wrapped_gaussian(phi - c.phi_c, v) / g0;
                let plus = 1.0 - c.t * wrapped_gaussian(phi + c.phi_c, v) / g0;
                let base = step * weights[i] * cos(gamma)
                    * trt_attenuation(eta, theta_d, ep, epar, h) * max(minus * plus, 0.0);
                let h2 = h * h;
                kept += base * vec3<f32>(1.0, h2, h2 * h2);
            }
        }
    }
    let h_c = sin(c.gamma_c);
    let glint = c.t * params.glint_scale * c.delta_h * trt_attenuation(eta, theta_d, ep, epar, h_c);
    return CausticMoments(kept, glint, sqrt(max(1.0 - (h_c / ep) * (h_c / ep), 0.0)));
}

// ∫ N_TRT dφ of Marschner 2003's practical model at σ′: the kept part and both glints.
fn caustic_energy(m: CausticMoments, g: Geometry, sigma_prime: f32) -> f32 {
    let c = taylor_coefficients(2.0, sigma_prime, g.eta_prime);
    return 0.5 * dot(c, m.kept) + 2.0 * m.glint * exp(-4.0 * sigma_prime * m.glint_path);
}

// trt_fit (Xu et al. 2011 eqs. 20–23 and the blend of §4.2.4), its energy that of Marschner
// 2003's N_TRT (`CausticMoments`), as cg_lobes.rs fits it.
fn trt_fit(g: Geometry, m: CausticMoments, mu_a: f32) -> TrtFit {
    let sp = mu_a / g.cos_theta_t;
    let energy = caustic_energy(m, g, sp);
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
