// srbf/quadrature.rs in f32: the product integral of a 1D Gaussian window with a smooth
// function by piecewise-linear quadrature (Xu et al. 2011 §4.2.2). The integrand, a closure on
// the CPU, is an `Integrand` here, evaluated by `integrand` (single_scattering.wgsl).

const MAX_SEGMENTS: u32 = 256u;
const NEGLIGIBLE_SCALE: f32 = 1e-12;

// scale · exp(−(x − μ)²/(2σ²)).
struct Window {
    scale: f32,
    mu: f32,
    sigma: f32,
}

// Window::product: an SRBF's exp(−(x − θ_j)²/λ²) (Xu et al. 2011 eq. 11) times the unit normal
// density of mean `mean`, deviation `dev`.
fn window_product(theta_j: f32, lambda: f32, mean: f32, dev: f32) -> Window {
    let va = 0.5 * lambda * lambda;
    let vb = dev * dev;
    let d = theta_j - mean;
    return Window(
        exp(-d * d / (2.0 * (va + vb))) / (dev * sqrt(2.0 * PI)),
        (theta_j * vb + mean * va) / (va + vb),
        sqrt(va * vb / (va + vb)),
    );
}

// Window::normal_product: N(x; a, μ_a) N(x; b, σ_b).
fn window_normal_product(a: f32, dev_a: f32, b: f32, dev_b: f32) -> Window {
    let va = dev_a * dev_a;
    let vb = dev_b * dev_b;
    let s = va + vb;
    return Window(
        exp(-(a - b) * (a - b) / (2.0 * s)) / sqrt(2.0 * PI * s) / sqrt(2.0 * PI * va * vb / s),
        (a * vb + b * va) / s,
        sqrt(va * vb / s),
    );
}

// A segment end in the window's variable u = (x − μ)/(√2 σ).
struct Edge {
    x: f32,
    u: f32,
    erfc_abs: f32,
    gauss: f32,
}

// erfc(x), x ≥ 0, given e^{−x²}: Abramowitz & Stegun 7.1.26.
fn erfc_from_gauss(x: f32, gauss: f32) -> f32 {
    let t = 1.0 / (1.0 + 0.3275911 * x);
    return t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429)))) * gauss;
}

fn edge(w: Window, x: f32) -> Edge {
    let u = (x - w.mu) / (SQRT_2 * w.sigma);
    var gauss = 0.0;
    if (u * u < 729.0) {
        gauss = exp(-u * u);
    }
    return Edge(x, u, erfc_from_gauss(abs(u), gauss), gauss);
}

// erf(u1) − erf(u0) without cancellation in the tails.
fn erf_difference(a: Edge, b: Edge) -> f32 {
    if (a.u >= 0.0) {
        return a.erfc_abs - b.erfc_abs;
    }
    if (b.u <= 0.0) {
        return b.erfc_abs - a.erfc_abs;
    }
    return 2.0 - b.erfc_abs - a.erfc_abs;
}

// ∫ over [a.x, b.x] of the window times the line through (a.x, f0) and (b.x, f1).
fn segment(w: Window, a: Edge, b: Edge, f0: vec3<f32>, f1: vec3<f32>) -> vec3<f32> {
    let i0 = w.sigma * sqrt(PI / 2.0) * erf_difference(a, b);
    let i1 = w.sigma * w.sigma * (a.gauss - b.gauss);
    let slope = (f1 - f0) / (b.x - a.x);
    return w.scale * (f0 * i0 + slope * (i1 + (w.mu - a.x) * i0));
}

// Window::nodes: the ends ±π/2 and m − 1 points spread uniformly over μ ± (m − 2)λ/2, the
// span clipped to [−π/2, π/2].
struct Nodes {
    m: u32,
    lo: f32,
    hi: f32,
}

fn nodes(w: Window, m_in: u32) -> Nodes {
    let m = clamp(m_in, 2u, MAX_SEGMENTS);
    let half = f32(m - 2u) * 0.5 * SQRT_2 * w.sigma;
    return Nodes(m, clamp(w.mu - half, -HALF_PI, HALF_PI), clamp(w.mu + half, -HALF_PI, HALF_PI));
}

fn node_at(n: Nodes, s: u32) -> f32 {
    if (s == 0u) {
        return -HALF_PI;
    }
    if (s >= n.m) {
        return HALF_PI;
    }
    if (n.m == 2u) {
        return n.lo;
    }
    return n.lo + (n.hi - n.lo) * f32(s - 1u) / f32(n.m - 2u);
}

// Window::integrate_incident: ∫ window · n(θ_i) cos²θ_i / cos²θ_d dθ_i, zero for a negligible
// window and at grazing samples (cos θ_i ≤ 1e-6); n is not evaluated at the ends ±π/2.
fn integrate_incident(w: Window, m: u32, o: Outgoing, it: Integrand) -> vec3<f32> {
    if (w.scale < NEGLIGIBLE_SCALE) {
        return vec3<f32>(0.0);
    }
    let n = nodes(w, m);
    var left = edge(w, node_at(n, 0u));
    var prev = vec3<f32>(0.0);
    var sum = vec3<f32>(0.0);
    for (var s = 1u; s <= n.m; s++) {
        let xs = node_at(n, s);
        var value = vec3<f32>(0.0);
        if (s != n.m) {
            let inc = incident(o, xs);
            if (inc.cos_i > 1e-6) {
                value = integrand(it, inc) * (inc.cos_i * inc.cos_i / inc.cos2_d);
            }
        }
        let right = edge(w, xs);
        if (right.x > left.x) {
            sum += segment(w, left, right, prev, value);
        }
        left = right;
        prev = value;
    }
    return sum;
}
