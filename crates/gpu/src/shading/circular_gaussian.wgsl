// srbf/circular_gaussian.rs in f32: circular Gaussians g^c(x; μ, λ) = exp(2(cos(x − μ) − 1)/λ²)
// (Xu et al. 2011 Table 1), their integrals and the closed form of a product of two.

// Abramowitz & Stegun 9.8.1 in t = (x/3.75)², x ≤ 3.75: I₀(x).
fn i0_small(x: f32) -> f32 {
    let t = (x / 3.75) * (x / 3.75);
    return 1.0 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813)))));
}

// Abramowitz & Stegun 9.8.2 in t = 3.75/x, x > 3.75: I₀(x) = e^x q / √x.
fn i0_large(x: f32) -> f32 {
    let t = 3.75 / x;
    return 0.39894228 + t * (0.01328592 + t * (0.00225319 + t * (-0.00157565 + t * (0.00916281
        + t * (-0.02057706 + t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))));
}

const I0_SWITCH: f32 = 3.75;

// I₀(κ) e^{s}, s ≤ 0, κ + s ≤ 0; above the switch e^{κ+s} is formed from `excess` = κ + s,
// which callers compute without cancellation.
fn i0_times_exp(kappa: f32, s: f32, excess: f32) -> f32 {
    if (kappa <= I0_SWITCH) {
        return i0_small(kappa) * exp(s);
    }
    return i0_large(kappa) / sqrt(kappa) * exp(excess);
}

// κ = 2/λ².
fn sharpness(lambda: f32) -> f32 {
    return 2.0 / (lambda * lambda);
}

// g^c(x; μ, λ).
fn cg_eval(x: f32, mu: f32, lambda: f32) -> f32 {
    return exp(sharpness(lambda) * (cos(x - mu) - 1.0));
}

// ∫_{−π}^{π} g^c(x; μ, λ) dx = 2π e^{−κ} I₀(κ).
fn cg_integral(lambda: f32) -> f32 {
    let kappa = sharpness(lambda);
    return 2.0 * PI * i0_times_exp(kappa, -kappa, 0.0);
}

// convolve_sharp: ∫ g^c(x; 0, λ₁) g^c(δ − x; μ₂, λ₂) dx from κ₁, κ₂ and c = cos(δ − μ₂):
// κ = |κ₁ + κ₂ e^{i(δ − μ₂)}|, and κ − κ₁ − κ₂ = 2κ₁κ₂(c − 1)/(κ + κ₁ + κ₂), the same number
// without the difference of large sharpnesses that f32 would lose.
fn convolve_sharp(k1: f32, k2: f32, c: f32) -> f32 {
    let kappa = sqrt(max(k1 * k1 + k2 * k2 + 2.0 * k1 * k2 * c, 0.0));
    let excess = 2.0 * k1 * k2 * (min(c, 1.0) - 1.0) / max(kappa + k1 + k2, 1e-30);
    return 2.0 * PI * i0_times_exp(kappa, -k1 - k2, excess);
}

// bandwidth_for_integral: the λ whose circular Gaussian integrates to `area`, from the width
// correction table over ln(area/√π).
fn bandwidth_for_integral(area: f32) -> f32 {
    let naive = area / sqrt(PI);
    let g = params.grids[GRID_WIDTH];
    if (naive <= exp(g.x0)) {
        return naive;
    }
    if (area >= 2.0 * PI * 0.99995) {
        return 20.0;
    }
    return naive * static_lookup(GRID_WIDTH, log(naive), 0.0, 0u);
}
