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

// How one light's energy arrives at a point (Dual::arrival's Arrival).
struct Arrival {
    direct: bool,
    scattered: vec3<f32>,
    variance: vec3<f32>,
}

// Dual::arrival: whether light of transmittance `t` from elevation `theta_j` arrives directly,
// and each channel's forward-scattered share.
fn arrival(theta_j: f32, t: f32) -> Arrival {
    var a: Arrival;
    a.direct = passes(t);
    for (var c = 0u; c < 3u; c++) {
        let f = forward(t, back_at_coordinate(theta_j, fiber.absorption[c]));
        a.scattered[c] = f.scattered;
        a.variance[c] = f.variance;
    }
    return a;
}

fn forward_scattered(a: Arrival) -> bool {
    return max(a.scattered.x, max(a.scattered.y, a.scattered.z)) > NEGLIGIBLE;
}

// Each channel's back-scattering averages at the θ_d of a light at `theta_j` (Dual::back_at; back_at is the table read).
fn back_for_light(theta_o: f32, theta_j: f32) -> array<Averages, 3> {
    let theta_d = 0.5 * (theta_o - theta_j);
    var back: array<Averages, 3>;
    for (var c = 0u; c < 3u; c++) {
        back[c] = back_at_coordinate(theta_d, fiber.absorption[c]);
    }
    return back;
}

// Where a light's (or a merged group's) energy comes from, in the fiber frame (Beam).
struct Beam {
    theta: f32,
    phi: f32,
    bandwidth: f32,
}

// Dual::direct: share · d_b ℳ^L / Z of the direct light from a beam of unit energy (eq. 29).
fn dual_direct(theta_o: f32, phi_o: f32, at: Beam, share: f32) -> vec3<f32> {
    let delta = wrap_pi(phi_o - at.phi);
    let back = back_for_light(theta_o, at.theta);
    let cos_j = max(cos(at.theta), 1e-4);
    let direct_azimuth = half_share(at.bandwidth / cos_j, delta) / PI;
    let sigma_light = srbf_deviation(at.bandwidth);
    return share * params.d_b * local_term(back, theta_o, at.theta, sigma_light, direct_azimuth)
        / spread_at(at.theta, sigma_light);
}

// Dual::scattered: share · (ℳ^G + d_b ℳ^L) / Z of forward-scattered light from a beam of unit
// energy whose crossings add the longitudinal variance `spread` (eqs. 27–29).
fn dual_scattered(theta_o: f32, phi_o: f32, at: Beam, share: vec3<f32>, spread: f32) -> vec3<f32> {
    let delta = wrap_pi(phi_o - at.phi);
    let back = back_for_light(theta_o, at.theta);
    let sigma_f = sqrt(srbf_deviation(at.bandwidth) * srbf_deviation(at.bandwidth) + spread);
    let scattered_azimuth = (PI - abs(delta)) / (PI * PI);
    return share
        * (global_term(theta_o, at.theta, sigma_f, delta)
            + params.d_b * local_term(back, theta_o, at.theta, sigma_f, scattered_azimuth))
        / spread_at(at.theta, sigma_f);
}

// Dual::light: one light's global and local terms; `radiance` unshadowed, `t` its T̃.
fn dual_light(theta_o: f32, phi_o: f32, theta_j: f32, phi_j: f32, bandwidth: f32, radiance: vec3<f32>, t: f32) -> vec3<f32> {
    let energy = radiance * srbf_integral(bandwidth);
    if (max(energy.x, max(energy.y, energy.z)) <= 0.0) {
        return vec3<f32>(0.0);
    }
    let a = arrival(theta_j, t);
    let at = Beam(theta_j, phi_j, bandwidth);
    var out = vec3<f32>(0.0);
    if (a.direct) {
        out = dual_direct(theta_o, phi_o, at, t);
    }
    if (forward_scattered(a)) {
        let spread = dot(a.variance, a.scattered) / (a.scattered.x + a.scattered.y + a.scattered.z);
        out += dual_scattered(theta_o, phi_o, at, a.scattered, spread);
    }
    return energy * out;
}

// Energies and mean vector of lights being merged into one beam (Merge).
struct Merge {
    energy: vec3<f32>,
    moment: vec3<f32>,
    weight: f32,
}

// Merge::add.
fn merge_add(m: ptr<function, Merge>, energy: vec3<f32>, mean: vec3<f32>) {
    let w = abs(energy.x) + abs(energy.y) + abs(energy.z);
    (*m).energy += energy;
    (*m).moment += w * mean;
    (*m).weight += w;
}

// Whether Merge::beam gives a beam: some energy and a mean vector.
fn merge_has_beam(m: Merge) -> bool {
    return m.weight > 0.0 && any(m.moment != vec3<f32>(0.0));
}

// Merge::beam: the SRBF of the mean vector, centre m/‖m‖ and sharpness A⁻¹(‖m‖/Σw).
fn merge_beam(m: Merge) -> Beam {
    let mean = m.moment / m.weight;
    let r = length(mean);
    let d = mean / r;
    let kappa = vmf_concentration(r);
    return Beam(asin(clamp(d.x, -1.0, 1.0)), atan2(d.z, d.y), clamp(sqrt(2.0 / kappa), MIN_BEAM, MAX_BEAM));
}

// dual_scattering.rs's MIN_BEAM and MAX_BEAM (cuticle-light's bandwidth range).
const MIN_BEAM: f32 = 1e-4;
const MAX_BEAM: f32 = 4.0;

// cuticle_fiber::math::vmf::mean_cosine: A(κ) = coth κ − 1/κ.
fn vmf_mean_cosine(kappa: f32) -> f32 {
    if (kappa < 1e-4) {
        return kappa / 3.0;
    }
    if (kappa > 20.0) {
        return 1.0 - 1.0 / kappa;
    }
    return 1.0 / tanh(kappa) - 1.0 / kappa;
}

// cuticle_fiber::math::vmf's dA/dκ = 1/κ² − 1/sinh²κ.
fn vmf_mean_cosine_slope(kappa: f32) -> f32 {
    if (kappa < 1e-2) {
        return 1.0 / 3.0 - kappa * kappa / 15.0;
    }
    if (kappa > 20.0) {
        return 1.0 / (kappa * kappa);
    }
    let s = sinh(kappa);
    return 1.0 / (kappa * kappa) - 1.0 / (s * s);
}

// cuticle_fiber::math::vmf::concentration: A⁻¹(r) by Banerjee et al. 2005's estimate and
// Newton steps (r kept below 1 − 1e-6, f32's resolution there).
fn vmf_concentration(r_in: f32) -> f32 {
    let r = clamp(r_in, 1e-6, 1.0 - 1e-6);
    var kappa = r * (3.0 - r * r) / (1.0 - r * r);
    for (var i = 0u; i < 8u; i++) {
        let step = (vmf_mean_cosine(kappa) - r) / vmf_mean_cosine_slope(kappa);
        kappa = max(kappa - step, 0.5 * kappa);
        if (abs(step) < 1e-6 * kappa) {
            break;
        }
    }
    return kappa;
}

// Dual::group: lights first … end − 1 of point k merged into a direct beam and a
// forward-scattered one, each shaded once (Dual::shade_clustered).
fn dual_group(f: Frame, theta_o: f32, phi_o: f32, k: u32, first: u32, end: u32) -> vec3<f32> {
    var direct: Merge;
    var scattered: Merge;
    // Each light's spread weighted by its energy (Dual::group).
    var spread = 0.0;
    var spread_weight = 0.0;
    for (var j = first; j < end; j++) {
        let light = lights[j];
        let t = shadow[k * params.lights + j];
        let energy = light.radiance * srbf_integral(light.bandwidth);
        if (max(energy.x, max(energy.y, energy.z)) <= 0.0) {
            continue;
        }
        let d = vec3<f32>(dot(light.direction, f.u), dot(light.direction, f.v), dot(light.direction, f.w));
        let a = arrival(asin(clamp(d.x, -1.0, 1.0)), t);
        let mean = vmf_mean_cosine(sharpness(light.bandwidth)) * d;
        if (a.direct) {
            merge_add(&direct, t * energy, mean);
        }
        if (forward_scattered(a)) {
            merge_add(&scattered, energy * a.scattered, mean);
            let w = abs(energy.x) + abs(energy.y) + abs(energy.z);
            spread += w * dot(a.variance, a.scattered);
            spread_weight += w * (a.scattered.x + a.scattered.y + a.scattered.z);
        }
    }
    var out = vec3<f32>(0.0);
    if (merge_has_beam(direct)) {
        out += direct.energy * dual_direct(theta_o, phi_o, merge_beam(direct), 1.0);
    }
    if (merge_has_beam(scattered)) {
        out += dual_scattered(theta_o, phi_o, merge_beam(scattered), scattered.energy, spread / spread_weight);
    }
    return out;
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
