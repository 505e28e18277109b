// srbf/dual_scattering.rs in f32, function for function: multiple scattering by dual scattering
// under SRBF lights (Xu et al. 2011 §4.3, Zinke et al. 2008). Keep it a line-by-line twin of
// the CPU file, so that a change there is mirrored here (the parity tests catch a miss).

const NEGLIGIBLE: f32 = 1e-5;
// dual_scattering.rs's BACK_SCALE: the local term's factor.
const BACK_SCALE: f32 = 2.0;

// ∫ G_j dω of an SRBF exp(κ(ω·ω_j − 1)), κ = 2/λ².
fn srbf_integral(lambda: f32) -> f32 {
    let kappa = 2.0 / max(lambda * lambda, 1e-12);
    return 2.0 * PI * (1.0 - exp(-2.0 * kappa)) / kappa;
}

// λ_j/√2: the longitudinal deviation of an SRBF of bandwidth λ_j.
fn srbf_deviation(lambda: f32) -> f32 {
    return lambda / SQRT_2;
}

// Z(θ_j, σ) of tables/spread.rs, at least its floor.
fn spread_at(theta_j: f32, sigma: f32) -> f32 {
    return max(static_lookup(GRID_SPREAD, abs(theta_j), sigma, 0u), params.min_z);
}

// P(λ, δ) of tables/half_circle.rs.
fn half_share(lambda: f32, delta: f32) -> f32 {
    return static_lookup(GRID_HALF_SHARE, log(clamp(lambda, 1e-3, 20.0)), abs(wrap_pi(delta)), 0u);
}

// W_k(δ) of tables/half_circle.rs, k = 0…6.
fn half_cosines(delta: f32) -> array<f32, 7> {
    let g = params.grids[GRID_HALF_COSINES];
    let cx = cell_x(g, abs(wrap_pi(delta)));
    let cy = cell_y(g, 0.0);
    var w: array<f32, 7>;
    for (var k = 0u; k < 7u; k++) {
        w[k] = static_at(GRID_HALF_COSINES, cx, cy, k);
    }
    return w;
}

// The shadows' cutoff (ShadowOptions::passes).
fn passes(t: f32) -> bool {
    return t > 0.0 && t >= params.cutoff;
}

// Dual::light: one light's global and local terms; `radiance` unshadowed, `t` its T̃.
fn dual_light(theta_o: f32, phi_o: f32, theta_j: f32, phi_j: f32, bandwidth: f32, radiance: vec3<f32>, t: f32) -> vec3<f32> {
    let energy = radiance * srbf_integral(bandwidth);
    if (max(energy.x, max(energy.y, energy.z)) <= 0.0) {
        return vec3<f32>(0.0);
    }
    let cos_j = max(cos(theta_j), 1e-4);
    let delta = wrap_pi(phi_o - phi_j);
    var scattered = vec3<f32>(0.0);
    var fw_variance = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        let f = forward(t, back_at_coordinate(theta_j, fiber.absorption[c]));
        scattered[c] = f.scattered;
        fw_variance[c] = f.variance;
    }
    let light_var = srbf_deviation(bandwidth) * srbf_deviation(bandwidth);
    let direct_azimuth = half_share(bandwidth / cos_j, delta) / PI;
    let theta_d = 0.5 * (theta_o - theta_j);
    var back: array<Averages, 3>;
    for (var c = 0u; c < 3u; c++) {
        back[c] = back_at_coordinate(theta_d, fiber.absorption[c]);
    }
    let sigma_light = sqrt(light_var);
    var out = vec3<f32>(0.0);
    if (passes(t)) {
        out = t * params.d_b * local_term(back, theta_o, theta_j, sigma_light, direct_azimuth)
            / spread_at(theta_j, sigma_light);
    }
    if (max(scattered.x, max(scattered.y, scattered.z)) > NEGLIGIBLE) {
        let weight = scattered.x + scattered.y + scattered.z;
        let spread = dot(fw_variance, scattered) / weight;
        let sigma_f = sqrt(light_var + spread);
        let scattered_azimuth = (PI - abs(delta)) / (PI * PI);
        out += scattered
            * (global_term(theta_o, theta_j, sigma_f, delta)
                + params.d_b * local_term(back, theta_o, theta_j, sigma_f, scattered_azimuth))
            / spread_at(theta_j, sigma_f);
    }
    return energy * out;
}

// Dual::global (a WGSL-safe name): Σ_t ∫ g^u(θ_i; θ_j, σ_f) ½M_t (cos²θ_i/cos²θ_d) 𝒩^G_t dθ_i (eq. 27 without 1/Z).
fn global_term(theta_o: f32, theta_j: f32, sigma_f: f32, delta: f32) -> vec3<f32> {
    var it: Integrand;
    it.delta = delta;
    it.half_w = half_cosines(delta);
    let o = outgoing(theta_o);
    var sum = vec3<f32>(0.0);
    for (var lobe = LOBE_R; lobe <= LOBE_TRT; lobe++) {
        let ab = longitudinal(lobe);
        let window = window_normal_product(theta_j, sigma_f, 2.0 * ab.x - theta_o, 2.0 * ab.y);
        it.kind = KIND_GLOBAL_R + lobe;
        sum += integrate_incident(window, params.m, o, it);
    }
    return sum;
}

// The TT integrand of Dual::global: each channel's pair of Gaussians at π ± δ over the half
// circle.
fn global_tt(tt: TtLobes, delta: f32) -> vec3<f32> {
    var out = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        out[c] = tt.weight[c] * (unit_half(tt.bandwidth[c], delta - PI - tt.offset[c])
            + unit_half(tt.bandwidth[c], delta - PI + tt.offset[c]));
    }
    return out;
}

// The TRT integrand of Dual::global: each channel's slots over the half circle.
fn global_trt(trt_in: TrtLobes, delta: f32) -> vec3<f32> {
    var trt = trt_in;
    var out = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        for (var s = 0u; s < 3u; s++) {
            let w = trt.weight[c][s];
            if (w != 0.0) {
                out[c] += w * unit_half(trt.bandwidth[c][s], delta - trt.centre[s]);
            }
        }
    }
    return out;
}

// Dual::unit_half: (1/π) ∫ over the half circle around `offset` = δ − μ of g^c(φ; μ, λ).
fn unit_half(bandwidth: f32, offset: f32) -> f32 {
    return cg_integral(bandwidth) * half_share(bandwidth, offset) / PI;
}

// Dual::local (a WGSL-safe name): per channel Ā_b 𝒩^L ∫ g^u(θ_i; θ_j, σ) ½M_b (cos²θ_i/cos²θ_d) dθ_i (eq. 29
// without 1/Z).
fn local_term(back_in: array<Averages, 3>, theta_o: f32, theta_j: f32, sigma: f32, azimuth: f32) -> vec3<f32> {
    if (azimuth <= 0.0) {
        return vec3<f32>(0.0);
    }
    var back = back_in;
    let o = outgoing(theta_o);
    var it: Integrand;
    it.kind = KIND_ONE;
    var out = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        let a = back[c];
        if (a.back > 0.0) {
            let window = window_normal_product(theta_j, sigma, 2.0 * a.back_shift - theta_o, 2.0 * a.back_width);
            out[c] = BACK_SCALE * a.back * azimuth * integrate_incident(window, params.m, o, it).x;
        }
    }
    return out;
}

// 𝒩^G_R = (1/π) Σ_k C_k W_k(δ) (eqs. 13, 28).
fn r_half(theta_d: f32, w_in: array<f32, 7>) -> f32 {
    var w = w_in;
    var c = r_coefficients(params.eta, theta_d);
    var sum = 0.0;
    for (var k = 1u; k < 7u; k++) {
        sum += c[k] * w[k];
    }
    return sum / PI;
}
