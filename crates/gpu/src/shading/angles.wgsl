// angles.rs, fresnel.rs and the fiber crate's frame and Bravais geometry, in f32.

// Wraps an angle to (−π, π].
fn wrap_pi(x: f32) -> f32 {
    let y = x - 2.0 * PI * floor((x + PI) / (2.0 * PI));
    if (y <= -PI) {
        return y + 2.0 * PI;
    }
    if (y > PI) {
        return y - 2.0 * PI;
    }
    return y;
}

// An orthonormal fiber frame: tangent u, normal-plane axes v, w (docs/conventions.md §2).
struct Frame {
    u: vec3<f32>,
    v: vec3<f32>,
    w: vec3<f32>,
}

// glam's any_orthonormal_vector (Duff et al. 2017's branchless basis).
fn any_orthonormal(n: vec3<f32>) -> vec3<f32> {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    return vec3<f32>(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
}

// FiberFrame::from_tangent: v is the part of `toward` normal to u.
fn frame_from_tangent(tangent: vec3<f32>, toward: vec3<f32>) -> Frame {
    let u = normalize(tangent);
    let normal = toward - u * dot(u, toward);
    var v: vec3<f32>;
    if (dot(normal, normal) > 1e-24) {
        v = normalize(normal);
    } else {
        v = any_orthonormal(u);
    }
    return Frame(u, v, cross(u, v));
}

// frame_fibers.rs's frame_at: the tangent, or +z for a zero-length one.
fn frame_at(tangent: vec3<f32>, position: vec3<f32>) -> Frame {
    var t = tangent;
    if (dot(t, t) <= 1e-20) {
        t = vec3<f32>(0.0, 0.0, 1.0);
    }
    return frame_from_tangent(t, position);
}

// θ and φ of a unit direction in the fiber frame.
struct Angles {
    theta: f32,
    phi: f32,
}

fn angles(f: Frame, d: vec3<f32>) -> Angles {
    return Angles(asin(clamp(dot(d, f.u), -1.0, 1.0)), atan2(dot(d, f.w), dot(d, f.v)));
}

// A viewing inclination θ_o with its sine and cosine (angles.rs's Outgoing).
struct Outgoing {
    theta: f32,
    sin_o: f32,
    cos_o: f32,
}

fn outgoing(theta: f32) -> Outgoing {
    return Outgoing(theta, sin(theta), cos(theta));
}

// One incident sample θ_i seen from θ_o (angles.rs's Incident).
struct Incident {
    cos_i: f32,
    theta_d: f32,
    cos2_d: f32,
}

fn incident(o: Outgoing, theta_i: f32) -> Incident {
    let sin_i = sin(theta_i);
    let cos_i = cos(theta_i);
    return Incident(cos_i, 0.5 * (o.theta - theta_i), 0.5 * (1.0 + o.cos_o * cos_i + o.sin_o * sin_i));
}

fn smoothstep_ab(a: f32, b: f32, x: f32) -> f32 {
    let s = clamp((x - a) / (b - a), 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
}

// η′ = √(η² − sin²θ)/cos θ (Bravais; Xu et al. 2011 Table 1).
fn eta_prime(eta: f32, theta: f32) -> f32 {
    let s = sin(theta);
    return sqrt(max(eta * eta - s * s, 0.0)) / max(abs(cos(theta)), 1e-12);
}

// η″ = η² cos θ / √(η² − sin²θ).
fn eta_double_prime(eta: f32, theta: f32) -> f32 {
    let s = sin(theta);
    return eta * eta * abs(cos(theta)) / sqrt(max(eta * eta - s * s, 1e-30));
}

// cos θ_t of the refracted inclination, sin θ_t = sin θ / η.
fn cos_theta_t(eta: f32, theta: f32) -> f32 {
    let s = sin(theta) / eta;
    return sqrt(max(1.0 - s * s, 0.0));
}

// Φ(p, h) = 2p asin(h/η′) − 2 asin h + pπ (Xu et al. 2011 eq. 8).
fn deflection(p: f32, h: f32, ep: f32) -> f32 {
    let gamma_i = asin(clamp(h, -1.0, 1.0));
    let gamma_t = asin(clamp(h / ep, -1.0, 1.0));
    return 2.0 * p * gamma_t - 2.0 * gamma_i + p * PI;
}

// dΦ/dh = 2p/√(η′² − h²) − 2/√(1 − h²).
fn deflection_slope(p: f32, h: f32, ep: f32) -> f32 {
    return 2.0 * p / sqrt(max(ep * ep - h * h, 1e-30)) - 2.0 / sqrt(max(1.0 - h * h, 1e-30));
}

// |r|² of one polarisation (perpendicular when `perp`) at incidence γ onto index η.
fn polarised_reflectance(eta: f32, gamma: f32, perp: bool) -> f32 {
    let cos_i = abs(cos(gamma));
    let sin_t = sin(gamma) / eta;
    if (abs(sin_t) >= 1.0) {
        return 1.0;
    }
    let cos_t = sqrt(1.0 - sin_t * sin_t);
    var r: f32;
    if (perp) {
        r = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    } else {
        r = (cos_t - eta * cos_i) / (cos_t + eta * cos_i);
    }
    return r * r;
}

// F(η, θ_d, h): Marschner 2003's oblique factor with Bravais' indices (Xu et al. 2011 eq. 10).
fn oblique(eta: f32, theta_d: f32, h: f32) -> f32 {
    let gamma = asin(clamp(h, -1.0, 1.0));
    return 0.5 * (polarised_reflectance(eta_prime(eta, theta_d), gamma, true)
        + polarised_reflectance(eta_double_prime(eta, theta_d), gamma, false));
}

