// srbf/single_scattering.rs in f32: single scattering under SRBF lights (Xu et al. 2011 §4.2),
// ℳ_t = ∫ g_j(θ_i) ½M_t(θ_h) (cos²θ_i/cos²θ_d) 𝒩_t(λ′_j, φ_o − φ_j, θ_d) dθ_i (eq. 11).

// What one quadrature integrand reads (the CPU's closures): its kind, the light's bandwidth
// and cos θ_j, the azimuth offsets of eqs. 12 and 26, and W_k(δ) for dual scattering's R.
struct Integrand {
    kind: u32,
    bandwidth: f32,
    cos_j: f32,
    delta: f32,
    cos_delta: f32,
    sin_delta: f32,
    phi_sum: f32,
    half_w: array<f32, 7>,
}

const KIND_R: u32 = LOBE_R;
const KIND_TT: u32 = LOBE_TT;
const KIND_TRT: u32 = LOBE_TRT;
const KIND_GLOBAL_R: u32 = 3u;
const KIND_GLOBAL_TT: u32 = 4u;
const KIND_GLOBAL_TRT: u32 = 5u;
const KIND_ONE: u32 = 6u;

fn integrand(it: Integrand, s: Incident) -> vec3<f32> {
    switch it.kind {
        case 0u, 1u, 2u: {
            let lambda = it.bandwidth / sqrt(s.cos_i * it.cos_j);
            if (it.kind == KIND_R) {
                return vec3<f32>(r_convolved(params.eta, s.theta_d, lambda, it.delta));
            }
            if (it.kind == KIND_TT) {
                return tt_convolved(tt_lobes(s.theta_d), sharpness(lambda), it);
            }
            let eta = mean_eta_star(lambda, it.phi_sum);
            return trt_convolved(trt_lobes(eta, s.theta_d), sharpness(lambda), it);
        }
        case 3u: {
            return vec3<f32>(r_half(s.theta_d, it.half_w));
        }
        case 4u: {
            return global_tt(tt_lobes(s.theta_d), it.delta);
        }
        case 5u: {
            // At the fiber's own η the TRT fit is the lobe table's, eccentric or not (the CPU
            // fits it on the spot there; the table holds the same fit).
            return global_trt(trt_table(s.theta_d), it.delta);
        }
        default: {
            return vec3<f32>(1.0);
        }
    }
}

// (α_p, β_p) of M_R, M_TT, M_TRT (Marschner 2003 Table 1).
fn longitudinal(lobe: u32) -> vec2<f32> {
    let a = params.alpha_r;
    let b = params.beta_r;
    switch lobe {
        case LOBE_R: {
            return vec2<f32>(a, b);
        }
        case LOBE_TT: {
            return vec2<f32>(-0.5 * a, 0.5 * b);
        }
        default: {
            return vec2<f32>(-1.5 * a, 2.0 * b);
        }
    }
}

// Σ_t ℳ_t of one light (eq. 11) over the lobes on in `lobes` (bit t: lobe t; the CPU's scene
// Lobes, params.lobes).
fn modes(theta_o: f32, phi_o: f32, theta_j: f32, phi_j: f32, bandwidth: f32, lobes: u32) -> vec3<f32> {
    let delta = phi_o - phi_j;
    var it: Integrand;
    it.bandwidth = bandwidth;
    it.cos_j = max(cos(theta_j), 1e-4);
    it.delta = delta;
    it.cos_delta = cos(delta);
    it.sin_delta = sin(delta);
    it.phi_sum = phi_o + phi_j;
    let o = outgoing(theta_o);
    var sum = vec3<f32>(0.0);
    for (var lobe = LOBE_R; lobe <= LOBE_TRT; lobe++) {
        if ((lobes & (1u << lobe)) == 0u) {
            continue;
        }
        let ab = longitudinal(lobe);
        let window = window_product(theta_j, bandwidth, 2.0 * ab.x - theta_o, 2.0 * ab.y);
        it.kind = KIND_R + lobe;
        sum += integrate_incident(window, params.m, o, it);
    }
    return sum;
}

// 𝒩_TT (eq. 12 with 16): each channel's pair of Gaussians at π ± δ against the light's of
// sharpness κ₁, cos(Δ − π ∓ δ) = −(cos Δ cos δ ± sin Δ sin δ).
fn tt_convolved(tt: TtLobes, k1: f32, it: Integrand) -> vec3<f32> {
    var out = vec3<f32>(0.0);
    for (var ch = 0u; ch < 3u; ch++) {
        if (tt.weight[ch] != 0.0) {
            let k2 = sharpness(tt.bandwidth[ch]);
            let a = it.cos_delta * cos(tt.offset[ch]);
            let b = it.sin_delta * sin(tt.offset[ch]);
            out[ch] = tt.weight[ch] * (convolve_sharp(k1, k2, -(a + b)) + convolve_sharp(k1, k2, -(a - b)));
        }
    }
    return out;
}

// 𝒩_TRT (eq. 12 with 20 and 25): the three slots of each channel.
fn trt_convolved(trt_in: TrtLobes, k1: f32, it: Integrand) -> vec3<f32> {
    var trt = trt_in;
    let sin_star = sin(trt.centre.x);
    let cos_star = cos(trt.centre.x);
    let a = it.cos_delta * cos_star;
    let b = it.sin_delta * sin_star;
    let cosines = vec3<f32>(a + b, a - b, it.cos_delta);
    var out = vec3<f32>(0.0);
    for (var ch = 0u; ch < 3u; ch++) {
        for (var s = 0u; s < 3u; s++) {
            let w = trt.weight[ch][s];
            if (w != 0.0) {
                out[ch] += w * convolve_sharp(k1, sharpness(trt.bandwidth[ch][s]), cosines[s]);
            }
        }
    }
    return out;
}

// η̄* (eq. 26): η* of eq. 24 averaged over the light's azimuthal Gaussian.
fn mean_eta_star(lambda: f32, phi_sum: f32) -> f32 {
    let a = params.eccentricity;
    if (a == 1.0) {
        return params.eta;
    }
    let eta = params.eta;
    let eta1 = 2.0 * (eta - 1.0) * a * a - eta + 2.0;
    let eta2 = 2.0 * (eta - 1.0) / (a * a) - eta + 2.0;
    let g = params.grids[GRID_COSINE];
    let mean_cos = static_at(GRID_COSINE, cell_x(g, log(clamp(lambda, 0.001, 10.0))), cell_y(g, abs(wrap_pi(phi_sum))), 2u);
    let cos2 = 2.0 * mean_cos - 1.0;
    return max(0.5 * ((eta1 + eta2) + cos2 * (eta1 - eta2)), 1.0 + 1e-6);
}
